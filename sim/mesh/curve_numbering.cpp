#include "sim/mesh/curve_numbering.hpp"

#include "sim/mesh/morton_key.hpp"

namespace tcb {

TetMesh vertices_along_curve(const TetMesh& mesh) {
  const std::vector<Vec3>& x = mesh.positions_m;
  if (x.empty()) return mesh;
  const auto [lo, hi] = bounding_box(x);
  return with_vertices_in_order(mesh, along_curve(x, lo, hi));
}

TetMesh with_vertices_in_order(const TetMesh& mesh, const std::vector<std::uint32_t>& order) {
  const std::vector<Vec3>& x = mesh.positions_m;
  std::vector<std::int32_t> renamed(x.size());  // renamed[old] = new
  std::vector<Vec3> positions(x.size());
  std::vector<std::int32_t> file_id(x.size());
  for (std::size_t v = 0; v < order.size(); ++v) {
    const auto old = static_cast<std::size_t>(order[v]);
    renamed[old] = static_cast<std::int32_t>(v);
    positions[v] = x[old];
    file_id[v] = file_vertex(mesh, static_cast<std::int32_t>(order[v]));
  }
  std::vector<Tet> tets = mesh.tets;
  for (Tet& t : tets)
    for (std::int32_t& v : t) v = renamed[static_cast<std::size_t>(v)];
  TetMesh out = build_tet_mesh(std::move(positions), std::move(tets));
  out.tet_part = mesh.tet_part;
  out.file_vertex_id = std::move(file_id);
  // build_tet_mesh counts again what it repairs; the given mesh's counts
  // describe the file (its tets are stored repaired already).
  out.inverted_tets = mesh.inverted_tets;
  return out;
}

}  // namespace tcb
