#pragma once
/// The run's timing verdict (timing_quality.hpp): counts preempted steps from
/// each step's wall and CPU handling time, samples the machine at the start
/// and the end, and writes summary.timing:
///   {verdict "quiet"|"noisy", reasons [..], notes [..], preempted_steps,
///    preempted_step_share, involuntary_switches, other_busy_cpus, cpus,
///    loadavg_1min {start, end}, governor, pinned_cpu, floor}
/// (null for what could not be read).
///
/// `floor`: under a wall-clock budget of at most kFloorMaxWindowMs, after
/// every step (outside every timed interval) the meter spins one window of the
/// budget's length with a null handler (run/timing_floor.hpp), so the machine's
/// own overshoot is sampled as often as the method's, interleaved with its
/// steps (between them, not at the same moments):
///   {windows, overshoot_us {p50, p99, max}, overshoot_pct {p50, p99, max}}
/// null otherwise, and null when the run turned it off (RunSetup::timing_floor:
/// tcbench live). It adds one window and its overshoot per step to the run's
/// wall time (wall_s), nothing to any handling figure.

#include "experiments/metrics/meter.hpp"
#include "experiments/run/machine_load.hpp"

#include <vector>

namespace tcb {

/// Above this budget (ms) no floor is measured: a stall of tens of µs is then
/// well under 1 % of the budget, and spinning for it would double long runs.
inline constexpr double kFloorMaxWindowMs = 10.0;

class TimingMeter final : public Meter {
 public:
  explicit TimingMeter(const RunSetup& run);
  void on_step(StepContext& ctx) override;
  void summarize(Json& summary) const override;

 private:
  BudgetSpec m_budget;
  bool m_floor = false;  ///< spin a floor window after each step (the file comment's conditions)
  MachineSample m_start;
  std::int64_t m_steps = 0, m_preempted = 0, m_switches = 0;
  std::vector<double> m_floor_overshoot_ms;  ///< one null-handler window a step
};

}  // namespace tcb
