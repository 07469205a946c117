// Every registered method, with an unlimited budget, finds exactly the
// colliding points of brute_force on a set of small scenes. One test over the
// registry: a new baseline is tested by being registered. A method that
// reports the vertices of colliding tet pairs (fcl_tets) is compared on what
// it can be compared on: every point brute_force finds inside a tet is among
// its vertices, with the partner body brute_force names. A whole-body
// detector (neural) reports no points: it runs on a latent scene of its own
// below, its verdicts compared with brute_force's as an approximation.
#include <catch2/catch.hpp>

#include <filesystem>
#include <set>
#include <tuple>

#include "baselines/registry.hpp"
#include "tests/method/test_worlds.hpp"

using namespace tcb;
using test::Placed;

namespace {

using PointSet = std::set<std::tuple<int, int, int, int>>;  // (object, vertex, other, tet)

PointSet colliding_points(const std::string& method, const test::TestScene& scene, int steps_before) {
  World world = build_world(scene.world);
  auto reference = make_handler("full");
  reference->init(world, test::settings_of(world, scene));
  // Move the world with `full` first so the scenes are not only their initial
  // configuration; every method then sees the same state.
  for (int s = 0; s < steps_before; ++s) {
    Budget b = Budget::unlimited();
    reference->step(world, b);
    world.step(scene.world.dt_s);
  }
  auto handler = make_handler(method);
  handler->init(world, test::settings_of(world, scene));
  Budget unlimited = Budget::unlimited();
  handler->step(world, unlimited);
  PointSet points;
  for (const Contact& c : handler->contacts()) points.insert({c.object, c.vertex, c.other, c.tet});
  return points;
}


}  // namespace

TEST_CASE("every registered method finds exactly brute_force's colliding points", "[handler][registry]") {
  for (const auto& [scene_name, scene] : test::collision_scenes()) {
    for (int steps_before : {0, 20}) {
      const PointSet expected = colliding_points("brute_force", scene, steps_before);
      INFO(scene_name << " after " << steps_before << " steps: " << expected.size() << " colliding points");
      if (steps_before == 0) CHECK(!expected.empty());
      for (const MethodInfo& method : method_registry()) {
        if (!method.detects || method.reports == MethodInfo::Reports::BodyVerdicts) continue;
        INFO("method " << method.name);
        const PointSet found = colliding_points(method.name, scene, steps_before);
        if (method.reports == MethodInfo::Reports::InsidePoints) {
          CHECK(found == expected);
          continue;
        }
        // Plates exactly face on face overlap in no volume: no tet pair penetrates.
        if (scene_name.find("exactly face on face") != std::string::npos) continue;
        std::set<std::tuple<int, int, int>> vertices;
        for (const auto& [object, vertex, other, tet] : found) vertices.insert({object, vertex, other});
        std::size_t missing = 0;
        for (const auto& [object, vertex, other, tet] : expected) missing += !vertices.count({object, vertex, other});
        CHECK(missing == 0);
        CHECK(found.size() >= expected.size());
      }
    }
  }
}

TEST_CASE("the plate stack: the tie-break gives each shared face to one plate", "[handler]") {
  // 4 plates of 5x3x5 vertices: on each of the 3 interfaces the lower plate's
  // top vertices are inside the upper plate except the rows on its +x and +z
  // faces (delta points +x, +y, +z): 4 x 4 = 16 per interface, 48 in all, and
  // no upper plate's bottom vertex is inside the plate below.
  const test::TestScene scene =
      test::scene_of({{"plate", "box:size=0.3x0.02x0.3,cells=4x2x4", Vec3::Zero(), false, false, 1.0, 4}});
  const PointSet points = colliding_points("full", scene, 0);
  CHECK(points.size() == 48);
  for (const auto& [object, vertex, other, tet] : points) CHECK(other == object + 1);
}

TEST_CASE("neural, approximate: its per-frame verdicts agree with brute_force's on the committed finger path",
          "[handler][registry][neural]") {
  // Not an equality: the network is a learned approximation (about 0.9 of
  // held-out codes right, `tcbench neural experiment`). The committed model
  // and path of experiments/scenes/finger_curl.toml; every 20th of 2,000
  // steps. Measured when written: 94 of 100 frames agree.
  const std::filesystem::path scenes = std::filesystem::path(TCBENCH_DATA_DIR) / ".." / "experiments" / "scenes";
  int ran = 0;
  for (const MethodInfo& method : method_registry()) {
    if (method.reports != MethodInfo::Reports::BodyVerdicts) continue;
    ++ran;
    INFO("method " << method.name);
    test::TestScene scene = test::scene_of({{"finger", "finger:finger_small", Vec3::Zero(), true, true}});
    scene.world.objects[0].latent_path = "finger_curl_path.csv";
    scene.world.objects[0].latent_model = "finger_small_active.json";
    scene.world.objects[0].base_dir = scenes;
    World world = build_world(scene.world);
    auto exact = make_handler("brute_force");
    auto learned = make_handler(method.name);
    exact->init(world, test::settings_of(world, scene));
    learned->init(world, test::settings_of(world, scene));
    int frames = 0, agree = 0, colliding = 0;
    for (int step = 1; step <= 2000; ++step) {
      if (step % 20 == 0) {
        Budget a = Budget::unlimited(), b = Budget::unlimited();
        exact->step(world, a);
        learned->step(world, b);
        const bool truth = exact->self_collision_verdicts(world)[0];
        colliding += truth;
        agree += truth == static_cast<bool>(learned->self_collision_verdicts(world)[0]);
        ++frames;
      }
      world.step(scene.world.dt_s);
    }
    INFO(agree << " of " << frames << " frames agree; brute_force finds self-collision in " << colliding);
    CHECK(colliding >= 20);  // the path folds the finger onto itself, and not always
    CHECK(colliding <= 80);
    CHECK(agree >= 85);
  }
  CHECK(ran == 1);  // neural is registered and was compared
}
