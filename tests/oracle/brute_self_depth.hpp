#pragma once
// The contract of oracle/self_depth.hpp written out directly, for tests:
// exact orient3d per tet, CGAL point-triangle distance per triangle, no
// boxes, no trees. O(V T) set lookups: small meshes only.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <vector>

#include "oracle/tet_inside.hpp"
#include "sim/geometry/orient3d.hpp"
#include "sim/world/world.hpp"

namespace tcb::test {

// The contract of self_depth.hpp, written out directly.
inline std::vector<double> brute_force_depths(const Body& body, const std::vector<TetSide>& self_sides) {
  const TetMesh& mesh = *body.mesh;
  std::vector<double> depth(body.x_m.size(), std::nan(""));
  // The parts of the tets at each vertex.
  std::vector<std::set<std::int32_t>> parts_at(mesh.vertex_count());
  for (std::size_t t = 0; t < mesh.tet_count(); ++t)
    for (const std::int32_t u : mesh.tets[t]) parts_at[static_cast<std::size_t>(u)].insert(mesh.tet_part[t]);
  for (std::size_t v = 0; v < body.x_m.size(); ++v) {
    if (self_sides[v] != TetSide::Inside) continue;
    // v's own parts, and its neighbourhood: the parts of every tet with a
    // vertex that a tet of an own part holds.
    const std::set<std::int32_t>& own = parts_at[v];
    std::set<std::int32_t> hood;
    for (std::size_t t = 0; t < mesh.tet_count(); ++t)
      for (const std::int32_t u : mesh.tets[t])
        for (const std::int32_t part : parts_at[static_cast<std::size_t>(u)])
          if (own.count(part)) hood.insert(mesh.tet_part[t]);
    // Strictly inside a far tet, or in a closed far tet and on no boundary
    // triangle of the body (the tet_inside rule over the far tets).
    bool strictly = false, touches = false, on_surface = false;
    for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
      const Tet& tet = mesh.tets[t];
      if (hood.count(mesh.tet_part[t]) || std::count(tet.begin(), tet.end(), static_cast<std::int32_t>(v))) continue;
      const Vec3 q[4] = {body.x_m[tet[0]], body.x_m[tet[1]], body.x_m[tet[2]], body.x_m[tet[3]]};
      const int o = orient3d(q[0], q[1], q[2], q[3]);
      if (o == 0) continue;
      int s[4];
      for (int k = 0; k < 4; ++k) {
        Vec3 r[4] = {q[0], q[1], q[2], q[3]};
        r[k] = body.x_m[v];
        s[k] = orient3d(r[0], r[1], r[2], r[3]) * o;
      }
      if (s[0] < 0 || s[1] < 0 || s[2] < 0 || s[3] < 0) continue;
      if (s[0] > 0 && s[1] > 0 && s[2] > 0 && s[3] > 0) strictly = true;
      else touches = true;
      for (int k = 0; k < 4; ++k) {
        if (s[k] != 0) continue;
        const auto face = tet_faces(tet)[k];  // opposite vertex k, as the tets are stored
        for (const Triangle& f : mesh.surface) {
          Triangle a = f, b = face;
          std::sort(a.begin(), a.end()), std::sort(b.begin(), b.end());
          if (a == b) on_surface = true;
        }
      }
    }
    if (!(strictly || (touches && !on_surface))) continue;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t f = 0; f < mesh.surface.size(); ++f) {
      if (hood.count(mesh.tet_part[mesh.surface_tet[f]])) continue;
      const auto P = [&](std::int32_t i) { return CGAL::Epick::Point_3(body.x_m[i].x(), body.x_m[i].y(), body.x_m[i].z()); };
      const Triangle& tri = mesh.surface[f];
      const CGAL::Epick::Point_3 p(body.x_m[v].x(), body.x_m[v].y(), body.x_m[v].z());
      best = std::min(best, CGAL::to_double(CGAL::squared_distance(p, CGAL::Epick::Triangle_3(P(tri[0]), P(tri[1]), P(tri[2])))));
    }
    depth[v] = std::sqrt(best);
  }
  return depth;
}


}  // namespace tcb::test
