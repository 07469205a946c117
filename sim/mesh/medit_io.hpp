#pragma once
/// MEDIT `.mesh` files (ASCII, the format of INRIA's medit, Gmsh and CGAL).
///
/// Reading: `Dimension` must be 3; `Vertices` (x y z ref), `Tetrahedra`
/// (4 one-based indices + ref) and `Hexahedra` (8 indices + ref, split into
/// tets by split_hexahedra) are read. Element references become the tets'
/// parts (TetMesh::tet_part; the six tets of a hex share its reference),
/// unless every element has the same one: then the mesh has no parts. Every
/// other section (Triangles, Edges,
/// Corners, ...) is skipped up to the next keyword. Counts, indices and
/// coordinates are checked: a malformed file throws InputError naming the file,
/// the line and the problem (NaN or infinite coordinates, indices out of range,
/// a section shorter than its count, a missing Vertices section, no elements).
/// Writing: Vertices, Tetrahedra (parts as references, else 0) and the
/// boundary Triangles, with the shortest
/// decimal form that reads back to the same double (lossless round trip).

#include <filesystem>

#include "sim/mesh/tet_mesh.hpp"

namespace tcb {

struct MeditReadStats {
  std::int64_t hexahedra = 0;  ///< hexes read (each became 6 tets)
};

TetMesh read_medit(const std::filesystem::path& path, MeditReadStats* stats = nullptr);
/// Parses MEDIT text; file_name is used in error messages only.
TetMesh parse_medit(const std::string& file_name, std::string text, MeditReadStats* stats = nullptr);

void write_medit(const std::filesystem::path& path, const TetMesh& mesh);

}  // namespace tcb
