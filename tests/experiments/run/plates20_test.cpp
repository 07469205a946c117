// plates20 with `full` for the scene's whole length (2000 steps, ~90 s): the
// stack stays standing and no plate passes into the one below.
#include <catch2/catch.hpp>

#include "baselines/registry.hpp"
#include "experiments/scene/scene_file.hpp"

using namespace tcb;

TEST_CASE("plates20: full keeps the 20-plate stack standing for the whole scene", "[scene][slow]") {
  const SceneDesc scene = load_scene_file(resolve_scene("plates20", default_scene_dirs()));
  World world = build_world(scene.world);
  auto handler = make_handler("full");
  const CollisionSettings settings = resolve_collision_settings(world, scene.collision, scene.world.dt_s);
  handler->init(world, settings);
  CHECK(settings.warnings.empty());
  const double thickness = 0.02;
  const auto mean_y = [&](const Body& b) {
    double y = 0.0;
    for (const Vec3& p : b.x_m) y += p.y();
    return y / static_cast<double>(b.x_m.size());
  };
  double smallest_gap = 1e9, final_top = 0.0;
  for (std::int64_t s = 0; s < scene.steps; ++s) {
    Budget unlimited = Budget::unlimited();
    handler->step(world, unlimited);
    world.step(scene.world.dt_s);
    REQUIRE(std::isfinite(world.max_speed_m_per_s()));
    if (s % 50 == 49) {
      for (std::size_t i = 0; i + 1 < world.bodies.size(); ++i)
        smallest_gap = std::min(smallest_gap, mean_y(world.bodies[i + 1]) - mean_y(world.bodies[i]));
    }
  }
  final_top = mean_y(world.bodies.back());
  INFO("smallest centre distance " << smallest_gap << " m, top plate centre " << final_top << " m");
  // Centres stay about one thickness apart (penetration at rest is ~1 mm).
  CHECK(smallest_gap > 0.9 * thickness);
  CHECK(final_top > 0.9 * (19.5 * thickness));
  CHECK(world.max_speed_m_per_s() < 0.05);
}

TEST_CASE("interruptible without a budget gives full's forces on every step of plates20 and cube_drop",
          "[scene][slow]") {
  for (const char* name : {"cube_drop", "plates20"}) {
    INFO(name);
    const SceneDesc scene = load_scene_file(resolve_scene(name, default_scene_dirs()));
    World a = build_world(scene.world), b = build_world(scene.world);
    auto full = make_handler("full");
    auto interruptible = make_handler("interruptible");
    const CollisionSettings settings = resolve_collision_settings(a, scene.collision, scene.world.dt_s);
    full->init(a, settings);
    interruptible->init(b, settings);
    for (std::int64_t s = 0; s < scene.steps; ++s) {
      Budget ua = Budget::unlimited(), ub = Budget::unlimited();
      full->step(a, ua);
      interruptible->step(b, ub);
      for (std::size_t i = 0; i < a.bodies.size(); ++i)
        REQUIRE(a.bodies[i].contact_force_n == b.bodies[i].contact_force_n);
      a.step(scene.world.dt_s);
      b.step(scene.world.dt_s);
    }
    for (std::size_t i = 0; i < a.bodies.size(); ++i) CHECK(a.bodies[i].x_m == b.bodies[i].x_m);
  }
}
