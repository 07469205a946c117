#include "oracle/inside_oracle.hpp"
#include "oracle/tunneling.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <cmath>
#include <map>
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

// B's boundary surface at its current positions; nullptr when not closed.
std::unique_ptr<SurfaceQuery> surface_of(const Body& body) {
  auto q = std::make_unique<SurfaceQuery>();
  std::map<std::int32_t, Mesh::Vertex_index> index;
  for (const std::int32_t v : body.mesh->surface_vertices) {
    const Vec3& p = body.x_m[v];
    index[v] = q->mesh.add_vertex(Point(p.x(), p.y(), p.z()));
  }
  for (const Triangle& f : body.mesh->surface)
    if (q->mesh.add_face(index[f[0]], index[f[1]], index[f[2]]) == Mesh::null_face()) return nullptr;
  if (!CGAL::is_closed(q->mesh)) return nullptr;
  q->tree = std::make_unique<Tree>(faces(q->mesh).first, faces(q->mesh).second, q->mesh);
  q->tree->accelerate_distance_queries();
  return q;
}

}  // namespace

namespace {

// (a, b) pairs with a's centre strictly inside b; `open` collects bodies
// whose surface cannot be judged.
std::vector<std::pair<std::size_t, std::size_t>> centres_inside(const World& world, std::vector<std::string>& open) {
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    const auto surface = surface_of(world.bodies[b]);
    if (!surface) {
      open.push_back("'" + world.bodies[b].name + "': surface not closed, tunnelling undefined");
      continue;
    }
    const CGAL::Side_of_triangle_mesh<Mesh, K> side(*surface->tree);
    for (std::size_t a = 0; a < world.bodies.size(); ++a) {
      if (a == b) continue;
      const Vec3 c = centre_of_mass_m(world.bodies[a]);
      if (side(Point(c.x(), c.y(), c.z())) == CGAL::ON_BOUNDED_SIDE) pairs.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

}  // namespace

BodyPairs interlocked_pairs(const World& world) {
  std::vector<std::string> ignored;
  return centres_inside(world, ignored);
}

TunnelingResult count_tunneling(const BodyPairs& before, const World& final_world) {
  TunnelingResult r;
  for (const auto& pair : centres_inside(final_world, r.unmeasured))
    if (!std::binary_search(before.begin(), before.end(), pair)) ++r.pairs;
  return r;
}

OracleFrame compute_inside_oracle(const World& world) {
  OracleFrame frame;
  const std::size_t n = world.bodies.size();
  const auto enabled = [&](std::size_t a, std::size_t b) {
    return a != b && !(world.bodies[a].passive && world.bodies[b].passive);
  };
  // Per vertex of each body: the best classification found so far.
  std::vector<std::vector<std::int32_t>> inside_of(n), on_boundary(n);
  std::vector<std::vector<double>> depth(n);
  for (std::size_t a = 0; a < n; ++a) {
    inside_of[a].assign(world.bodies[a].x_m.size(), -1);
    on_boundary[a].assign(world.bodies[a].x_m.size(), 0);
    depth[a].assign(world.bodies[a].x_m.size(), 0.0);
    if (world.bodies[a].self_collision && !world.bodies[a].passive)
      frame.unmeasured.push_back("self-collision of '" + world.bodies[a].name + "' (not measured by the oracle yet)");
  }
  for (std::size_t b = 0; b < n; ++b) {
    bool partner = false;
    for (std::size_t a = 0; a < n; ++a) partner |= enabled(a, b);
    if (!partner) continue;
    const auto surface = surface_of(world.bodies[b]);
    if (!surface) {
      frame.unmeasured.push_back("'" + world.bodies[b].name + "': surface not closed, inside test undefined");
      continue;
    }
    const CGAL::Side_of_triangle_mesh<Mesh, K> side(*surface->tree);
    for (std::size_t a = 0; a < n; ++a) {
      if (!enabled(a, b)) continue;
      const Body& A = world.bodies[a];
      for (std::size_t v = 0; v < A.x_m.size(); ++v) {
        if (inside_of[a][v] >= 0) continue;  // already inside a body with a smaller index
        const Point p(A.x_m[v].x(), A.x_m[v].y(), A.x_m[v].z());
        const CGAL::Bounded_side s = side(p);
        if (s == CGAL::ON_BOUNDED_SIDE) {
          inside_of[a][v] = static_cast<std::int32_t>(b);
          depth[a][v] = std::sqrt(CGAL::to_double(surface->tree->squared_distance(p)));
        } else if (s == CGAL::ON_BOUNDARY) {
          on_boundary[a][v] = 1;
        }
      }
    }
  }
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t v = 0; v < inside_of[a].size(); ++v) {
      if (inside_of[a][v] >= 0) {
        frame.inside.push_back({static_cast<std::int32_t>(a), static_cast<std::int32_t>(v), inside_of[a][v], depth[a][v]});
        frame.max_depth_m = std::max(frame.max_depth_m, depth[a][v]);
      } else if (on_boundary[a][v]) {
        frame.boundary.emplace_back(static_cast<std::int32_t>(a), static_cast<std::int32_t>(v));
      }
    }
  return frame;
}

}  // namespace tcb
