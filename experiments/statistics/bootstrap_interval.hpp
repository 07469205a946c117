#pragma once
/// Medians of repeats with percentile-bootstrap 95 % intervals, the same on
/// every machine: resampling draws come from the project's counter-based
/// generator (sim/random/counter_random.hpp) with a fixed seed, and the
/// report (report/tcbench_report/statistics.py) implements the identical
/// definition, so both print the same interval for the same runs.
///
/// median: the middle value, the mean of the two middle ones for even n.
/// Resample r (0 .. resamples-1), draw j (0 .. n-1) takes
/// values[floor(uniform_01(seed, r, j) * n)] (values in the caller's order:
/// sort repeats by seed first); the resample's median. The interval is
/// [sorted[floor(0.025 R)], sorted[ceil(0.975 R) - 1]] of the R resample
/// medians (R = 2000: indices 50 and 1949). Fewer than 2 values: no interval.
/// A difference of medians (B - A) resamples A with streams 2r and B with
/// streams 2r + 1, independently.

#include <cstdint>
#include <optional>
#include <vector>

#include "experiments/statistics/wilson_interval.hpp"

namespace tcb {

/// "tcbench" in ASCII.
inline constexpr std::uint64_t kBootstrapSeed = 0x746362656E6368ull;
inline constexpr std::size_t kBootstrapResamples = 2000;

/// NaN for no values.
double median_of(std::vector<double> values);

struct MedianEstimate {
  double median = 0.0;
  std::optional<Interval> ci95;  ///< with 2 or more values
  std::size_t n = 0;
};

MedianEstimate bootstrap_median(const std::vector<double>& values, std::size_t resamples = kBootstrapResamples,
                                std::uint64_t seed = kBootstrapSeed);

/// median(b) - median(a), with its interval when both have 2 or more values.
MedianEstimate bootstrap_median_difference(const std::vector<double>& a, const std::vector<double>& b,
                                           std::size_t resamples = kBootstrapResamples,
                                           std::uint64_t seed = kBootstrapSeed);

}  // namespace tcb
