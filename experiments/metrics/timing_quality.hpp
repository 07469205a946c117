#pragma once
/// Whose overshoot is it: a run's timing verdict, `quiet` or `noisy`, from its
/// per-step handling times and the machine around it. A noisy run is not an
/// unstable simulation (its status stays ok); its wall-clock figures say as
/// much about the scheduler as about the method.
///
/// A step is *preempted* when its wall handling time exceeds the handling
/// thread's CPU time over the same interval by more than 1 % of the base: the
/// wall-clock budget (ms) when the run has a positive one, else the step's own
/// wall handling time; never by less than kPreemptFloorMs (the two clocks are
/// read a few hundred ns apart, so smaller gaps are not evidence).
///
/// The run is noisy when any of these holds (each one a reason, in words):
///   - more than 1 % of its steps were preempted;
///   - the other processes kept more than a quarter of the CPUs it did not
///     use busy on average (other_busy_cpus > 0.25 max(1, cpus - 1)).
/// Notes, which do not make it noisy: the machine's own overshoot floor (a
/// null handler beside the run, run/timing_floor.hpp) when its p99 reaches 1 %
/// of the budget (overshoot up to it is the machine's as much as the method's;
/// a floor is evidence about the machine, not about this run's interference,
/// so it never makes a run noisy), the 1-minute load average at the start
/// when it exceeds cpus - 0.5 (it lags by a minute and counts a sweep's own
/// previous runs, so it is a hint, not evidence), the CPU governor is not
/// "performance" or cannot be read, the handling thread was not pinned.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace tcb {

inline constexpr double kPreemptFloorMs = 0.01;  ///< 10 us

/// Whether a step of `wall_ms` whose thread ran `cpu_ms` of it lost more than
/// 1 % of `base_ms` (and more than kPreemptFloorMs) to preemption.
bool is_preempted(double wall_ms, double cpu_ms, double base_ms);

struct TimingEvidence {
  std::int64_t steps = 0, preempted_steps = 0;
  std::optional<double> other_busy_cpus;  ///< average over the run
  int cpus = 1;                           ///< the machine's online CPUs
  std::optional<double> loadavg_start;    ///< 1-minute load average
  std::optional<std::string> governor;
  std::optional<int> pinned_cpu;
  std::optional<double> floor_p99_pct;    ///< the null handler's overshoot p99, % of the budget
};

struct TimingVerdict {
  bool noisy = false;
  std::vector<std::string> reasons;  ///< why noisy (empty when quiet)
  std::vector<std::string> notes;    ///< worth knowing, not evidence of noise
};

TimingVerdict timing_verdict(const TimingEvidence& evidence);

}  // namespace tcb
