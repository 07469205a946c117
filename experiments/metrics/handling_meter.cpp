#include "experiments/metrics/handling_meter.hpp"

#include "experiments/metrics/distribution.hpp"

namespace tcb {

std::vector<ColumnSpec> HandlingMeter::columns() const {
  return {{"handling_ms", "wall time of the handler's step (ms)"},
          {"budget_ms", "the wall-clock budget of the step (ms); empty under other budget kinds"}};
}

void HandlingMeter::on_step(StepContext& ctx) {
  ctx.row.set("handling_ms", ctx.handling_ms);
  m_handling_ms.push_back(ctx.handling_ms);
  if (m_budget.kind != BudgetKind::WallMs) return;
  ctx.row.set("budget_ms", m_budget.value);
  if (m_budget.value > 0.0) m_overshoot_pct.push_back(100.0 * (ctx.handling_ms - m_budget.value) / m_budget.value);
}

void HandlingMeter::summarize(Json& summary) const {
  summary["handling_ms"] = distribution_json(m_handling_ms);
  if (m_overshoot_pct.empty()) {
    summary["overshoot_pct"] = nullptr;  // no (positive) wall budget
    return;
  }
  const Distribution o = tcb::summarize(m_overshoot_pct);
  summary["overshoot_pct"] = {{"p50", o.p50}, {"p99", o.p99}, {"max", o.max}};
}

}  // namespace tcb
