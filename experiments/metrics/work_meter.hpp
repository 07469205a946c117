#pragma once
/// What the handler did, from its StepReport: work units, the cycle worked
/// on and whether it completed, and how many points got which kind of force.
/// Columns work_units, cycle, cycle_done, colliding_points, exact_forces,
/// estimated_forces. Summary work_units_total, colliding_points_max,
/// depth_fallback_points, and cycle_steps {mean, max}: how many steps a
/// completed cycle spanned (null when none completed).

#include "experiments/metrics/meter.hpp"

namespace tcb {

class WorkMeter final : public Meter {
 public:
  std::vector<ColumnSpec> columns() const override;
  void on_step(StepContext& ctx) override;
  void summarize(Json& summary) const override;

 private:
  std::uint64_t m_work_total = 0;
  std::int64_t m_depth_fallback = 0, m_colliding_max = 0, m_cycle_start_step = 1;
  std::vector<double> m_cycle_lengths;
};

}  // namespace tcb
