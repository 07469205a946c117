#include "sim/mesh/mesh_statistics.hpp"

#include <algorithm>

namespace tcb {

MeshStatistics mesh_statistics(const TetMesh& mesh) {
  MeshStatistics s;
  const auto& x = mesh.positions_m;
  s.vertices = mesh.vertex_count();
  s.tets = mesh.tet_count();
  s.edges = mesh.edges.size();
  s.surface_triangles = mesh.surface.size();
  s.volume_m3 = total_volume(mesh, x);
  if (!x.empty()) {
    s.bbox_min = s.bbox_max = x[0];
    for (const Vec3& p : x) {
      s.bbox_min = s.bbox_min.cwiseMin(p);
      s.bbox_max = s.bbox_max.cwiseMax(p);
    }
  }
  double edge_sum = 0.0;
  for (const Edge& e : mesh.edges) edge_sum += (x[e[1]] - x[e[0]]).norm();
  s.average_edge_m = mesh.edges.empty() ? 0.0 : edge_sum / static_cast<double>(mesh.edges.size());
  const std::vector<char>& degenerate = mesh.is_degenerate;
  double worst = 1.0, sum = 0.0;
  std::size_t counted = 0;
  for (std::size_t i = 0; i < mesh.tet_count(); ++i) {
    if (degenerate[i]) continue;
    const Tet& t = mesh.tets[i];
    const double q = tet_quality(x[t[0]], x[t[1]], x[t[2]], x[t[3]]);
    worst = std::min(worst, q);
    sum += q;
    ++counted;
  }
  s.worst_quality = counted ? worst : 0.0;
  s.mean_quality = counted ? sum / static_cast<double>(counted) : 0.0;
  s.inverted_tets = mesh.inverted_tets;
  s.degenerate_tets = mesh.degenerate_tets;
  s.folded_faces = mesh.folded_faces;
  s.isolated_vertices = mesh.isolated_vertices;
  s.surface_euler_characteristic = surface_euler_characteristic(mesh);
  s.parts = part_count(mesh);
  return s;
}

}  // namespace tcb
