#pragma once
/// Loads a mesh named by a scene or the command line: a generator string
/// (see box_mesh.hpp) or a file whose extension picks the reader
/// (.mesh MEDIT; .node/.ele TetGen). Relative paths resolve against base_dir.
/// Throws InputError (file, line, problem) for anything malformed.

#include <filesystem>
#include <string>

#include "sim/mesh/tet_mesh.hpp"

namespace tcb {

TetMesh load_mesh(const std::string& source, const std::filesystem::path& base_dir = {});

}  // namespace tcb
