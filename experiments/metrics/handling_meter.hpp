#pragma once
/// Handling time and, under a wall-clock budget, its overshoot (the paper's
/// "granularity": how far past the budget a step's handling ran).
/// Columns handling_ms (ms, the handler's step() on the steady clock),
/// handling_cpu_ms (the handling thread's CPU time over the same interval:
/// what the method itself spent; the handler has no worker threads),
/// handling_switches (involuntary context switches during it) and budget_ms
/// (the wall budget; empty under other kinds). Summary handling_ms and
/// handling_cpu_ms {mean, p50, p95, p99, max}; overshoot_pct {p50, p99, max}
/// of 100 (handling_ms - budget_ms) / budget_ms over all steps and
/// overshoot_cpu_pct, the same with handling_cpu_ms: null without a positive
/// wall budget. The method still polls the wall clock (a deadline is wall
/// time); the CPU columns only explain where an overshoot came from.
/// overshoot_us {p50, p99, max}: handling_ms - budget_ms in microseconds
/// (null without a positive wall budget). The granularity: max_task_work,
/// the largest single charge to a step's budget (one task; a whole cycle for
/// methods that run it at once); max_task_us {p50, p99, max} over the steps
/// that polled the budget of each step's longest interval between two
/// interruption checks (the first from the budget's creation, just before
/// the handler is called), under a wall budget (null under others, or when
/// no step polled: no clock is read). The max is one event and on a shared machine often an
/// interrupt's; the p99 is the task granularity a user can count on. Handling after the last check (applying forces) is not a
/// task: it shows in the overshoot.

#include "experiments/metrics/meter.hpp"

namespace tcb {

class HandlingMeter final : public Meter {
 public:
  explicit HandlingMeter(const RunSetup& run) : m_budget(run.budget) {}
  std::vector<ColumnSpec> columns() const override;
  void on_step(StepContext& ctx) override;
  void summarize(Json& summary) const override;

 private:
  BudgetSpec m_budget;
  std::vector<double> m_handling_ms, m_handling_cpu_ms;  // the overshoots are derived from them
  std::uint64_t m_max_task_work = 0;
  std::vector<double> m_max_task_us;
};

}  // namespace tcb
