#pragma once
/// The Wilson score interval of a rate: k outcomes in n runs. Unlike the
/// normal approximation it stays inside [0, 1] and is not zero-width at 0/n
/// or n/n, which is where a benchmark's outcomes ("the stack stands") sit.
/// centre = (p + z^2/2n) / (1 + z^2/n), half = z sqrt(p(1-p)/n + z^2/4n^2) / (1 + z^2/n),
/// p = k/n; clamped to [0, 1], exactly 0 at k = 0 and 1 at k = n. z = 1.959963984540054 for 95 %.

#include <cstddef>
#include <optional>

namespace tcb {

struct Interval {
  double lo = 0.0, hi = 0.0;
};

inline constexpr double kZ95 = 1.959963984540054;

/// nullopt when n == 0 (no runs: no rate). k <= n.
std::optional<Interval> wilson_interval(std::size_t k, std::size_t n, double z = kZ95);

}  // namespace tcb
