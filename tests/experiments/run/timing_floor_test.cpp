#include "experiments/run/timing_floor.hpp"

#include <catch2/catch.hpp>

#include <chrono>
#include <limits>

using namespace tcb;

TEST_CASE("the null handler spins its whole window and reports what it ran past", "[timing_floor]") {
  using Clock = std::chrono::steady_clock;
  for (const double window_ms : {0.05, 0.5, 2.0}) {
    const auto start = Clock::now();
    const double over_ms = null_handler_overshoot_ms(window_ms);
    const double elapsed_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    CHECK(over_ms >= 0.0);
    // It stopped no earlier than the window, and what it reports happened
    // inside the interval this test measured around it (no margin needed:
    // both are steady-clock differences and the function's reads lie between
    // this test's two).
    CHECK(elapsed_ms >= window_ms);
    CHECK(window_ms + over_ms <= elapsed_ms);
  }
}

TEST_CASE("a window that is not positive spins nothing", "[timing_floor]") {
  CHECK(null_handler_overshoot_ms(0.0) == 0.0);
  CHECK(null_handler_overshoot_ms(-1.0) == 0.0);
  CHECK(null_handler_overshoot_ms(std::numeric_limits<double>::quiet_NaN()) == 0.0);
}
