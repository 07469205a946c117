#pragma once
/// The Mann-Whitney U (Wilcoxon rank-sum) test of two samples: does one tend
/// to be larger than the other? Rank-based, so one slow outlier step cannot
/// dominate it, which is why benchmark comparisons use it (Google
/// Benchmark's compare.py does). Ties get mid-ranks. The p-value is two-sided
/// from the normal approximation with tie correction and continuity
/// correction: z = (|U_a - n_a n_b / 2| - 1/2) / sigma,
/// sigma^2 = n_a n_b / 12 ((n + 1) - sum(t^3 - t) / (n (n - 1))), p = erfc(|z| / sqrt 2).
/// The approximation is rough below about 8 values a side; sigma = 0 (all
/// values tied) gives p = 1. Per-step values of one run are autocorrelated,
/// so a p-value over them overstates significance: prefer repeats.

#include <cstddef>
#include <optional>
#include <vector>

namespace tcb {

struct MannWhitney {
  double u_a = 0.0;  ///< pairs (x in a, y in b) with x > y, ties counted 1/2
  double p_two_sided = 1.0;
  /// u_a / (n_a n_b): the chance that a value of a exceeds one of b (0.5: no tendency).
  double a_greater_share = 0.5;
  std::size_t n_a = 0, n_b = 0;
};

/// nullopt when either sample is empty.
std::optional<MannWhitney> mann_whitney(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace tcb
