// plates20 and cube_drop with `full` and `interruptible` without a budget for
// each scene's whole length (plates20: 2000 steps, about 75 s a method in
// Release): both give the same forces on every step, and with them the
// 20-plate stack stays standing and no plate passes into the one below.
// The two claims share one test because they need the same `full` run, the
// longest of the suite; checked apart, it ran twice.
#include <algorithm>
#include <cmath>
#include <string>

#include <catch2/catch.hpp>

#include "baselines/registry.hpp"
#include "experiments/scene/scene_file.hpp"

using namespace tcb;

namespace {
double mean_y_m(const Body& b) {
  double y = 0.0;
  for (const Vec3& p : b.x_m) y += p.y();
  return y / static_cast<double>(b.x_m.size());
}
}  // namespace

TEST_CASE("interruptible without a budget gives full's forces on every step of plates20 and cube_drop, "
          "and full keeps the 20-plate stack standing",
          "[scene][slow]") {
  for (const char* name : {"cube_drop", "plates20"}) {
    INFO(name);
    const SceneDesc scene = load_scene_file(resolve_scene(name, default_scene_dirs()));
    World a = build_world(scene.world), b = build_world(scene.world);
    auto full = make_handler("full");
    auto interruptible = make_handler("interruptible");
    const CollisionSettings settings = resolve_collision_settings(a, scene.collision, scene.world.dt_s);
    CHECK(settings.warnings.empty());
    full->init(a, settings);
    interruptible->init(b, settings);
    const bool stack = std::string(name) == "plates20";
    double smallest_gap_m = 1e9;
    for (std::int64_t s = 0; s < scene.steps; ++s) {
      Budget ua = Budget::unlimited(), ub = Budget::unlimited();
      full->step(a, ua);
      interruptible->step(b, ub);
      for (std::size_t i = 0; i < a.bodies.size(); ++i)
        REQUIRE(a.bodies[i].contact_force_n == b.bodies[i].contact_force_n);
      a.step(scene.world.dt_s);
      b.step(scene.world.dt_s);
      REQUIRE(std::isfinite(a.max_speed_m_per_s()));
      if (stack && s % 50 == 49)
        for (std::size_t i = 0; i + 1 < a.bodies.size(); ++i)
          smallest_gap_m = std::min(smallest_gap_m, mean_y_m(a.bodies[i + 1]) - mean_y_m(a.bodies[i]));
    }
    for (std::size_t i = 0; i < a.bodies.size(); ++i) CHECK(a.bodies[i].x_m == b.bodies[i].x_m);
    if (stack) {
      // full's stack stands: centres stay about one plate thickness apart
      // (penetration at rest is ~1 mm), the top plate near its height, at rest.
      const double thickness_m = 0.02;
      const double top_m = mean_y_m(a.bodies.back());
      INFO("smallest centre distance " << smallest_gap_m << " m, top plate centre " << top_m << " m");
      CHECK(smallest_gap_m > 0.9 * thickness_m);
      CHECK(top_m > 0.9 * (19.5 * thickness_m));
      CHECK(a.max_speed_m_per_s() < 0.05);
    }
  }
}
