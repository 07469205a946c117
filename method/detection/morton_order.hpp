#pragma once
/// Orders along a Morton (Z-order) curve, for memory layouts that stream:
/// elements near each other in space get numbers near each other, so a
/// walk over them, or a bucket listing several, reads few cache lines.
/// A layout only: nothing here decides geometry.
///
/// Contract: morton_key() scales each coordinate of p into [lo, hi] to 21
/// bits (floor of t * (2^21 - 1), t = (p - lo) / (hi - lo) clamped to
/// [0, 1]; an empty or inverted extent counts as 1e-300 m, a NaN as 0) and
/// interleaves them, x in the lowest bit: equal points get equal keys, and
/// any input, infinities and NaN included, gives some key (no undefined
/// conversion). Units: any, as long as p, lo and hi share them.

#include <cstdint>
#include <vector>

#include "sim/mesh/tet_mesh.hpp"

namespace tcb {

/// The Morton key of p within the box [lo, hi] (file comment).
std::uint64_t morton_key(const Vec3& p, const Vec3& lo, const Vec3& hi);

/// The tets ordered by their centroids' Morton keys within the box of the
/// positions x: order[r] is the tet of rank r; equal keys keep index order
/// (a stable sort), so the order is a function of x and tets alone. Every
/// tet's vertices must index x.
std::vector<std::uint32_t> morton_tet_order(const std::vector<Vec3>& x, const std::vector<Tet>& tets);

}  // namespace tcb
