#include "experiments/metrics/latency.hpp"

#include <catch2/catch.hpp>

#include "tests/method/test_worlds.hpp"

using namespace tcb;

TEST_CASE("latency: steps from first true penetration to the first depth-based force", "[metrics]") {
  const World world = build_world(test::scene_of({{"a", "box:size=0.2x0.2x0.2,cells=1x1x1"}}));
  LatencyMeter meter(world);
  const auto inside = [](std::vector<std::int32_t> vertices) {
    OracleFrame f;
    for (auto v : vertices) f.inside.push_back({0, v, 1, 0.01});
    return f;
  };
  meter.record_oracle(1, inside({0, 1}));
  meter.record_forces(1, {{0, 0}});          // vertex 0 served at once: latency 0
  meter.record_oracle(2, inside({0, 1, 2}));
  meter.record_forces(2, {{0, 0}});          // served again: not a new latency
  meter.record_oracle(3, inside({0, 1, 2}));
  meter.record_forces(3, {{0, 1}, {0, 7}});  // vertex 1 after 2 steps; 7 never penetrated: ignored
  meter.record_oracle(4, inside({0}));       // vertex 2 left unserved
  meter.record_oracle(5, inside({0, 2}));    // vertex 2: a new episode
  meter.record_forces(6, {{0, 2}});          // served one step later
  CHECK(meter.latencies() == std::vector<double>{0.0, 2.0, 1.0});
  CHECK(meter.unserved() == 1);
}
