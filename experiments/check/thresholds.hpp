#pragma once
/// `tcbench check THRESHOLDS.toml DIR`: accuracy and cost bounds on the runs
/// of a results directory, for a user's CI.
///
///   [[threshold]]
///   scene  = "plates20"
///   method = "interruptible"   # the run's method_label: "every_nth(n=3)" for a non-default setting
///   budget = "work:20000"   # the run's budget label (run.json budget.label); default "none"
///   seed   = 0              # optional: otherwise every seed's run must pass
///   metric = "recall_min"   # a summary key; nested with dots: "depth_err.max"
///   min = 0.95              # at least one of min / max
///   max = 1.0
///
/// A threshold whose run is missing, or whose metric is null or absent in it,
/// fails: a CI check must not pass because nothing was measured.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tcb {

struct Threshold {
  std::string scene, method, budget = "none", metric;
  std::optional<std::uint64_t> seed;
  std::optional<double> min, max;
  int line = 0;
};

struct CheckRow {
  const Threshold* threshold = nullptr;
  std::string run;              ///< the run directory name; empty when none matched
  std::optional<double> value;
  std::string verdict;          ///< "pass", "FAIL", "missing"
};

/// Reads a thresholds file; InputError (file:line) for anything malformed.
std::vector<Threshold> load_thresholds(const std::filesystem::path& path);

/// One row per threshold and matching run (at least one row per threshold).
std::vector<CheckRow> check_thresholds(const std::vector<Threshold>& thresholds, const std::filesystem::path& dir);

}  // namespace tcb
