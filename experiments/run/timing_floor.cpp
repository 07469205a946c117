#include "experiments/run/timing_floor.hpp"

#include <chrono>

namespace tcb {

double null_handler_overshoot_ms(double window_ms) {
  if (!(window_ms > 0.0)) return 0.0;
  using Clock = std::chrono::steady_clock;
  const std::chrono::duration<double, std::milli> window(window_ms);
  const Clock::time_point start = Clock::now();
  Clock::time_point now = start;
  while (now - start < window) now = Clock::now();
  return std::chrono::duration<double, std::milli>(now - start - window).count();
}

}  // namespace tcb
