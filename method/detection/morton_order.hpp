#pragma once
/// Orders along a Morton (Z-order) curve, for memory layouts that stream:
/// elements near each other in space get numbers near each other, so a
/// walk over them, or a bucket listing several, reads few cache lines.
/// A layout only: nothing here decides geometry.
///
/// The key itself (sim/mesh/morton_key.hpp) is shared with the vertex
/// renumbering at load (sim/mesh/curve_numbering.hpp).

#include <cstdint>
#include <vector>

#include "sim/mesh/morton_key.hpp"
#include "sim/mesh/tet_mesh.hpp"

namespace tcb {

/// The tets ordered by their centroids' Morton keys within the box of the
/// positions x: order[r] is the tet of rank r; equal keys keep index order
/// (a stable sort), so the order is a function of x and tets alone. Every
/// tet's vertices must index x.
std::vector<std::uint32_t> morton_tet_order(const std::vector<Vec3>& x, const std::vector<Tet>& tets);

}  // namespace tcb
