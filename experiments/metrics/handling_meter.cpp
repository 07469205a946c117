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
    if (ctx.budget->polls() > 0) m_max_task_us.push_back(1000.0 * ctx.budget->max_poll_gap_ms());  // wall budgets only
  }
  if (m_budget.kind == BudgetKind::WallMs) ctx.row.set("budget_ms", m_budget.value);
}

void HandlingMeter::summarize(Json& summary) const {
  summary["handling_ms"] = distribution_json(m_handling_ms);
  summary["handling_cpu_ms"] = distribution_json(m_handling_cpu_ms);
  // {p50, p99, max} of scale * (value - offset): the overshoots are affine in
  // the handling times, and percentiles (linearly interpolated) follow.
  const auto tail = [](const std::vector<double>& values, double offset = 0.0, double scale = 1.0) {
    if (values.empty()) return Json(nullptr);
    const Distribution o = tcb::summarize(values);
    return Json{{"p50", scale * (o.p50 - offset)}, {"p99", scale * (o.p99 - offset)}, {"max", scale * (o.max - offset)}};
  };
  const double budget_ms = m_budget.value;
  const bool wall = m_budget.kind == BudgetKind::WallMs && budget_ms > 0.0 && !m_handling_ms.empty();
  summary["overshoot_pct"] = wall ? tail(m_handling_ms, budget_ms, 100.0 / budget_ms) : Json(nullptr);
  summary["overshoot_cpu_pct"] = wall ? tail(m_handling_cpu_ms, budget_ms, 100.0 / budget_ms) : Json(nullptr);
  summary["overshoot_us"] = wall ? tail(m_handling_ms, budget_ms, 1000.0) : Json(nullptr);
  summary["max_task_work"] = m_max_task_work;
  summary["max_task_us"] = tail(m_max_task_us);
}

}  // namespace tcb
