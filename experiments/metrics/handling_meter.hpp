#pragma once
/// Handling time and, under a wall-clock budget, its overshoot (the paper's
/// "granularity": how far past the budget a step's handling ran).
/// Columns handling_ms (ms, the handler's step() on the steady clock) and
/// budget_ms (the wall budget; empty under other kinds). Summary
/// handling_ms {mean, p50, p95, p99, max}; overshoot_pct {p50, p99, max} of
/// 100 (handling_ms - budget_ms) / budget_ms over all steps, null without a
/// positive wall budget.

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
  std::vector<double> m_handling_ms, m_overshoot_pct;
};

}  // namespace tcb
