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
  // At k = 0 (k = n) the lower (upper) end is exactly 0 (1); rounding would
  // leave 5.6e-17 there.
  return Interval{k == 0 ? 0.0 : std::max(0.0, centre - half), k == n ? 1.0 : std::min(1.0, centre + half)};
}

}  // namespace tcb
