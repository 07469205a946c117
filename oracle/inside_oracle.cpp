#include "oracle/inside_oracle.hpp"
#include "oracle/self_depth.hpp"
#include "oracle/surface_mesh.hpp"
#include "oracle/tet_inside.hpp"
#include "oracle/tunneling.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace tcb {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

struct SurfaceQuery {
  Mesh mesh;
  std::unique_ptr<Tree> tree;
};

// Distances to a surface that need not be closed (a triangle soup).
using SoupTriangles = std::vector<K::Triangle_3>;
using SoupPrimitive = CGAL::AABB_triangle_primitive<K, SoupTriangles::const_iterator>;
using SoupTree = CGAL::AABB_tree<CGAL::AABB_traits<K, SoupPrimitive>>;

struct SoupQuery {
  SoupTriangles triangles;
  std::unique_ptr<SoupTree> tree;
};

std::unique_ptr<SoupQuery> soup_of(const Body& body) {
  auto q = std::make_unique<SoupQuery>();
  const auto point = [&](std::int32_t v) { return Point(body.x_m[v].x(), body.x_m[v].y(), body.x_m[v].z()); };
  for (const Triangle& f : body.mesh->surface) q->triangles.emplace_back(point(f[0]), point(f[1]), point(f[2]));
  q->tree = std::make_unique<SoupTree>(q->triangles.cbegin(), q->triangles.cend());
  q->tree->accelerate_distance_queries();
  return q;
}

// B's boundary surface at its current positions; nullptr when not closed.
std::unique_ptr<SurfaceQuery> surface_of(const Body& body) {
  auto q = std::make_unique<SurfaceQuery>();
  bool manifold = false;
  q->mesh = oracle_detail::surface_mesh_of<K>(body, manifold);
  if (!manifold || !CGAL::is_closed(q->mesh)) return nullptr;
  q->tree = std::make_unique<Tree>(faces(q->mesh).first, faces(q->mesh).second, q->mesh);
  q->tree->accelerate_distance_queries();
  return q;
}

}  // namespace

BodyPairs centres_inside_pairs(const World& world) {
  BodyPairs pairs;
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    std::vector<std::size_t> others;
    std::vector<Vec3> centres;
    for (std::size_t a = 0; a < world.bodies.size(); ++a) {
      if (a == b || (world.bodies[a].passive && world.bodies[b].passive)) continue;
      others.push_back(a);
      centres.push_back(centre_of_mass_m(world.bodies[a]));
    }
    if (others.empty()) continue;
    std::vector<bool> inside(others.size(), false);
    if (const auto surface = surface_of(world.bodies[b])) {
      const CGAL::Side_of_triangle_mesh<Mesh, K> side(*surface->tree);
      for (std::size_t i = 0; i < others.size(); ++i)
        inside[i] = side(Point(centres[i].x(), centres[i].y(), centres[i].z())) == CGAL::ON_BOUNDED_SIDE;
    } else {
      const std::vector<TetSide> sides = classify_points_in_tets(world.bodies[b], centres);
      for (std::size_t i = 0; i < others.size(); ++i) inside[i] = sides[i] == TetSide::Inside;
    }
    for (std::size_t i = 0; i < others.size(); ++i)
      if (inside[i]) pairs.emplace_back(std::min(others[i], b), std::max(others[i], b));
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

OracleFrame compute_inside_oracle(const World& world) {
  OracleFrame frame;
  const std::size_t n = world.bodies.size();
  const auto enabled = [&](std::size_t a, std::size_t b) {
    return a != b && !(world.bodies[a].passive && world.bodies[b].passive);
  };
  // Per vertex of each body: the body it is inside (the smallest index wins),
  // whether it lies on some body's boundary, and its true depth.
  std::vector<std::vector<std::int32_t>> inside_of(n), on_boundary(n);
  std::vector<std::vector<double>> depth(n);
  for (std::size_t a = 0; a < n; ++a) {
    inside_of[a].assign(world.bodies[a].x_m.size(), -1);
    on_boundary[a].assign(world.bodies[a].x_m.size(), 0);
    depth[a].assign(world.bodies[a].x_m.size(), 0.0);
  }
  const auto mark = [&](std::size_t a, std::size_t v, std::size_t b, const auto& distance_to_b) {
    const auto bi = static_cast<std::int32_t>(b);
    if (inside_of[a][v] >= 0 && inside_of[a][v] < bi) return;
    inside_of[a][v] = bi;
    depth[a][v] = distance_to_b();
  };
  for (std::size_t b = 0; b < n; ++b) {
    const Body& B = world.bodies[b];
    bool partner = false;
    for (std::size_t a = 0; a < n; ++a) partner |= enabled(a, b);
    if (partner) {
      if (const auto surface = surface_of(B)) {
        const CGAL::Side_of_triangle_mesh<Mesh, K> side(*surface->tree);
        for (std::size_t a = 0; a < n; ++a) {
          if (!enabled(a, b)) continue;
          const Body& A = world.bodies[a];
          for (std::size_t v = 0; v < A.x_m.size(); ++v) {
            const Point p(A.x_m[v].x(), A.x_m[v].y(), A.x_m[v].z());
            const CGAL::Bounded_side s = side(p);
            if (s == CGAL::ON_BOUNDED_SIDE)
              mark(a, v, b, [&] { return std::sqrt(CGAL::to_double(surface->tree->squared_distance(p))); });
            else if (s == CGAL::ON_BOUNDARY)
              on_boundary[a][v] = 1;
          }
        }
      } else {
        // An open surface (folds, holes) has no inside: decide by B's tets instead.
        const auto soup = soup_of(B);
        for (std::size_t a = 0; a < n; ++a) {
          if (!enabled(a, b)) continue;
          const Body& A = world.bodies[a];
          const std::vector<TetSide> sides = classify_points_in_tets(B, A.x_m);
          for (std::size_t v = 0; v < A.x_m.size(); ++v) {
            const Point p(A.x_m[v].x(), A.x_m[v].y(), A.x_m[v].z());
            if (sides[v] == TetSide::Inside)
              mark(a, v, b, [&] { return std::sqrt(CGAL::to_double(soup->tree->squared_distance(p))); });
            else if (sides[v] == TetSide::Boundary)
              on_boundary[a][v] = 1;
          }
        }
      }
    }
    if (self_collision_active(B)) {
      const std::vector<TetSide> sides = classify_self_points(B);
      const SelfDepths self = self_collision_depths(B, sides);
      for (std::size_t v = 0; v < sides.size(); ++v) {
        if (sides[v] == TetSide::Inside)
          mark(b, v, b, [&] { return self.depth_m[v]; });
        else if (sides[v] == TetSide::Boundary)
          on_boundary[b][v] = 1;
      }
      if (self.shallow > 0)
        frame.unmeasured.push_back(
            part_count(*B.mesh) < 2
                ? "true depth of self-collision points of '" + B.name + "' (the body has no parts)"
                : "true depth of self-collision points of '" + B.name +
                      "' that lie in no far part (self_depth.hpp: not defined)");
    }
  }
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t v = 0; v < inside_of[a].size(); ++v) {
      if (inside_of[a][v] >= 0) {
        frame.inside.push_back({static_cast<std::int32_t>(a), static_cast<std::int32_t>(v), inside_of[a][v], depth[a][v]});
        if (std::isfinite(depth[a][v])) frame.max_depth_m = std::max(frame.max_depth_m, depth[a][v]);
      } else if (on_boundary[a][v]) {
        frame.boundary.emplace_back(static_cast<std::int32_t>(a), static_cast<std::int32_t>(v));
      }
    }
  return frame;
}

}  // namespace tcb
