#pragma once
/// Where handling time goes (issue 20's stage costs), from the handler's
/// StepReport::stages (method/handler/stage_costs.hpp). Columns
/// stage_<stage>_ms for every stage, apply included, stage_<stage>_work for
/// the cycle's stages (apply charges none), and interrupted_stage
/// (the index of the stage the cycle stopped in, in the order of
/// cost_stage_name(); empty when it was not interrupted). Summary `stages`:
/// per stage {ms_mean (per step, every step counted), ms_max, work_mean,
/// interrupted_steps}, and `stages_ms_unaccounted_mean`: handling time the
/// stages do not cover (the call into the handler and its clock reads), per
/// step. A method without a cycle reports zeros.

#include <array>

#include "experiments/metrics/meter.hpp"

namespace tcb {

class StageMeter final : public Meter {
 public:
  std::vector<ColumnSpec> columns() const override;
  void on_step(StepContext& ctx) override;
  void summarize(Json& summary) const override;

 private:
  std::int64_t m_steps = 0;
  std::array<double, kCostStages> m_ms_sum{}, m_ms_max{};
  std::array<double, kCostStages> m_work_sum{};
  std::array<std::int64_t, kCostStages> m_interrupted{};
  double m_unaccounted_sum = 0.0;
};

}  // namespace tcb
