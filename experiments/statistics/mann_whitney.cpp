#include "experiments/statistics/mann_whitney.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace tcb {

std::optional<MannWhitney> mann_whitney(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.empty() || b.empty()) return std::nullopt;
  std::vector<std::pair<double, bool>> all;  // (value, from a)
  all.reserve(a.size() + b.size());
  for (double x : a) all.emplace_back(x, true);
  for (double y : b) all.emplace_back(y, false);
  std::sort(all.begin(), all.end(), [](const auto& l, const auto& r) { return l.first < r.first; });
  const double n = static_cast<double>(all.size());
  double rank_sum_a = 0.0, tie_term = 0.0;
  for (std::size_t i = 0; i < all.size();) {
    std::size_t j = i;
    while (j < all.size() && all[j].first == all[i].first) ++j;
    const double mid_rank = 0.5 * static_cast<double>(i + 1 + j);  // ranks i+1 .. j
    const double t = static_cast<double>(j - i);
    tie_term += t * t * t - t;
    for (std::size_t k = i; k < j; ++k)
      if (all[k].second) rank_sum_a += mid_rank;
    i = j;
  }
  MannWhitney m;
  m.n_a = a.size();
  m.n_b = b.size();
  const double na = static_cast<double>(m.n_a), nb = static_cast<double>(m.n_b);
  m.u_a = rank_sum_a - na * (na + 1.0) / 2.0;
  m.a_greater_share = m.u_a / (na * nb);
  const double variance = na * nb / 12.0 * ((n + 1.0) - (n > 1.0 ? tie_term / (n * (n - 1.0)) : 0.0));
  if (!(variance > 0.0)) return m;  // every value tied: no evidence either way
  const double z = std::max(0.0, std::abs(m.u_a - na * nb / 2.0) - 0.5) / std::sqrt(variance);
  m.p_two_sided = std::erfc(z / std::sqrt(2.0));
  return m;
}

}  // namespace tcb
