#pragma once
/// Runs a sweep: each run is a child `tcbench run` process (so one run that
/// crashes or goes unstable never stops the others), up to `jobs` at once,
/// each writing DIR/runs/<id>/{run.json, steps.csv, log.txt}. A run is
/// complete when its run.json is (written last, atomically); --resume skips
/// complete runs and redoes the rest from scratch, so a killed sweep resumed
/// ends with every run present exactly once and none half-written.
/// Relative budgets start once their reference run is complete; the absolute
/// value they used is in their run.json (budget.value, budget.label).
/// DIR/summary.csv covers every run of the plan (all shards) found in DIR;
/// shards write it under DIR's lock (directory_lock.hpp), so the last to
/// finish leaves the complete one.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "experiments/sweep/sweep_plan.hpp"

namespace tcb {

struct SweepOptions {
  std::filesystem::path out_dir;
  std::filesystem::path executable;  ///< the tcbench binary the runs use
  std::size_t jobs = 1;
  std::size_t shard_index = 0, shard_count = 1;
  bool resume = false;
  bool quick = false;  ///< use the plan's quick_steps (when it has them) as every run's length
  /// CPUs to pin runs to (`tcbench run --pin`): each running run gets one no
  /// other running run holds; needs at least `jobs` of them. Empty: unpinned.
  std::vector<int> pin_cpus;
  /// After each run ends (or is skipped): done, total, the run, its status.
  std::function<void(std::size_t, std::size_t, const SweepRun&, const std::string&)> on_run;
};

struct SweepOutcome {
  std::size_t total = 0, skipped = 0, ok = 0, unstable = 0, failed = 0;
  int exit_code() const { return unstable + failed == 0 ? 0 : 1; }
};

SweepOutcome run_sweep(const SweepPlan& plan, const SweepOptions& options);

/// `--pin` of sweep and reproduce: "auto" (the CPUs this process may use,
/// highest first, so CPU 0 and its interrupts are left alone when a job
/// needs fewer) or a comma list "2,3". The result has exactly `jobs` CPUs.
/// InputError naming --pin when there are fewer than `jobs` CPUs, or a CPU
/// is not allowed here.
std::vector<int> parse_pin_cpus(const std::string& text, std::size_t jobs);

}  // namespace tcb
