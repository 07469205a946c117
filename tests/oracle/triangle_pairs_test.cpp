// FCL's intersecting triangle pairs against CGAL's exact do_intersect.
#include "oracle/triangle_pairs.hpp"

#include <catch2/catch.hpp>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include "tests/method/test_worlds.hpp"

using namespace tcb;

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

K::Triangle_3 triangle_of(const Body& body, std::size_t f) {
  const auto point = [&](std::int32_t v) { return K::Point_3(body.x_m[v].x(), body.x_m[v].y(), body.x_m[v].z()); };
  const Triangle& t = body.mesh->surface[f];
  return K::Triangle_3(point(t[0]), point(t[1]), point(t[2]));
}

// Every surface triangle of a against every one of b, exact predicates.
std::vector<TrianglePair> brute_force(const World& world, std::int32_t a, std::int32_t b) {
  std::vector<TrianglePair> pairs;
  const Body &A = world.bodies[a], &B = world.bodies[b];
  std::vector<K::Triangle_3> tb;
  for (std::size_t g = 0; g < B.mesh->surface.size(); ++g) tb.push_back(triangle_of(B, g));
  for (std::size_t f = 0; f < A.mesh->surface.size(); ++f) {
    const K::Triangle_3 ta = triangle_of(A, f);
    for (std::size_t g = 0; g < tb.size(); ++g)
      if (CGAL::do_overlap(ta.bbox(), tb[g].bbox()) && CGAL::do_intersect(ta, tb[g]))
        pairs.push_back({a, b, static_cast<std::int32_t>(f), static_cast<std::int32_t>(g)});
  }
  return pairs;
}

bool same(const std::vector<TrianglePair>& p, const std::vector<TrianglePair>& q) {
  if (p.size() != q.size()) return false;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p[i].a != q[i].a || p[i].b != q[i].b || p[i].triangle_a != q[i].triangle_a || p[i].triangle_b != q[i].triangle_b)
      return false;
  return true;
}

}  // namespace

TEST_CASE("FCL triangle pairs equal CGAL's exact do_intersect, also after the meshes move", "[oracle]") {
  const test::TestScene scene = test::scene_of(
      {{"torus", "meshes/torus_coarse.mesh"}, {"sphere", "meshes/sphere_fine.mesh", Vec3(0.1, 0.02, 0.0), false, false, 0.5}},
      TCBENCH_DATA_DIR);
  World world = build_world(scene.world);
  SurfaceTrianglePairs fcl_pairs(world);
  for (int frame = 0; frame < 3; ++frame) {
    const std::vector<TrianglePair> found = fcl_pairs.find(world);  // refitted to the moved sphere
    const std::vector<TrianglePair> exact = brute_force(world, 0, 1);
    CHECK(exact.size() > 50);
    CHECK(same(found, exact));
    for (Vec3& x : world.bodies[1].x_m) x += Vec3(0.013, -0.007, 0.011);
  }
}

TEST_CASE("FCL sees no triangle pairs for a box wholly inside another", "[oracle]") {
  const World world = build_world(test::scene_of(
      {{"big", "box:size=1x1x1,cells=2x2x2", Vec3::Zero(), true}, {"small", "box:size=0.2x0.2x0.2,cells=2x2x2"}}));
  SurfaceTrianglePairs fcl_pairs(world);
  CHECK(fcl_pairs.find(world).empty());  // the inside oracle is what finds this one
}
