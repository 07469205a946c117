#pragma once
/// TetGen `.node` + `.ele` pairs (ASCII).
///
/// `.node`: header `<points> <dim=3> <attributes> <boundary marker 0|1>`, then
/// `<index> x y z [attributes...] [marker]`. `.ele`: header `<tets> <4|10>
/// <region attribute 0|1>`, then `<index> v0 v1 v2 v3 [more nodes] [region]`
/// (only the four corners of 10-node tets are used). Indices may start at 0
/// or 1: the first point's index decides, as in TetGen. `#` comments.
/// Errors are InputError with the file and line, as for MEDIT.

#include <filesystem>

#include "sim/mesh/tet_mesh.hpp"

namespace tcb {

/// `path` may name the .node file, the .ele file or the common stem.
TetMesh read_tetgen(const std::filesystem::path& path);

TetMesh parse_tetgen(const std::string& node_name, std::string node_text,
                     const std::string& ele_name, std::string ele_text);

}  // namespace tcb
