#include "experiments/metrics/handling_meter.hpp"

#include <algorithm>

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
  if (ctx.budget) {
    m_max_task_work = std::max(m_max_task_work, ctx.budget->max_task_work());
    // A step with no poll (its only task finished the cycle, or the method
    // ignores budgets) measured no interval: it adds nothing.
    if (m_budget.kind == BudgetKind::WallMs && ctx.budget->polls() > 0)
      m_max_task_us.push_back(1000.0 * ctx.budget->max_poll_gap_ms());
  }
  if (m_budget.kind != BudgetKind::WallMs) return;
  ctx.row.set("budget_ms", m_budget.value);
  if (m_budget.value > 0.0) {
    m_overshoot_pct.push_back(100.0 * (ctx.handling_ms - m_budget.value) / m_budget.value);
    m_overshoot_cpu_pct.push_back(100.0 * (ctx.handling_cpu_ms - m_budget.value) / m_budget.value);
    m_overshoot_us.push_back(1000.0 * (ctx.handling_ms - m_budget.value));
  }
}

void HandlingMeter::summarize(Json& summary) const {
  summary["handling_ms"] = distribution_json(m_handling_ms);
  summary["handling_cpu_ms"] = distribution_json(m_handling_cpu_ms);
  const auto tail = [](const std::vector<double>& values) {  // {p50, p99, max}
    if (values.empty()) return Json(nullptr);  // no (positive) wall budget
    const Distribution o = tcb::summarize(values);
    return Json{{"p50", o.p50}, {"p99", o.p99}, {"max", o.max}};
  };
  summary["overshoot_pct"] = tail(m_overshoot_pct);
  summary["overshoot_cpu_pct"] = tail(m_overshoot_cpu_pct);
  summary["overshoot_us"] = tail(m_overshoot_us);
  summary["max_task_work"] = m_max_task_work;
  summary["max_task_us"] = tail(m_max_task_us);
}

}  // namespace tcb
