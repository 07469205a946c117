#pragma once
/// Whether the run is still sane after each step: a non-finite position or
/// velocity, or a vertex faster than the scene's max_speed, marks it
/// unstable (StepContext::unstable; the run stops and keeps its files).
/// Summary nan_steps (the speed itself is the dynamics meter's column).

#include "experiments/metrics/meter.hpp"

namespace tcb {

class StabilityMeter final : public Meter {
 public:
  explicit StabilityMeter(const RunSetup& run) : m_max_speed_m_per_s(run.scene.max_speed_m_per_s) {}
  void on_step(StepContext& ctx) override;
  void summarize(Json& summary) const override { summary["nan_steps"] = m_nan_steps; }

 private:
  double m_max_speed_m_per_s;
  std::int64_t m_nan_steps = 0;
};

}  // namespace tcb
