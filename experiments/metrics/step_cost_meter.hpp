#pragma once
/// The whole step's cost (issue 20): what a user's application pays per
/// step, collision handling plus integration (which, under implicit response,
/// includes the contact terms the handler handed to the solve). Column step_ms
/// = handling_ms + dynamics_ms (ms); the harness's own work between the two
/// (meters, the oracle, writing files) is not part of it. Summary step_ms
/// {mean, p50, p95, p99, max}. The claims table compares speed-ups on
/// handling_ms and on step_ms side by side.

#include "experiments/metrics/meter.hpp"

namespace tcb {

class StepCostMeter final : public Meter {
 public:
  std::vector<ColumnSpec> columns() const override;
  void on_step(StepContext& ctx) override;
  void summarize(Json& summary) const override;

 private:
  std::vector<double> m_step_ms;
};

}  // namespace tcb
