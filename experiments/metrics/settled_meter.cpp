#include "experiments/metrics/settled_meter.hpp"

#include <cmath>

#include "experiments/metrics/distribution.hpp"

namespace tcb {

void SettledMeter::on_step(StepContext& ctx) {
  if (!in_settled_half(ctx.step, m_steps_total)) return;
  const double speed = ctx.max_speed_m_per_s;
  if (!std::isfinite(speed)) return;  // the stability meter stops such a run
  m_max_speed.push_back(speed);
  m_kinetic_energy.push_back(ctx.kinetic_energy_j);
}

void SettledMeter::summarize(Json& summary) const {
  if (m_max_speed.empty()) {
    summary["settled_max_speed_median"] = nullptr;
    summary["settled_kinetic_energy"] = nullptr;
    return;
  }
  summary["settled_max_speed_median"] = tcb::summarize(m_max_speed).p50;
  const Distribution e = tcb::summarize(m_kinetic_energy);
  summary["settled_kinetic_energy"] = {{"mean", e.mean}, {"max", e.max}};
}

}  // namespace tcb
