#include "experiments/metrics/stability_meter.hpp"

#include <fmt/format.h>

#include <cmath>

namespace tcb {

void StabilityMeter::on_step(StepContext& ctx) {
  const double speed = ctx.max_speed_m_per_s;
  if (std::isnan(speed)) {
    ++m_nan_steps;
    ctx.unstable = fmt::format("non-finite position or velocity at step {}", ctx.step);
  } else if (speed > m_max_speed_m_per_s) {
    ctx.unstable = fmt::format("a vertex moves at {:.4g} m/s at step {}, above the scene's max_speed {:.4g} m/s",
                               speed, ctx.step, m_max_speed_m_per_s);
  }
}

}  // namespace tcb
