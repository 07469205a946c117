#include "sim/mesh/tetgen_io.hpp"

#include <limits>

#include "sim/io/atomic_file.hpp"
#include "sim/io/input_error.hpp"
#include "sim/io/token_reader.hpp"

namespace tcb {
namespace {
constexpr std::int64_t kMaxCount = std::numeric_limits<std::int32_t>::max();
constexpr std::int64_t kAnyInt = std::numeric_limits<std::int64_t>::max();
}  // namespace

TetMesh parse_tetgen(const std::string& node_name, std::string node_text, const std::string& ele_name,
                     std::string ele_text) {
  TokenReader nodes(node_name, std::move(node_text));
  const std::int64_t n = nodes.next_int("the point count", 1, kMaxCount);
  const int dim_line = nodes.peek_line();
  if (nodes.next_int("the dimension", 0, 1000) != 3) nodes.fail(dim_line, "only 3D .node files are supported");
  const std::int64_t attributes = nodes.next_int("the attribute count", 0, 1000);
  const std::int64_t markers = nodes.next_int("the boundary-marker flag", 0, 1);
  std::vector<Vec3> vertices;
  vertices.reserve(nodes.reservable(n, 8));  // "i x y z": at least 8 characters
  std::int64_t base = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    const int line = nodes.peek_line();
    const std::int64_t index = nodes.next_int("a point index", -kAnyInt, kAnyInt);
    if (i == 0) {
      if (index != 0 && index != 1) nodes.fail(line, "the first point index must be 0 or 1");
      base = index;
    } else if (index != base + i) {
      nodes.fail(line, "point index " + std::to_string(index) + " where " + std::to_string(base + i) +
                           " was expected");
    }
    const double x = nodes.next_double("a point x coordinate");
    const double y = nodes.next_double("a point y coordinate");
    const double z = nodes.next_double("a point z coordinate");
    for (std::int64_t a = 0; a < attributes; ++a) nodes.next_double("a point attribute");
    if (markers) nodes.next_int("a boundary marker", -kAnyInt, kAnyInt);
    vertices.emplace_back(x, y, z);
  }

  TokenReader eles(ele_name, std::move(ele_text));
  const std::int64_t m = eles.next_int("the tet count", 1, kMaxCount);
  const int nodes_line = eles.peek_line();
  const std::int64_t per_tet = eles.next_int("the nodes per tet", 0, 1000);
  if (per_tet != 4 && per_tet != 10) eles.fail(nodes_line, "nodes per tet must be 4 or 10");
  const std::int64_t regions = eles.next_int("the region-attribute flag", 0, 1);
  std::vector<Tet> tets;
  tets.reserve(eles.reservable(m, 10));  // "i a b c d": at least 10 characters
  for (std::int64_t i = 0; i < m; ++i) {
    eles.next_int("a tet index", -kAnyInt, kAnyInt);
    Tet t{};
    for (std::int64_t k = 0; k < per_tet; ++k) {
      const int line = eles.peek_line();
      const std::int64_t v = eles.next_int("a vertex index", -kAnyInt, kAnyInt);
      if (v < base || v >= base + n)
        eles.fail(line, "vertex index " + std::to_string(v) + " is outside " + std::to_string(base) +
                            ".." + std::to_string(base + n - 1));
      if (k < 4) t[k] = static_cast<std::int32_t>(v - base);
    }
    if (regions) eles.next_double("a region attribute");
    tets.push_back(t);
  }
  try {
    return build_tet_mesh(std::move(vertices), std::move(tets));
  } catch (const MeshError& e) {
    throw InputError(ele_name, 0, e.what());
  }
}

TetMesh read_tetgen(const std::filesystem::path& path) {
  std::filesystem::path stem = path;
  if (path.extension() == ".node" || path.extension() == ".ele") stem.replace_extension();
  const std::filesystem::path node = stem.string() + ".node", ele = stem.string() + ".ele";
  return parse_tetgen(node.string(), read_file(node), ele.string(), read_file(ele));
}

}  // namespace tcb
