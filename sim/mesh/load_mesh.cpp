#include "sim/mesh/load_mesh.hpp"

#include <stdexcept>

#include "sim/io/input_error.hpp"
#include "sim/mesh/box_mesh.hpp"
#include "sim/mesh/medit_io.hpp"
#include "sim/mesh/tetgen_io.hpp"

namespace tcb {

TetMesh load_mesh(const std::string& source, const std::filesystem::path& base_dir) {
  if (is_generator_source(source)) {
    try {
      return make_generated_mesh(source);
    } catch (const std::invalid_argument& e) {
      throw InputError(source, 0, e.what());
    }
  }
  std::filesystem::path path(source);
  if (path.is_relative() && !base_dir.empty()) path = base_dir / path;
  const std::string ext = path.extension().string();
  if (ext == ".mesh") return read_medit(path);
  if (ext == ".node" || ext == ".ele") return read_tetgen(path);
  throw InputError(path.string(), 0, "unknown mesh format '" + ext + "' (expected .mesh, .node or .ele)");
}

}  // namespace tcb
