// The project's own random numbers: SplitMix64's published first output,
// uniform draws in [-1, 1), and independence of draw order.
#include "sim/random/counter_random.hpp"

#include <catch2/catch.hpp>

using namespace tcb;

TEST_CASE("mix64 is SplitMix64's output function", "[random]") {
  // SplitMix64 seeded with 0 first returns 0xE220A8397B1DCDAF (Vigna's reference implementation).
  CHECK(mix64(0) == 0xE220A8397B1DCDAFull);
}

TEST_CASE("uniform_pm1 lies in [-1, 1), is centred and depends only on (seed, stream, index)", "[random]") {
  double sum = 0.0, lowest = 1.0, highest = -1.0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const double u = uniform_pm1(7, 3, static_cast<std::uint64_t>(i));
    REQUIRE(u >= -1.0);
    REQUIRE(u < 1.0);
    sum += u;
    lowest = std::min(lowest, u);
    highest = std::max(highest, u);
  }
  CHECK(std::abs(sum / n) < 0.01);  // the mean of n uniforms has sd 0.0018
  CHECK(lowest < -0.999);
  CHECK(highest > 0.999);
  CHECK(uniform_pm1(7, 3, 42) == uniform_pm1(7, 3, 42));
  CHECK(uniform_pm1(7, 3, 42) != uniform_pm1(8, 3, 42));
  CHECK(uniform_pm1(7, 3, 42) != uniform_pm1(7, 4, 42));
}
