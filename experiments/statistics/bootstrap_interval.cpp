#include "experiments/statistics/bootstrap_interval.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/random/counter_random.hpp"

namespace tcb {
namespace {

double resampled_median(const std::vector<double>& values, std::uint64_t seed, std::uint64_t stream,
                        std::vector<double>& scratch) {
  const std::size_t n = values.size();
  scratch.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    const auto pick = static_cast<std::size_t>(uniform_01(seed, stream, j) * static_cast<double>(n));
    scratch[j] = values[std::min(pick, n - 1)];
  }
  return median_of(scratch);
}

Interval percentile_interval(std::vector<double> medians) {
  std::sort(medians.begin(), medians.end());
  const double r = static_cast<double>(medians.size());
  const auto lo = static_cast<std::size_t>(std::floor(0.025 * r));
  const auto hi = static_cast<std::size_t>(std::ceil(0.975 * r)) - 1;
  return {medians[lo], medians[hi]};
}

}  // namespace

double median_of(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

MedianEstimate bootstrap_median(const std::vector<double>& values, std::size_t resamples, std::uint64_t seed) {
  MedianEstimate e{median_of(values), std::nullopt, values.size()};
  if (values.size() < 2 || resamples == 0) return e;
  std::vector<double> medians(resamples), scratch;
  for (std::size_t r = 0; r < resamples; ++r) medians[r] = resampled_median(values, seed, r, scratch);
  e.ci95 = percentile_interval(std::move(medians));
  return e;
}

MedianEstimate bootstrap_median_difference(const std::vector<double>& a, const std::vector<double>& b,
                                           std::size_t resamples, std::uint64_t seed) {
  MedianEstimate e{median_of(b) - median_of(a), std::nullopt, std::min(a.size(), b.size())};
  if (a.size() < 2 || b.size() < 2 || resamples == 0) return e;
  std::vector<double> differences(resamples), scratch;
  for (std::size_t r = 0; r < resamples; ++r)
    differences[r] = resampled_median(b, seed, 2 * r + 1, scratch) - resampled_median(a, seed, 2 * r, scratch);
  e.ci95 = percentile_interval(std::move(differences));
  return e;
}

}  // namespace tcb
