#include "experiments/metrics/distribution.hpp"

#include <algorithm>
#include <cmath>

namespace tcb {

double percentile_of_sorted(const std::vector<double>& v, double p) {
  if (v.empty()) return 0.0;
  const double rank = p / 100.0 * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(rank));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (rank - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

Distribution summarize(std::vector<double> values) {
  Distribution d;
  if (values.empty()) return d;
  std::sort(values.begin(), values.end());
  d.count = values.size();
  double sum = 0.0, sum_sq = 0.0;
  for (double v : values) {
    sum += v;
    sum_sq += v * v;
  }
  d.mean = sum / static_cast<double>(d.count);
  d.rms = std::sqrt(sum_sq / static_cast<double>(d.count));
  d.min = values.front();
  d.max = values.back();
  d.p50 = percentile_of_sorted(values, 50);
  d.p95 = percentile_of_sorted(values, 95);
  d.p99 = percentile_of_sorted(values, 99);
  return d;
}

}  // namespace tcb
