#pragma once
// Shared checks on a mesh's boundary surface, used by the mesh tests.

#include <catch2/catch.hpp>

#include <map>

#include "sim/mesh/tet_mesh.hpp"

namespace tcb::test {

/// Volume enclosed by the surface by the divergence theorem; equals the tet
/// volume only if the surface is closed and wound outward.
inline double surface_enclosed_volume(const TetMesh& mesh) {
  double v = 0.0;
  for (const Triangle& f : mesh.surface) {
    const Vec3& a = mesh.positions_m[f[0]];
    const Vec3& b = mesh.positions_m[f[1]];
    const Vec3& c = mesh.positions_m[f[2]];
    v += a.dot(b.cross(c)) / 6.0;
  }
  return v;
}

/// Every directed surface edge must be matched by exactly one edge in the
/// opposite direction: the surface is closed, manifold along edges, and
/// consistently oriented.
inline int unmatched_directed_edges(const TetMesh& mesh) {
  std::map<std::pair<int, int>, int> directed;
  for (const Triangle& f : mesh.surface)
    for (int k = 0; k < 3; ++k) ++directed[{f[k], f[(k + 1) % 3]}];
  int unmatched = 0;
  for (const auto& [edge, count] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    unmatched += count != 1 || reverse == directed.end() || reverse->second != 1;
  }
  return unmatched;
}

inline void require_closed_oriented_surface(const TetMesh& mesh) {
  REQUIRE(unmatched_directed_edges(mesh) == 0);
}

}  // namespace tcb::test
