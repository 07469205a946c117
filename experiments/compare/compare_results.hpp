#pragma once
/// `tcbench compare A B`: what changed from A to B, with intervals. A and B
/// are results directories (or single runs). Runs are paired by
/// configuration (run_collection.hpp: everything but the seed); when each
/// side holds exactly one configuration the two are paired whatever they are
/// (full against interruptible, say). Per pair and metric: the median over
/// repeats on each side with its bootstrap 95 % interval, the difference of
/// medians B - A with its interval, the change relative to A, and a
/// Mann-Whitney U test (over the repeats' values when each side has 3 or
/// more; for timing metrics with fewer repeats, over the per-step values of
/// the steps.csv column the metric summarizes, pooled: autocorrelated, so
/// its p-value is optimistic and says "steps"). Outcomes (unstable,
/// tunnelling) as rates with Wilson intervals.
///
/// Thresholds, for CI (--threshold METRIC=LIMIT): LIMIT "+X" lets B's median
/// rise at most X above A's, "-X" fall at most X, "X" move at most X either
/// way; a trailing "%" makes X relative to A's median. A pair breaks the
/// threshold when its change is beyond the limit and, for timing metrics
/// (a wall-clock time, whose repeats scatter), the U test also finds the
/// difference significant (p < 0.05). A threshold whose metric no pair has
/// is "unknown metric" and fails too (a misspelling must not pass).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/results/run_collection.hpp"
#include "experiments/statistics/bootstrap_interval.hpp"
#include "experiments/statistics/mann_whitney.hpp"

namespace tcb {

struct CompareThreshold {
  std::string text;  ///< as given
  std::string metric;
  double limit = 0.0;  ///< >= 0
  enum class Direction { Rise, Fall, Either } direction = Direction::Either;
  bool relative = false;  ///< limit in % of A's median
};

/// Parses METRIC=LIMIT; InputError naming --threshold when malformed.
CompareThreshold parse_compare_threshold(const std::string& text);

/// Whether a metric is a wall-clock time (noisy repeats; per-step U test).
bool is_timing_metric(const std::string& metric);

struct MetricComparison {
  std::string metric;
  MedianEstimate a, b, difference;
  std::optional<double> relative;  ///< difference / |A's median|; none when A's is 0
  std::optional<MannWhitney> u_test;
  std::string u_over;  ///< "runs" or "steps"
};

struct OutcomeComparison {
  std::string outcome;  ///< "unstable", "tunnelling"
  std::size_t a_count = 0, a_runs = 0, b_count = 0, b_runs = 0;
};

struct ThresholdVerdict {
  const CompareThreshold* threshold = nullptr;
  std::string status;  ///< "pass", "fail", "unknown metric"
  std::string why;
};

struct ComparedPair {
  std::string a_label, b_label;
  std::size_t a_runs = 0, b_runs = 0;
  std::vector<MetricComparison> metrics;
  std::vector<OutcomeComparison> outcomes;
  std::vector<ThresholdVerdict> verdicts;  ///< one per threshold whose metric the pair has
};

struct Comparison {
  std::vector<ComparedPair> pairs;
  std::vector<std::string> only_a, only_b;  ///< configurations without a partner
  std::vector<ThresholdVerdict> unknown;    ///< thresholds no pair could judge
  bool regression() const;                  ///< some threshold failed
};

/// metrics empty: headline_metrics() (run_collection.hpp); a pair skips a
/// metric one of its sides has in no run.
Comparison compare_runs(const std::vector<CollectedRun>& a, const std::vector<CollectedRun>& b,
                        std::vector<std::string> metrics, const std::vector<CompareThreshold>& thresholds);

std::string format_comparison(const Comparison& c, const std::string& a_name, const std::string& b_name);
nlohmann::json comparison_json(const Comparison& c, const std::string& a_name, const std::string& b_name);

}  // namespace tcb
