// The oracle's inside sets against a brute-force exact per-tet classification
// written here with sim/'s exact orient3d (no CGAL, no box filter), on a
// generic and on a degenerate configuration.
#include "oracle/tet_inside.hpp"

#include <catch2/catch.hpp>

#include <random>

#include "oracle/inside_oracle.hpp"
#include "sim/geometry/orient3d.hpp"
#include "tests/method/test_worlds.hpp"

using namespace tcb;

namespace {

// Every tet of `body`, every point: the contract of tet_inside.hpp, by brute force.
std::vector<TetSide> brute_force(const Body& body, const std::vector<Vec3>& points, bool self) {
  const TetMesh& mesh = *body.mesh;
  std::vector<TetSide> sides;
  for (std::size_t i = 0; i < points.size(); ++i) {
    bool strictly = false, touches = false, on_surface = false;
    for (const Tet& t : mesh.tets) {
      if (self && std::find(t.begin(), t.end(), static_cast<std::int32_t>(i)) != t.end()) continue;
      const Vec3 q[4] = {body.x_m[t[0]], body.x_m[t[1]], body.x_m[t[2]], body.x_m[t[3]]};
      const int o = orient3d(q[0], q[1], q[2], q[3]);
      if (o == 0) continue;
      int s[4];
      for (int k = 0; k < 4; ++k) {
        Vec3 r[4] = {q[0], q[1], q[2], q[3]};
        r[k] = points[i];
        s[k] = orient3d(r[0], r[1], r[2], r[3]) * o;
      }
      if (s[0] < 0 || s[1] < 0 || s[2] < 0 || s[3] < 0) continue;
      if (s[0] > 0 && s[1] > 0 && s[2] > 0 && s[3] > 0) strictly = true;
      else touches = true;
    }
    if (!strictly && touches) {
      // On a closed boundary triangle: coplanar with it and inside it.
      for (const Triangle& f : mesh.surface) {
        const Vec3 &a = body.x_m[f[0]], &b = body.x_m[f[1]], &c = body.x_m[f[2]];
        if (orient3d(a, b, c, points[i]) != 0) continue;
        const Vec3 n = (b - a).cross(c - a);  // a point off the plane, to project against
        const Vec3 apex = a + n;
        const int o = orient3d(a, b, c, apex);
        if (orient3d(points[i], b, c, apex) * o >= 0 && orient3d(a, points[i], c, apex) * o >= 0 &&
            orient3d(a, b, points[i], apex) * o >= 0)
          on_surface = true;
      }
    }
    sides.push_back(strictly ? TetSide::Inside
                    : touches ? (on_surface ? TetSide::Boundary : TetSide::Inside)
                              : TetSide::Outside);
  }
  return sides;
}

// Side of `b` for every vertex of `a` as compute_inside_oracle reports it.
std::vector<TetSide> oracle_sides(const World& world, std::int32_t a, std::int32_t b) {
  const OracleFrame frame = compute_inside_oracle(world);
  std::vector<TetSide> sides(world.bodies[a].x_m.size(), TetSide::Outside);
  for (const OraclePoint& p : frame.inside)
    if (p.object == a && p.other == b) sides[p.vertex] = TetSide::Inside;
  for (const auto& [object, vertex] : frame.boundary)
    if (object == a) sides[vertex] = TetSide::Boundary;
  return sides;
}

int count(const std::vector<TetSide>& sides, TetSide s) { return static_cast<int>(std::count(sides.begin(), sides.end(), s)); }

}  // namespace

TEST_CASE("tet_inside and the surface oracle equal brute force: degenerate grid-aligned cubes", "[oracle]") {
  // Dyadic sizes, so both grids are exact in binary: B's vertices lie on A's
  // grid, and A's vertices fall exactly on B's vertices, edges, interior faces
  // and boundary faces. A: [-0.25, 0.25]^3, spacing 0.125; B: [0, 0.25] x
  // [0, 0.25] x [-0.125, 0.125], spacing 0.125.
  const test::TestScene scene = test::scene_of({{"a", "box:size=0.5x0.5x0.5,cells=4x4x4"},
                                          {"b", "box:size=0.25x0.25x0.25,cells=2x2x2", Vec3(0.125, 0.125, 0.0)}});
  const World world = build_world(scene.world);
  const std::vector<TetSide> expected = brute_force(world.bodies[1], world.bodies[0].x_m, false);
  CHECK(count(expected, TetSide::Inside) == 1);     // B's centre vertex: on interior faces only
  CHECK(count(expected, TetSide::Boundary) == 26);  // the rest of B's 3x3x3 grid
  CHECK(classify_points_in_tets(world.bodies[1], world.bodies[0].x_m) == expected);
  CHECK(oracle_sides(world, 0, 1) == expected);
  // B's vertices against A: those with x or y = 0.25 lie on A's boundary
  // (15), the other 12 on A's interior faces, edges or vertices.
  const std::vector<TetSide> b_in_a = brute_force(world.bodies[0], world.bodies[1].x_m, false);
  CHECK(count(b_in_a, TetSide::Inside) == 12);
  CHECK(count(b_in_a, TetSide::Boundary) == 15);
  CHECK(classify_points_in_tets(world.bodies[0], world.bodies[1].x_m) == b_in_a);
  CHECK(oracle_sides(world, 1, 0) == b_in_a);
}

TEST_CASE("tet_inside and the surface oracle equal brute force: sphere through torus", "[oracle]") {
  const test::TestScene scene = test::scene_of(
      {{"torus", "meshes/torus_coarse.mesh"}, {"sphere", "meshes/sphere_coarse.mesh", Vec3(0.1, 0.02, 0.0), false, false, 0.5}},
      TCBENCH_DATA_DIR);
  World world = build_world(scene.world);
  // Random points in the torus's box besides the sphere's vertices.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec3 lo = world.bodies[0].x_m[0], hi = lo;
  for (const Vec3& x : world.bodies[0].x_m) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  std::vector<Vec3> points = world.bodies[1].x_m;
  for (int i = 0; i < 300; ++i)
    points.push_back(0.5 * (lo + hi) + 0.5 * (hi - lo).cwiseProduct(Vec3(u(rng), u(rng), u(rng))));
  const std::vector<TetSide> expected = brute_force(world.bodies[0], points, false);
  CHECK(count(expected, TetSide::Inside) > 20);
  CHECK(count(expected, TetSide::Outside) > 20);
  CHECK(classify_points_in_tets(world.bodies[0], points) == expected);
  const std::vector<TetSide> sphere_part(expected.begin(), expected.begin() + world.bodies[1].x_m.size());
  CHECK(oracle_sides(world, 1, 0) == sphere_part);
}

TEST_CASE("self-collision: a vertex pushed into its own body is inside, with no true depth", "[oracle]") {
  const test::TestScene scene = test::scene_of({{"self", "box:size=0.5x0.5x0.5,cells=4x4x4", Vec3::Zero(), false, true}});
  World world = build_world(scene.world);
  Body& body = world.bodies[0];
  CHECK(count(classify_self_points(body), TetSide::Inside) == 0);  // conforming and undeformed
  std::int32_t corner = 0;
  for (std::size_t v = 0; v < body.x_m.size(); ++v)
    if (body.x_m[v].maxCoeff() == -0.25) corner = static_cast<std::int32_t>(v);  // (-0.25, -0.25, -0.25)
  body.x_m[corner] = Vec3(0.01, 0.02, 0.03);  // deep inside tets not incident to it
  const std::vector<TetSide> sides = classify_self_points(body);
  CHECK(sides == brute_force(body, body.x_m, true));
  CHECK(sides[corner] == TetSide::Inside);
  // (The corner's stretched tets may now also contain some other vertices.)
  const OracleFrame frame = compute_inside_oracle(world);
  CHECK(static_cast<int>(frame.inside.size()) == count(sides, TetSide::Inside));
  for (const OraclePoint& p : frame.inside) {
    CHECK(sides[p.vertex] == TetSide::Inside);
    CHECK(p.other == 0);
    CHECK(std::isnan(p.depth_m));
  }
  REQUIRE(frame.unmeasured.size() == 1);
  CHECK_THAT(frame.unmeasured[0], Catch::Matchers::Contains("self-collision"));
}
