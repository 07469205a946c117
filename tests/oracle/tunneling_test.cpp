#include "oracle/tunneling.hpp"

#include <catch2/catch.hpp>

#include "tests/method/test_worlds.hpp"

using namespace tcb;

TEST_CASE("tunnelling counts pairs whose centre ended inside the other", "[oracle]") {
  const test::TestScene scene = test::scene_of({{"a", "box:size=0.2x0.2x0.2,cells=2x2x2"},
                                          {"b", "box:size=0.2x0.2x0.2,cells=2x2x2", Vec3(0.5, 0.0, 0.0)},
                                          {"c", "box:size=0.2x0.2x0.2,cells=2x2x2", Vec3(0.05, 0.0, 0.0)}});
  World moved = build_world(scene.world);
  TunnelingJudge meter(moved);
  CHECK(meter.interlocked() == BodyPairs{{0, 2}});  // a and c already interlocked: never counted
  for (Vec3& p : moved.bodies[1].x_m) p.x() -= 0.45;  // b's centre now inside a (and c)
  const TunnelingResult r = meter.finish(moved);
  CHECK(r.pairs == 2);
  CHECK(r.unmeasured.empty());
}

TEST_CASE("tunnelling counts an overlap above half the smaller object, even when it passed", "[oracle]") {
  const test::TestScene scene = test::scene_of({{"big", "box:size=0.4x0.4x0.4,cells=2x2x2"},
                                          {"small", "box:size=0.1x0.1x0.1,cells=2x2x2", Vec3(0.5, 0.0, 0.0)}});
  World world = build_world(scene.world);
  TunnelingJudge meter(world);
  CHECK(meter.interlocked().empty());
  // Small overlaps big by 0.04 of its 0.1 width: 40% of its volume, not tunnelling.
  for (Vec3& p : world.bodies[1].x_m) p.x() -= 0.5 - 0.25 + 0.04;
  meter.record_overlaps(compute_overlap_volumes(world));
  // Then by 0.06 (60%): tunnelling, judged from this frame alone.
  for (Vec3& p : world.bodies[1].x_m) p.x() -= 0.02;
  meter.record_overlaps(compute_overlap_volumes(world));
  // It moves away again before the end: the pair still counts, once.
  for (Vec3& p : world.bodies[1].x_m) p.x() += 1.0;
  CHECK(meter.finish(world).pairs == 1);
}
