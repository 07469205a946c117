#include "experiments/statistics/wilson_interval.hpp"

#include <algorithm>
#include <cmath>

namespace tcb {

std::optional<Interval> wilson_interval(std::size_t k, std::size_t n, double z) {
  if (n == 0) return std::nullopt;
  const double nn = static_cast<double>(n), p = static_cast<double>(k) / nn, z2 = z * z;
  const double denominator = 1.0 + z2 / nn;
  const double centre = (p + z2 / (2.0 * nn)) / denominator;
  const double half = z * std::sqrt(p * (1.0 - p) / nn + z2 / (4.0 * nn * nn)) / denominator;
  return Interval{std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

}  // namespace tcb
