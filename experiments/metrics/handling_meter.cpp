#include "experiments/metrics/handling_meter.hpp"

#include "experiments/metrics/distribution.hpp"

namespace tcb {

std::vector<ColumnSpec> HandlingMeter::columns() const {
  return {{"handling_ms", "wall time of the handler's step (ms)"},
          {"handling_cpu_ms", "the handling thread's CPU time over the same interval (ms)"},
          {"handling_switches", "involuntary context switches of the handling thread during handling"},
          {"budget_ms", "the wall-clock budget of the step (ms); empty under other budget kinds"}};
}

void HandlingMeter::on_step(StepContext& ctx) {
  ctx.row.set("handling_ms", ctx.handling_ms);
  ctx.row.set("handling_cpu_ms", ctx.handling_cpu_ms);
  ctx.row.set("handling_switches", ctx.handling_switches);
  m_handling_ms.push_back(ctx.handling_ms);
  m_handling_cpu_ms.push_back(ctx.handling_cpu_ms);
  if (m_budget.kind != BudgetKind::WallMs) return;
  ctx.row.set("budget_ms", m_budget.value);
  if (m_budget.value > 0.0) {
    m_overshoot_pct.push_back(100.0 * (ctx.handling_ms - m_budget.value) / m_budget.value);
    m_overshoot_cpu_pct.push_back(100.0 * (ctx.handling_cpu_ms - m_budget.value) / m_budget.value);
  }
}

void HandlingMeter::summarize(Json& summary) const {
  summary["handling_ms"] = distribution_json(m_handling_ms);
  summary["handling_cpu_ms"] = distribution_json(m_handling_cpu_ms);
  const auto overshoot = [](const std::vector<double>& pct) {
    if (pct.empty()) return Json(nullptr);  // no (positive) wall budget
    const Distribution o = tcb::summarize(pct);
    return Json{{"p50", o.p50}, {"p99", o.p99}, {"max", o.max}};
  };
  summary["overshoot_pct"] = overshoot(m_overshoot_pct);
  summary["overshoot_cpu_pct"] = overshoot(m_overshoot_cpu_pct);
}

}  // namespace tcb
