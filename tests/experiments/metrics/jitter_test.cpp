#include "experiments/metrics/jitter.hpp"

#include <catch2/catch.hpp>

#include "tests/method/test_worlds.hpp"

using namespace tcb;

TEST_CASE("jitter: RMS of body vertical velocity over the second half", "[metrics]") {
  const test::TestScene scene = test::scene_of({{"a", "box:size=0.2x0.2x0.2,cells=2x2x2"},
                                          {"b", "box:size=0.2x0.2x0.2,cells=2x2x2", Vec3(0.5, 0, 0)}});
  World world = build_world(scene.world);
  JitterMeter meter;
  for (std::int64_t step = 1; step <= 10; ++step) {
    // a moves up and down at 0.3 m/s, b is still; horizontal motion is ignored.
    const double vy = step % 2 ? 0.3 : -0.3;
    for (Vec3& v : world.bodies[0].v_m_per_s) v = Vec3(5.0, vy, 0.0);
    for (Vec3& v : world.bodies[1].v_m_per_s) v = Vec3(-2.0, 0.0, 1.0);
    if (step <= 5) world.bodies[0].v_m_per_s[0].y() = 100.0;  // the first half never counts
    meter.record(world, step, 10);
  }
  CHECK(meter.samples() == 10);  // 5 steps x 2 bodies
  CHECK(meter.rms_m_per_s() == Approx(std::sqrt(0.3 * 0.3 / 2.0)));
}
