#include "experiments/metrics/step_cost_meter.hpp"

namespace tcb {

std::vector<ColumnSpec> StepCostMeter::columns() const {
  return {{"step_ms", "the whole step: handling_ms + dynamics_ms, the harness's own work excluded (ms)"}};
}

void StepCostMeter::on_step(StepContext& ctx) {
  const double step_ms = ctx.handling_ms + ctx.dynamics_ms;
  ctx.row.set("step_ms", step_ms);
  m_step_ms.push_back(step_ms);
}

void StepCostMeter::summarize(Json& summary) const { summary["step_ms"] = distribution_json(m_step_ms); }

}  // namespace tcb
