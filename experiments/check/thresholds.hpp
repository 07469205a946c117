#pragma once
/// `tcbench check THRESHOLDS.toml DIR`: accuracy and cost bounds on the runs
/// of a results directory, for a user's CI.
///
///   [[threshold]]
///   scene  = "plates20"
///   method = "interruptible"   # the run's method_label: "every_nth(n=3)" for a non-default setting
///   budget = "work:20000"   # the run's budget label (run.json budget.label); default "none"
///   seed   = 0              # optional: otherwise every seed's run must pass
///   response = "implicit"   # optional: only runs of that response mode (run.json response)
///   set    = ["collision.response=explicit"]  # optional: only runs with exactly these --set overrides ([] none)
///   status = "unstable"     # optional: the run's status must be this ("ok" or "unstable") ...
///   reason = "energy rose"  # ... and, for "unstable", its unstable_reason contain this
///   metric = "recall_min"   # a summary key; nested with dots: "depth_err.max" (optional with status)
///   relative_to = "full"    # optional: bound metric / the same metric of that method's run
///   min = 0.95              # at least one of min / max
///   max = 1.0
///
/// With relative_to, the bounded value is the run's metric divided by its
/// reference's: the run of that method label with budget none, the same
/// scene, seed, response mode, length and --set overrides (run.json keeps
/// only the scene's), in the same folder as the run (the sweep's own
/// reference, never another sweep's of the same scene). "Jitter within 2x of full's"
/// is `metric = "jitter"`, `relative_to = "full"`, `max = 2`.
///
/// With status, the run's status (and, for "unstable", a part of its
/// reason) must be as stated; a metric is then optional, and checked too
/// when given. That is how a thresholds file says which extreme case is
/// expected to run and which to stop (experiments/thresholds/extremes.toml).
///
/// A threshold whose run is missing, or whose metric is null or absent in it,
/// fails: a CI check must not pass because nothing was measured. So does a
/// relative one whose reference run is missing or measured 0.
///
/// A wall-clock threshold (its run has a wall-clock budget, or its metric is
/// wall time: handling_ms.*, overshoot_pct.*, dynamics_ms.*) on a run whose
/// summary.timing.verdict is "noisy" (or on a reference that is; ms:0, spent
/// at the first poll on any machine, is not a wall-clock budget here) is
/// "inconclusive": neither passed nor failed, since the scheduler had a hand
/// in the number (metrics/timing_quality.hpp). CPU-time metrics
/// (handling_cpu_ms, overshoot_cpu_pct) and work budgets are never
/// inconclusive.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tcb {

struct Threshold {
  std::string scene, method, budget = "none", metric;
  std::optional<std::uint64_t> seed;
  std::optional<std::string> response;     ///< "implicit" or "explicit"
  std::optional<std::string> relative_to;  ///< a method label: bound the ratio to its run's metric
  std::optional<std::vector<std::string>> set;  ///< the run's --set overrides, sorted; absent: any
  std::optional<std::string> status;       ///< "ok" or "unstable": what the run's status must be
  std::optional<std::string> reason;       ///< with status "unstable": a part of unstable_reason
  /// Wall clock decides the value (see above): a wall-clock metric, or a run
  /// under a wall-clock budget. Set by load_thresholds.
  bool wall_metric = false, wall_budget = false;
  std::optional<double> min, max;
  int line = 0;
};

struct CheckRow {
  const Threshold* threshold = nullptr;
  std::string run;              ///< the run directory name; empty when none matched
  std::string reference;        ///< relative thresholds: the reference run's directory name
  std::optional<double> value;  ///< the metric, or its ratio to the reference's
  std::string verdict;          ///< "pass", "FAIL", "missing", "inconclusive"
  std::string status;           ///< the run's status
  bool status_check = false;    ///< the verdict is the status check's (metric empty, or status not as expected)
};

/// Reads a thresholds file; InputError (file:line) for anything malformed.
std::vector<Threshold> load_thresholds(const std::filesystem::path& path);

/// The same from text; `path` names the file in errors.
std::vector<Threshold> parse_thresholds(std::string_view text, const std::filesystem::path& path);

/// One row per threshold and matching run (at least one row per threshold).
std::vector<CheckRow> check_thresholds(const std::vector<Threshold>& thresholds, const std::filesystem::path& dir);

/// The rows as `tcbench check` prints them: a table, then "K of N checks passed (FILE)".
std::string format_check_rows(const std::vector<CheckRow>& rows, const std::string& thresholds_file);

/// `tcbench check`'s exit status: 0 every row passed; 1 a row failed or is
/// missing (or, with strict_timing, is inconclusive); 4 the rest passed but
/// some are inconclusive.
int check_exit_status(const std::vector<CheckRow>& rows, bool strict_timing);

}  // namespace tcb
