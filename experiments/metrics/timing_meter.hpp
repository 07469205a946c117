#pragma once
/// The run's timing verdict (timing_quality.hpp): counts preempted steps from
/// each step's wall and CPU handling time, samples the machine at the start
/// and the end, and writes summary.timing:
///   {verdict "quiet"|"noisy", reasons [..], notes [..], preempted_steps,
///    preempted_step_share, involuntary_switches, other_busy_cpus, cpus,
///    loadavg_1min {start, end}, governor, pinned_cpu}
/// (null for what could not be read).

#include "experiments/metrics/meter.hpp"
#include "experiments/run/machine_load.hpp"

namespace tcb {

class TimingMeter final : public Meter {
 public:
  explicit TimingMeter(const RunSetup& run);
  void on_step(StepContext& ctx) override;
  void summarize(Json& summary) const override;

 private:
  BudgetSpec m_budget;
  MachineSample m_start;
  std::int64_t m_steps = 0, m_preempted = 0, m_switches = 0;
};

}  // namespace tcb
