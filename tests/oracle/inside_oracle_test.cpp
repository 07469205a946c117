// The oracle against analytic answers, and full against the oracle.
#include "oracle/inside_oracle.hpp"

#include <catch2/catch.hpp>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <cmath>
#include <map>
#include <tuple>

#include "baselines/registry.hpp"
#include "experiments/metrics/oracle_comparison.hpp"
#include "experiments/scene/scene_file.hpp"
#include "tests/method/test_worlds.hpp"

using namespace tcb;

TEST_CASE("oracle: two axis-aligned boxes overlapping by a known box", "[oracle]") {
  // A spans [-0.1, 0.1]^3 on a 0.05 grid; B spans [0, 0.2]^3. A's vertices with
  // all coordinates in {0.05, 0.1} are inside B, at depth min(coordinates);
  // those with a 0 coordinate and the rest >= 0 lie on B's surface.
  const test::TestScene scene = test::scene_of({{"a", "box:size=0.2x0.2x0.2,cells=4x4x4"},
                                          {"b", "box:size=0.2x0.2x0.2,cells=3x3x3", Vec3(0.1, 0.1, 0.1)}});
  const World world = build_world(scene.world);
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
  const test::TestScene scene = test::scene_of(
      {{"big", "box:size=1x1x1,cells=2x2x2", Vec3::Zero(), true}, {"small", "box:size=0.2x0.2x0.2,cells=2x2x2"}});
  const World world = build_world(scene.world);
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
  CHECK(c.self_points == 0);
  CHECK(c.self_depth_errors.empty());
  CHECK_FALSE(compare_with_oracle({}, OracleFrame{}).recall.has_value());
  // Self-collision points (other == object): one with a true depth, one
  // without; only the first has an error, kept apart as well.
  oracle.inside.push_back({0, 4, 0, 0.03});
  oracle.inside.push_back({0, 5, 0, std::nan("")});
  method.resize(5);
  method[3].object = 0, method[3].vertex = 4, method[3].other = 0, method[3].depth_source = DepthSource::Border,
  method[3].depth_m = 0.01;
  method[4].object = 0, method[4].vertex = 5, method[4].other = 0, method[4].depth_source = DepthSource::Border,
  method[4].depth_m = 0.01;
  const OracleComparison self = compare_with_oracle(method, oracle);
  CHECK(self.self_points == 2);
  CHECK(self.self_points_with_depth == 1);
  REQUIRE(self.self_depth_errors.size() == 1);
  CHECK(self.self_depth_errors[0] == Approx(0.02));
  CHECK(self.depth_errors.size() == 2);
}

namespace {

struct OracleRun {
  int compared = 0;  ///< oracle frames where recall was defined
  double worst_depth_error_m = 0.0;
  std::int64_t method_points = 0, oracle_points = 0;
  std::int64_t self_points = 0, self_with_depth = 0;
  std::vector<double> self_depth_errors;
};

// Runs `full` for `steps` steps with the oracle every `every` steps; every
// defined recall and precision must be exactly 1.
OracleRun full_against_oracle(const test::TestScene& scene, int steps, int every, const std::string& method = "full") {
  World world = build_world(scene.world);
  auto full = make_handler(method);
  full->init(world, test::settings_of(world, scene));
  OracleRun run;
  for (int s = 1; s <= steps; ++s) {
    Budget unlimited = Budget::unlimited();
    full->step(world, unlimited);
    if (s % every == 0) {
      const OracleComparison c = compare_with_oracle(full->contacts(), compute_inside_oracle(world));
      INFO("step " << s);
      if (c.recall) REQUIRE(*c.recall == 1.0);
      if (c.precision) REQUIRE(*c.precision == 1.0);
      if (c.depth_err_max) run.worst_depth_error_m = std::max(run.worst_depth_error_m, *c.depth_err_max);
      run.compared += c.recall.has_value();
      run.method_points += static_cast<std::int64_t>(full->contacts().size());
      run.oracle_points += c.oracle_points;
      run.self_points += c.self_points;
      run.self_with_depth += c.self_points_with_depth;
      run.self_depth_errors.insert(run.self_depth_errors.end(), c.self_depth_errors.begin(), c.self_depth_errors.end());
    }
    world.step(scene.world.dt_s);
    REQUIRE(std::isfinite(world.max_speed_m_per_s()));
  }
  return run;
}

// A committed scene file's world and collision table, as the tests here use them.
test::TestScene committed(const std::string& name) {
  const SceneDesc s = load_scene_file(resolve_scene(name, default_scene_dirs()));
  return {s.world, s.collision};
}

}  // namespace

TEST_CASE("full reaches recall 1 and precision 1 against the oracle", "[oracle]") {
  const std::string data = TCBENCH_DATA_DIR;
  test::TestScene dogs = test::scene_of({{"dog", std::string(TCBENCH_SHARED_MESHES) + "/dog.mesh", Vec3::Zero(), false,
                                    false, 0.01},
                                   {"dog2", std::string(TCBENCH_SHARED_MESHES) + "/dog.mesh", Vec3(0.05, 0.4, 0.1),
                                    false, false, 0.01}});
  const std::vector<std::tuple<std::string, test::TestScene, int, int>> scenes = {
      {"plate stack", test::scene_of({{"plate", "box:size=0.3x0.02x0.3,cells=4x2x4", Vec3(0, 0.01, 0), false, false,
                                       1.0, 4}}), 20, 1},
      {"sphere into torus", test::scene_of({{"torus", "meshes/torus_coarse.mesh"},
                                            {"sphere", "meshes/sphere_fine.mesh", Vec3(0.1, 0.02, 0.0), false, false,
                                             0.5}},
                                           data), 20, 1},
      {"two boxes", test::scene_of({{"a", "box:size=0.2x0.2x0.2,cells=3x3x3"},
                                    {"b", "box:size=0.2x0.2x0.2,cells=4x2x3", Vec3(0.07, 0.05, 0.03)}}), 20, 1},
      {"plates20", committed("plates20"), 300, 15},
      {"two dogs (open surfaces: decided by tets)", dogs, 6, 1},
  };
  for (const auto& [name, scene, steps, every] : scenes) {
    INFO(name);
    const OracleRun run = full_against_oracle(scene, steps, every);
    CHECK(run.compared > 0);
    WARN(name << ": full against the oracle on " << run.compared << " frames, " << run.oracle_points
              << " inside points, largest depth error " << run.worst_depth_error_m << " m");
  }
}

TEST_CASE("cube_drop has no object pairs: the oracle and full both find nothing", "[oracle]") {
  const OracleRun run = full_against_oracle(committed("cube_drop"), 400, 20);
  CHECK(run.compared == 0);
  CHECK(run.oracle_points == 0);
  CHECK(run.method_points == 0);
}

TEST_CASE("true depth: the AABB tree (inexact constructions) against the exact kernel", "[oracle]") {
  const test::TestScene scene = test::scene_of(
      {{"torus", "meshes/torus_coarse.mesh"}, {"sphere", "meshes/sphere_fine.mesh", Vec3(0.1, 0.02, 0.0), false, false, 0.5}},
      TCBENCH_DATA_DIR);
  const World world = build_world(scene.world);
  const OracleFrame frame = compute_inside_oracle(world);
  using E = CGAL::Exact_predicates_exact_constructions_kernel;
  int checked = 0;
  double worst = 0.0;
  for (const OraclePoint& p : frame.inside) {
    if (p.object != 1 || checked >= 25) continue;
    const Body& torus = world.bodies[0];
    const auto point = [](const Vec3& x) { return E::Point_3(x.x(), x.y(), x.z()); };
    const E::Point_3 q = point(world.bodies[1].x_m[p.vertex]);
    E::FT best = -1;
    for (const Triangle& f : torus.mesh->surface) {
      const E::FT d2 = CGAL::squared_distance(q, E::Triangle_3(point(torus.x_m[f[0]]), point(torus.x_m[f[1]]),
                                                                point(torus.x_m[f[2]])));
      if (best < 0 || d2 < best) best = d2;
    }
    const double exact = std::sqrt(CGAL::to_double(best));
    worst = std::max(worst, std::abs(p.depth_m - exact));
    ++checked;
  }
  CHECK(checked == 25);
  WARN("true depth against the exact kernel: largest difference " << worst << " m over " << checked << " points");
  CHECK(worst < 1e-14);
}

TEST_CASE("folding_bar: brute_force and full find exactly the oracle's self-collision inside set", "[oracle][self]") {
  // The bar buckles under its own weight, folds onto itself and inverts
  // some of its tets on the way (up to ~12 %): the method counts an inverted
  // tet's region as the oracle does (perturbed_predicates.hpp).
  const test::TestScene scene = committed("folding_bar");
  for (const std::string method : {"brute_force", "full"}) {
    INFO(method);
    const OracleRun run = full_against_oracle(scene, 1500, 25, method);
    CHECK(run.compared > 20);
    CHECK(run.oracle_points > 500);  // it really folds onto itself
    // Its 15 parts give many of those points a true depth (self_depth.hpp),
    // and the method gives them one too.
    CHECK(run.self_with_depth > 0);
    CHECK(run.self_depth_errors.size() > 0);
    double sum = 0.0, worst = 0.0;
    for (const double e : run.self_depth_errors) sum += e, worst = std::max(worst, e);
    WARN(method << " on folding_bar: " << run.self_with_depth << " of " << run.self_points
                << " self-collision points have a true depth; depth error mean "
                << sum / static_cast<double>(run.self_depth_errors.size()) << " m, max " << worst << " m");
  }
}
