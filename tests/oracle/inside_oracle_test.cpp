// The oracle against analytic answers, and full against the oracle.
#include "oracle/inside_oracle.hpp"

#include <catch2/catch.hpp>

#include <map>

#include "baselines/registry.hpp"
#include "experiments/metrics/oracle_comparison.hpp"
#include "tests/method/test_worlds.hpp"

using namespace tcb;

TEST_CASE("oracle: two axis-aligned boxes overlapping by a known box", "[oracle]") {
  // A spans [-0.1, 0.1]^3 on a 0.05 grid; B spans [0, 0.2]^3. A's vertices with
  // all coordinates in {0.05, 0.1} are inside B, at depth min(coordinates);
  // those with a 0 coordinate and the rest >= 0 lie on B's surface.
  const SceneDesc scene = test::scene_of({{"a", "box:size=0.2x0.2x0.2,cells=4x4x4"},
                                          {"b", "box:size=0.2x0.2x0.2,cells=3x3x3", Vec3(0.1, 0.1, 0.1)}});
  const World world = build_world(scene);
  const OracleFrame frame = compute_inside_oracle(world);
  CHECK(frame.unmeasured.empty());
  std::map<int, double> a_inside;
  for (const OraclePoint& p : frame.inside)
    if (p.object == 0) a_inside[p.vertex] = p.depth_m;
  CHECK(a_inside.size() == 8);
  for (const auto& [v, d] : a_inside) {
    const Vec3& x = world.bodies[0].x_m[v];
    CHECK(x.minCoeff() > 0.0);
    CHECK(d == Approx(x.minCoeff()).margin(1e-12));
  }
  int a_boundary = 0;
  for (const auto& [object, vertex] : frame.boundary) a_boundary += object == 0;
  CHECK(a_boundary == 27 - 8);
  CHECK(frame.max_depth_m == Approx(0.1).margin(1e-12));
}

TEST_CASE("oracle: a small box wholly inside a large one is found (FCL would see nothing)", "[oracle]") {
  const SceneDesc scene = test::scene_of(
      {{"big", "box:size=1x1x1,cells=2x2x2", Vec3::Zero(), true}, {"small", "box:size=0.2x0.2x0.2,cells=2x2x2"}});
  const World world = build_world(scene);
  const OracleFrame frame = compute_inside_oracle(world);
  int small_inside = 0;
  for (const OraclePoint& p : frame.inside)
    if (p.object == 1) {
      ++small_inside;
      const Vec3& x = world.bodies[1].x_m[p.vertex];
      CHECK(p.depth_m == Approx(0.5 - x.cwiseAbs().maxCoeff()).margin(1e-12));
    }
  CHECK(small_inside == 27);
}

TEST_CASE("oracle: what it cannot decide is reported, not skipped", "[oracle]") {
  const SceneDesc scene = test::scene_of({{"self", "box:size=0.2x0.2x0.2,cells=2x2x2", Vec3::Zero(), false, true},
                                          {"other", "box:size=0.2x0.2x0.2,cells=2x2x2", Vec3(0.05, 0.05, 0.05)}});
  const OracleFrame frame = compute_inside_oracle(build_world(scene));
  REQUIRE(frame.unmeasured.size() == 1);
  CHECK_THAT(frame.unmeasured[0], Catch::Matchers::Contains("self-collision"));
}

TEST_CASE("comparison: on-boundary points are neither missed nor false", "[oracle]") {
  OracleFrame oracle;
  oracle.inside = {{0, 1, 1, 0.01}, {0, 2, 1, 0.02}};
  oracle.boundary = {{0, 3}};
  std::vector<Contact> method(3);
  method[0].object = 0, method[0].vertex = 1, method[0].depth_source = DepthSource::Border, method[0].depth_m = 0.015;
  method[1].object = 0, method[1].vertex = 3;  // on the boundary: not counted
  method[2].object = 0, method[2].vertex = 9;  // a false positive
  const OracleComparison c = compare_with_oracle(method, oracle);
  CHECK(c.oracle_points == 2);
  CHECK(*c.recall == Approx(0.5));
  CHECK(*c.precision == Approx(0.5));
  CHECK(*c.depth_err_max == Approx(0.005));
  CHECK_FALSE(compare_with_oracle({}, OracleFrame{}).recall.has_value());
}

TEST_CASE("full reaches recall 1 and precision 1 against the oracle", "[oracle]") {
  const std::string data = TCBENCH_DATA_DIR;
  const std::vector<std::pair<std::string, SceneDesc>> scenes = {
      {"plate stack", test::scene_of({{"plate", "box:size=0.3x0.02x0.3,cells=4x2x4", Vec3(0, 0.01, 0), false, false,
                                       1.0, 4}})},
      {"sphere into torus", test::scene_of({{"torus", "meshes/torus_coarse.mesh"},
                                            {"sphere", "meshes/sphere_fine.mesh", Vec3(0.1, 0.02, 0.0), false, false,
                                             0.5}},
                                           data)},
      {"two boxes", test::scene_of({{"a", "box:size=0.2x0.2x0.2,cells=3x3x3"},
                                    {"b", "box:size=0.2x0.2x0.2,cells=4x2x3", Vec3(0.07, 0.05, 0.03)}})},
  };
  for (const auto& [name, scene] : scenes) {
    World world = build_world(scene);
    auto full = make_handler("full", scene);
    full->init(world, scene);
    double worst_depth_error = 0.0;
    int compared = 0;
    for (int s = 0; s < 20; ++s) {
      Budget unlimited = Budget::unlimited();
      full->step(world, unlimited);
      const OracleComparison c = compare_with_oracle(full->contacts(), compute_inside_oracle(world));
      if (c.recall) REQUIRE(*c.recall == 1.0);
      if (c.precision) REQUIRE(*c.precision == 1.0);
      if (c.depth_err_max) worst_depth_error = std::max(worst_depth_error, *c.depth_err_max);
      compared += c.recall.has_value();
      world.step(scene.dt_s);
    }
    CHECK(compared > 0);
    WARN(name << ": full against the oracle, largest depth error " << worst_depth_error << " m over 20 steps");
  }
}
