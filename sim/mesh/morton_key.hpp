#pragma once
/// The Morton (Z-order) key of a point: points near each other in space get
/// keys near each other, so elements sorted by it are laid out along a
/// space-filling curve. Used for memory layouts only (the detector's tet
/// slots, method/detection/morton_order.hpp; a mesh's vertices renumbered at
/// load, sim/mesh/curve_numbering.hpp): nothing decides geometry by it.
///
/// Contract: morton_key() scales each coordinate of p into [lo, hi] to 21
/// bits (floor of t * (2^21 - 1), t = (p - lo) / (hi - lo) clamped to
/// [0, 1]; an empty or inverted extent counts as 1e-300 m, a NaN as 0) and
/// interleaves them, x in the lowest bit: equal points get equal keys, and
/// any input, infinities and NaN included, gives some key (no undefined
/// conversion). Units: any, as long as p, lo and hi share them.

#include <cstdint>
#include <utility>
#include <vector>

#include "sim/mesh/tet_mesh.hpp"

namespace tcb {

/// The Morton key of p within the box [lo, hi] (file comment).
std::uint64_t morton_key(const Vec3& p, const Vec3& lo, const Vec3& hi);

/// The points' indices in the order of their Morton keys within [lo, hi],
/// equal keys in index order (a stable sort): result[k] is the index of the
/// k-th point along the curve.
std::vector<std::uint32_t> along_curve(const std::vector<Vec3>& points, const Vec3& lo, const Vec3& hi);

/// The smallest box {lo, hi} holding every point, the box the layouts scale
/// keys in; points must not be empty.
std::pair<Vec3, Vec3> bounding_box(const std::vector<Vec3>& points);

}  // namespace tcb
