#pragma once
/// The force a haptic device would render: the contact force the step
/// actually applied to the driven objects (World::driven_contact_force_n:
/// explicit forces and, under implicit response, the solved link forces), N.
/// Columns probe_force_x, probe_force_y, probe_force_z (empty without a driven
/// object). Summary probe_force_max (largest |F|, N) and
/// probe_force_change_rms: the root mean square of |F| at step i+1 minus |F|
/// at step i over consecutive steps, N per step, the roughness the device
/// would render (the student haptic system's force jitter); null without a
/// driven object or with fewer than two steps.

#include <optional>

#include "experiments/metrics/meter.hpp"

namespace tcb {

class ProbeForceMeter final : public Meter {
 public:
  std::vector<ColumnSpec> columns() const override;
  void on_step(StepContext& ctx) override;
  void summarize(Json& summary) const override;

 private:
  std::optional<double> m_max, m_last;
  double m_change_sum_sq = 0.0;
  std::int64_t m_changes = 0;
};

}  // namespace tcb
