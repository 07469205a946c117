#pragma once
/// Splits hexahedra into tetrahedra so that neighbouring hexes stay conforming.
///
/// Rule (a "pulling" triangulation on the global vertex order): each hex is
/// coned from its vertex with the smallest global index v to the three quads
/// that do not contain v; each of those quads is cut along the diagonal through
/// its own smallest-index vertex. A quad shared by two hexes is cut the same
/// way from both sides (the rule depends only on the quad's indices), so the
/// result is conforming; the three quads through v are cut through v, which is
/// their smallest index too. Always 6 tets per hex.
///
/// Vertex order of a hex (MEDIT): 0-1-2-3 one face, 4-5-6-7 the opposite face,
/// vertex 4+k joined to vertex k. Tets are emitted positively oriented when the
/// hex follows the convention that 0-1-2-3 seen from 4-5-6-7 turns counterclockwise
/// (so face 4-5-6-7 winds outward); a hex of the other handedness yields
/// negatively oriented tets, which build_tet_mesh repairs and counts as inverted.

#include <array>
#include <cstdint>
#include <vector>

#include "sim/mesh/tet_mesh.hpp"

namespace tcb {

using Hex = std::array<std::int32_t, 8>;

std::vector<Tet> split_hexahedra(const std::vector<Hex>& hexes);

}  // namespace tcb
