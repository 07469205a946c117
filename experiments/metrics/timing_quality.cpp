#include "experiments/metrics/timing_quality.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace tcb {

bool is_preempted(double wall_ms, double cpu_ms, double base_ms) {
  return wall_ms - cpu_ms > std::max(0.01 * base_ms, kPreemptFloorMs);
}

TimingVerdict timing_verdict(const TimingEvidence& e) {
  TimingVerdict v;
  if (e.steps > 0 && 100 * e.preempted_steps > e.steps)
    v.reasons.push_back(fmt::format("{:.1f} % of steps ({} of {}) lost more than 1 % of the budget to preemption "
                                    "(wall time above the handling thread's CPU time)",
                                    100.0 * static_cast<double>(e.preempted_steps) / static_cast<double>(e.steps),
                                    e.preempted_steps, e.steps));
  const double spare = std::max(1, e.cpus - 1);
  if (e.other_busy_cpus && *e.other_busy_cpus > 0.25 * spare)
    v.reasons.push_back(fmt::format("other processes kept {:.2f} CPUs busy on average ({} CPUs)", *e.other_busy_cpus,
                                    e.cpus));
  if (e.loadavg_start && *e.loadavg_start > e.cpus - 0.5)
    v.notes.push_back(fmt::format("load average {:.2f} at the start on {} CPUs (a lagging hint: it counts earlier "
                                  "runs too)",
                                  *e.loadavg_start, e.cpus));
  if (!e.other_busy_cpus)
    v.notes.push_back("the other processes' load is unknown (/proc/stat unreadable, or the run lasted under 1 s)");
  if (!e.governor) v.notes.push_back("CPU frequency governor not readable (no cpufreq here)");
  else if (*e.governor != "performance")
    v.notes.push_back("CPU frequency governor '" + *e.governor + "': the clock rate may change during the run");
  if (!e.pinned_cpu) v.notes.push_back("handling thread not pinned (--pin)");
  if (e.floor_p99_pct && *e.floor_p99_pct >= 1.0)
    v.notes.push_back(fmt::format("a null handler beside the run overshot the budget by {:.2f} % at p99 "
                                  "(summary.timing.floor): overshoot up to that is the machine's as much as the "
                                  "method's",
                                  *e.floor_p99_pct));
  v.noisy = !v.reasons.empty();
  return v;
}

}  // namespace tcb
