#pragma once
/// Jitter of a resting scene (summary jitter, m/s; the paper shows that
/// handling collisions every other step makes a resting stack jitter).
/// Measure "vertical_velocity_rms": the root mean square, over the steps of
/// the second half of the run and over the dynamic bodies, of each body's
/// centre-of-mass vertical (y) velocity, in m/s. A scene opts in with
/// [metrics] jitter = "vertical_velocity_rms"; other scenes report null.

#include "experiments/metrics/meter.hpp"

namespace tcb {

class JitterMeter final : public Meter {
 public:
  JitterMeter() = default;
  explicit JitterMeter(const RunSetup& run)
      : m_enabled(!run.scene.jitter_measure.empty()), m_steps_total(run.steps_total) {}
  void on_step(StepContext& ctx) override { record(ctx.world, ctx.step, m_steps_total); }
  void summarize(Json& summary) const override;
  /// Call once per step with the step number (1-based) and the run's length.
  void record(const World& world, std::int64_t step, std::int64_t steps_total);
  /// RMS in m/s; 0 samples gives 0.
  double rms_m_per_s() const;
  std::int64_t samples() const { return m_samples; }

 private:
  bool m_enabled = true;
  std::int64_t m_steps_total = 0;
  double m_sum_sq = 0.0;
  std::int64_t m_samples = 0;
};

}  // namespace tcb
