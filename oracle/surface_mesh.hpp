#pragma once
// A body's boundary surface at its current positions as a CGAL Surface_mesh in
// any kernel (internal to oracle/: the oracle's .cpp files include it, nothing
// outside oracle/ sees CGAL). Only surface vertices are added, so vertex
// indices differ from the mesh's.

#include <CGAL/Surface_mesh.h>

#include <map>

#include "sim/world/world.hpp"

namespace tcb::oracle_detail {

/// The surface mesh; `manifold` is false when a face could not be added
/// (a non-manifold surface), and the mesh then lacks that face.
template <class Kernel>
CGAL::Surface_mesh<typename Kernel::Point_3> surface_mesh_of(const Body& body, bool& manifold) {
  using Mesh = CGAL::Surface_mesh<typename Kernel::Point_3>;
  Mesh mesh;
  std::map<std::int32_t, typename Mesh::Vertex_index> index;
  for (const std::int32_t v : body.mesh->surface_vertices)
    index[v] = mesh.add_vertex(typename Kernel::Point_3(body.x_m[v].x(), body.x_m[v].y(), body.x_m[v].z()));
  manifold = true;
  for (const Triangle& f : body.mesh->surface)
    if (mesh.add_face(index[f[0]], index[f[1]], index[f[2]]) == Mesh::null_face()) manifold = false;
  return mesh;
}

}  // namespace tcb::oracle_detail
