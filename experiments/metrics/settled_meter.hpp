#pragma once
/// How still a scene is once it has settled: over the second half of the run
/// (steps > steps_total / 2, like the jitter), the median of the per-step
/// largest vertex speed (chatter: a few vertices that keep moving show here
/// and not in the centre-of-mass jitter) and the kinetic energy of the
/// dynamic bodies. Summary settled_max_speed_median (m/s) and
/// settled_kinetic_energy {mean, max} (J); null when the run ended before its
/// second half (or was shortened to nothing).

#include "experiments/metrics/meter.hpp"

namespace tcb {

class SettledMeter final : public Meter {
 public:
  explicit SettledMeter(const RunSetup& run) : m_steps_total(run.steps_total) {}
  void on_step(StepContext& ctx) override;
  void summarize(Json& summary) const override;

 private:
  std::int64_t m_steps_total;
  std::vector<double> m_max_speed, m_kinetic_energy;
};

}  // namespace tcb
