#include <catch2/catch.hpp>

#include "baselines/registry.hpp"
#include "sim/io/input_error.hpp"
#include "tests/method/test_worlds.hpp"

using namespace tcb;

namespace {
test::TestScene overlapping() {
  test::TestScene scene = test::scene_of({{"floor", "box:size=1x0.1x1,cells=4x1x4", Vec3::Zero(), true},
                                          {"cube", "box:size=0.1x0.1x0.1,cells=2x2x2", Vec3(0.0, 0.099, 0.0)}});
  scene.world.gravity_m_per_s2 = Vec3::Zero();
  return scene;
}

MethodSettings every_nth_settings(std::int64_t n, bool hold) {
  MethodSettings s(find_method("every_nth").settings);
  s.set("n", n);
  s.set("hold", hold);
  return s;
}
}  // namespace

TEST_CASE("every_nth runs a cycle every n-th step and holds or drops forces between", "[handler]") {
  for (bool hold : {true, false}) {
    INFO("hold " << hold);
    const test::TestScene scene = overlapping();
    World world = build_world(scene.world);
    const MethodSettings settings = every_nth_settings(3, hold);
    auto handler = make_handler("every_nth", &settings);
    handler->init(world, test::settings_of(world, scene));
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
      world.step(scene.world.dt_s);
    }
  }
}

TEST_CASE("the registry: every method builds with its defaults, labels name the settings that differ", "[registry]") {
  for (const MethodInfo& m : method_registry()) {
    INFO(m.name);
    CHECK(make_handler(m.name) != nullptr);
    CHECK(method_label(m.name, m.settings, MethodSettings(m.settings)) == m.name);
  }
  const auto& schema = find_method("every_nth").settings;
  CHECK(method_label("every_nth", schema, every_nth_settings(4, true)) == "every_nth(n=4)");
  CHECK(method_label("every_nth", schema, every_nth_settings(2, false)) == "every_nth(hold=false)");
  CHECK(method_label("every_nth", schema, every_nth_settings(8, false)) == "every_nth(n=8,hold=false)");
  CHECK_THROWS_WITH(make_handler("nope"), Catch::Matchers::Contains("unknown method 'nope'"));
}
