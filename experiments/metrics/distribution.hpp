#pragma once
/// Summary statistics of a series (handling times, errors, ...).
/// Percentiles interpolate linearly between order statistics (numpy's
/// default): p50 of {1, 2} is 1.5. Non-finite values are not expected here;
/// callers filter them.

#include <vector>

namespace tcb {

struct Distribution {
  std::size_t count = 0;
  double mean = 0.0, p50 = 0.0, p95 = 0.0, p99 = 0.0, max = 0.0, rms = 0.0, min = 0.0;
};

/// Summary of the values (taken by value: they are sorted). count = 0 and all
/// fields 0 for an empty series.
Distribution summarize(std::vector<double> values);

/// The p-th percentile (0..100) of sorted values.
double percentile_of_sorted(const std::vector<double>& sorted, double p);

}  // namespace tcb
