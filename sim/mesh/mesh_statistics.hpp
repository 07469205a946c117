#pragma once
/// What `tcbench mesh info` reports about a mesh: sizes, volume, bounding box,
/// element quality and the defects build_tet_mesh found.

#include "sim/mesh/tet_mesh.hpp"

namespace tcb {

struct MeshStatistics {
  std::size_t vertices = 0, tets = 0, edges = 0, surface_triangles = 0;
  double volume_m3 = 0.0;                ///< sum of signed tet volumes
  Vec3 bbox_min = Vec3::Zero(), bbox_max = Vec3::Zero();
  double average_edge_m = 0.0;           ///< the spatial hash's "auto" cell size
  double worst_quality = 0.0;            ///< min tet_quality over non-degenerate tets (1 regular, 0 flat)
  double mean_quality = 0.0;
  std::int64_t inverted_tets = 0, degenerate_tets = 0, folded_faces = 0, isolated_vertices = 0;
  std::int64_t surface_euler_characteristic = 0;
  std::size_t parts = 1;                 ///< distinct parts (tet_part); 1 without
};

MeshStatistics mesh_statistics(const TetMesh& mesh);

}  // namespace tcb
