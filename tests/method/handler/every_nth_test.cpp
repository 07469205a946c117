#include <catch2/catch.hpp>

#include "baselines/registry.hpp"
#include "sim/io/input_error.hpp"
#include "tests/method/test_worlds.hpp"

using namespace tcb;

namespace {
SceneDesc overlapping(const std::string& n, bool hold) {
  SceneDesc scene = test::scene_of({{"floor", "box:size=1x0.1x1,cells=4x1x4", Vec3::Zero(), true},
                                    {"cube", "box:size=0.1x0.1x0.1,cells=2x2x2", Vec3(0.0, 0.099, 0.0)}});
  scene.gravity_m_per_s2 = Vec3::Zero();
  scene.methods["every_nth"]["n"] = {std::stod(n), "test"};
  scene.methods["every_nth"]["hold"] = {hold, "test"};
  return scene;
}
}  // namespace

TEST_CASE("every_nth runs a cycle every n-th step and holds or drops forces between", "[handler]") {
  for (bool hold : {true, false}) {
    INFO("hold " << hold);
    const SceneDesc scene = overlapping("3", hold);
    World world = build_world(scene);
    auto handler = make_handler("every_nth", scene);
    handler->init(world, scene);
    for (int s = 0; s < 7; ++s) {
      Budget b = Budget::unlimited();
      const StepReport r = handler->step(world, b);
      const bool cycle = s % 3 == 0;
      CHECK(r.cycle_done == cycle);
      CHECK(r.cycle == s / 3 + 1);
      CHECK((r.work_units > 0) == cycle);
      CHECK(r.colliding_points > 0);
      double applied = 0.0;
      for (const Vec3& f : world.bodies[1].contact_force_n) applied += f.norm();
      if (cycle) {
        CHECK(r.exact_forces > 0);
        CHECK(applied > 0.0);
      } else if (hold) {
        CHECK(r.exact_forces == 0);
        CHECK(r.estimated_forces > 0);  // held forces are not from this step's depths
        CHECK(applied > 0.0);
      } else {
        CHECK(applied == 0.0);
      }
      world.step(scene.dt_s);
    }
  }
}

TEST_CASE("method settings are validated", "[handler]") {
  SceneDesc scene = overlapping("0", true);
  CHECK_THROWS_AS(make_handler("every_nth", scene), InputError);
  scene = overlapping("2.5", true);
  CHECK_THROWS_AS(make_handler("every_nth", scene), InputError);
  scene = overlapping("2", true);
  scene.methods["every_nth"]["m"] = {1.0, "scene.toml:7"};
  try {
    make_handler("every_nth", scene);
    FAIL("accepted an unknown setting");
  } catch (const InputError& e) {
    CHECK(e.file() == "scene.toml");
    CHECK(e.line() == 7);
    CHECK_THAT(e.what(), Catch::Matchers::Contains("unknown setting 'm'"));
  }
  CHECK_THROWS_WITH(make_handler("nope", scene), Catch::Matchers::Contains("unknown method 'nope'"));
}
