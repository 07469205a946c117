#pragma once
/// Structured tet mesh of an axis-aligned box, centred on the origin.
///
/// Each of the nx*ny*nz cells is split into the 6 tets of the Kuhn
/// (Freudenthal) subdivision around its (0,0,0)->(1,1,1) diagonal; all cells
/// use the same diagonal directions, so the mesh is conforming. Vertex
/// coordinates are lo + (hi - lo) * i / n with the end points exactly lo and
/// hi = size/2, so opposite faces are exactly planar and boxes built with the
/// same size can be stacked face on face without rounding gaps. All tets are
/// positively oriented. Units: metres.

#include <string>

#include "sim/mesh/tet_mesh.hpp"

namespace tcb {

/// `parts` (px, py, pz), each 1..n along its axis: the cells are grouped into
/// px*py*pz blocks, cell i along x going to part floor(i*px/nx) (likewise y,
/// z), part id (kz*py + ky)*px + kx; (1,1,1), the default, gives no parts.
TetMesh make_box_mesh(const Vec3& size_m, int nx, int ny, int nz, const std::array<int, 3>& parts = {1, 1, 1});

/// True when source names a generator rather than a file ("box:...").
bool is_generator_source(const std::string& source);

/// Builds a mesh from a generator string:
///   box:size=SXxSYxSZ,cells=NXxNYxNZ      e.g. "box:size=1x0.05x1,cells=10x1x10"
///   box:size=...,cells=...,parts=PXxPYxPZ  the same, its cells grouped into parts
/// Throws std::invalid_argument with a one-line reason when it is malformed.
/// The most tets a generated box may have (the cells' product x 6).
inline constexpr double kMaxGeneratedTets = 60.0e6;

TetMesh make_generated_mesh(const std::string& source);

}  // namespace tcb
