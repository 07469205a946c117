#include "method/handler/budget.hpp"

namespace tcb {

ClockMs steady_clock_ms() {
  return [] {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
  };
}

}  // namespace tcb
