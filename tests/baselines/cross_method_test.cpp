// Every registered method, with an unlimited budget, finds exactly the
// colliding points of brute_force on a set of small scenes. One test over the
// registry: a new baseline is tested by being registered.
#include <catch2/catch.hpp>

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

std::vector<std::pair<std::string, test::TestScene>> scenes() {
  const std::string data = TCBENCH_DATA_DIR;
  std::vector<std::pair<std::string, test::TestScene>> s;
  s.emplace_back("two overlapping boxes",
                 test::scene_of({{"a", "box:size=0.2x0.2x0.2,cells=3x3x3"},
                                 {"b", "box:size=0.2x0.2x0.2,cells=4x2x3", Vec3(0.07, 0.05, 0.03)}}));
  s.emplace_back("plate stack, exactly face on face and vertex on vertex",
                 test::scene_of({{"plate", "box:size=0.3x0.02x0.3,cells=4x2x4", Vec3::Zero(), false, false, 1.0, 4}}));
  s.emplace_back("sphere into torus", test::scene_of({{"torus", "meshes/torus_coarse.mesh"},
                                                      {"sphere", "meshes/sphere_fine.mesh", Vec3(0.1, 0.02, 0.0),
                                                       false, false, 0.5}},
                                                     data));
  s.emplace_back("passive obstacle",
                 test::scene_of({{"floor", "box:size=1x0.1x1,cells=5x1x5", Vec3::Zero(), true},
                                 {"cube", "box:size=0.2x0.2x0.2,cells=3x3x3", Vec3(0.1, 0.12, 0.0)}}));
  s.emplace_back("self-collision of a folded pair",
                 test::scene_of({{"self", "box:size=0.2x0.2x0.2,cells=2x2x2", Vec3::Zero(), false, true},
                                 {"other", "box:size=0.2x0.2x0.2,cells=2x2x2", Vec3(0.05, 0.05, 0.05)}}));
  return s;
}

}  // namespace

TEST_CASE("every registered method finds exactly brute_force's colliding points", "[handler][registry]") {
  for (const auto& [scene_name, scene] : scenes()) {
    for (int steps_before : {0, 20}) {
      const PointSet expected = colliding_points("brute_force", scene, steps_before);
      INFO(scene_name << " after " << steps_before << " steps: " << expected.size() << " colliding points");
      if (steps_before == 0) CHECK(!expected.empty());
      for (const MethodInfo& method : method_registry()) {
        if (!method.detects) continue;
        INFO("method " << method.name);
        CHECK(colliding_points(method.name, scene, steps_before) == expected);
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
