#include "oracle/tunneling.hpp"

#include <catch2/catch.hpp>

#include "tests/method/test_worlds.hpp"

using namespace tcb;

TEST_CASE("tunnelling counts pairs whose centre ended inside the other", "[oracle]") {
  const SceneDesc scene = test::scene_of({{"a", "box:size=0.2x0.2x0.2,cells=2x2x2"},
                                          {"b", "box:size=0.2x0.2x0.2,cells=2x2x2", Vec3(0.5, 0.0, 0.0)},
                                          {"c", "box:size=0.2x0.2x0.2,cells=2x2x2", Vec3(0.05, 0.0, 0.0)}});
  World moved = build_world(scene);
  const BodyPairs initial = interlocked_pairs(moved);  // a and c already interlocked: never counted
  CHECK(initial == BodyPairs{{0, 2}});
  CHECK(count_tunneling(initial, moved).pairs == 0);
  for (Vec3& p : moved.bodies[1].x_m) p.x() -= 0.45;  // b's centre now inside a (and c)
  const TunnelingResult r = count_tunneling(initial, moved);
  CHECK(r.pairs == 2);
  CHECK(r.unmeasured.empty());
}
