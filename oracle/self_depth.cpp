#include "oracle/self_depth.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

namespace tcb {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Triangles = std::vector<K::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

Point point_of(const Vec3& x) { return Point(x.x(), x.y(), x.z()); }

void sort_unique(std::vector<std::int32_t>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

}  // namespace

SelfDepths self_collision_depths(const Body& body, const std::vector<TetSide>& self_sides) {
  const TetMesh& mesh = *body.mesh;
  const std::size_t n = body.x_m.size();
  SelfDepths r;
  r.depth_m.assign(n, std::numeric_limits<double>::quiet_NaN());
  std::vector<char> inside(n, 0);
  std::int64_t count = 0;
  for (std::size_t v = 0; v < n && v < self_sides.size(); ++v)
    if (self_sides[v] == TetSide::Inside) inside[v] = 1, ++count;
  if (count == 0) return r;
  if (!mesh.tet_part.empty() && mesh.tet_part.size() != mesh.tet_count())
    throw std::invalid_argument("self_collision_depths: tet_part has " + std::to_string(mesh.tet_part.size()) +
                                " entries for " + std::to_string(mesh.tet_count()) + " tets");
  if (part_count(mesh) < 2) {
    r.shallow = count;
    return r;
  }
  // Each vertex's parts (of its incident tets), then which parts touch: two
  // parts are neighbours when some vertex belongs to both.
  std::vector<std::vector<std::int32_t>> vertex_parts(n);
  for (std::size_t v = 0; v < n; ++v) {
    for (const std::int32_t* t = mesh.vertex_tets.begin(v); t != mesh.vertex_tets.end(v); ++t)
      vertex_parts[v].push_back(mesh.tet_part[*t]);
    sort_unique(vertex_parts[v]);
  }
  std::map<std::int32_t, std::vector<std::int32_t>> touching;
  for (const auto& parts : vertex_parts)
    for (const std::int32_t a : parts) touching[a].insert(touching[a].end(), parts.begin(), parts.end());
  for (auto& [part, others] : touching) sort_unique(others);
  // N(v) for the self-collision points only.
  std::vector<std::vector<std::int32_t>> hood(n);
  for (std::size_t v = 0; v < n; ++v) {
    if (!inside[v]) continue;
    for (const std::int32_t a : vertex_parts[v]) hood[v].insert(hood[v].end(), touching[a].begin(), touching[a].end());
    sort_unique(hood[v]);
  }
  const auto far = [&](std::size_t v, std::int32_t part) { return !std::binary_search(hood[v].begin(), hood[v].end(), part); };
  const std::vector<TetSide> deep_sides = classify_self_points_among(
      body, [&](std::int32_t v, std::int32_t t) { return inside[v] && far(v, mesh.tet_part[t]); });
  // Deep points grouped by their neighbourhood: one distance tree per group.
  std::map<std::vector<std::int32_t>, std::vector<std::int32_t>> groups;
  for (std::size_t v = 0; v < n; ++v) {
    if (!inside[v]) continue;
    if (deep_sides[v] == TetSide::Inside)
      groups[hood[v]].push_back(static_cast<std::int32_t>(v)), ++r.deep;
    else
      ++r.shallow;
  }
  for (const auto& [parts, vertices] : groups) {
    Triangles triangles;
    for (std::size_t f = 0; f < mesh.surface.size(); ++f) {
      if (!far(vertices.front(), mesh.tet_part[mesh.surface_tet[f]])) continue;
      const Triangle& tri = mesh.surface[f];
      triangles.emplace_back(point_of(body.x_m[tri[0]]), point_of(body.x_m[tri[1]]), point_of(body.x_m[tri[2]]));
    }
    // Far parts wholly enclosed by p's neighbourhood have no boundary
    // triangle: nothing to measure to, so no depth.
    if (triangles.empty()) {
      r.deep -= static_cast<std::int64_t>(vertices.size());
      r.shallow += static_cast<std::int64_t>(vertices.size());
      continue;
    }
    Tree tree(triangles.cbegin(), triangles.cend());
    tree.accelerate_distance_queries();
    for (const std::int32_t v : vertices)
      r.depth_m[v] = std::sqrt(CGAL::to_double(tree.squared_distance(point_of(body.x_m[v]))));
  }
  return r;
}

}  // namespace tcb
