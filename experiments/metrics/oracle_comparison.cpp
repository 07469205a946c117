#include "experiments/metrics/oracle_comparison.hpp"

#include <cmath>
#include <map>
#include <set>

namespace tcb {

OracleComparison compare_with_oracle(const std::vector<Contact>& method, const OracleFrame& oracle) {
  using Key = std::pair<std::int32_t, std::int32_t>;
  std::map<Key, double> truth;
  std::set<Key> self;
  OracleComparison r;
  for (const OraclePoint& p : oracle.inside) {
    truth[{p.object, p.vertex}] = p.depth_m;
    if (p.object != p.other) continue;
    self.insert({p.object, p.vertex});
    ++r.self_points;
    if (std::isfinite(p.depth_m)) ++r.self_points_with_depth;
  }
  const std::set<Key> boundary(oracle.boundary.begin(), oracle.boundary.end());
  r.oracle_points = static_cast<std::int64_t>(truth.size());
  r.max_depth_m = oracle.max_depth_m;
  std::size_t hits = 0, counted = 0;
  for (const Contact& c : method) {
    const Key key{c.object, c.vertex};
    const auto it = truth.find(key);
    if (it == truth.end()) {
      if (!boundary.count(key)) ++counted;  // a false positive
      continue;
    }
    ++hits;
    ++counted;
    if (c.depth_source == DepthSource::None || !std::isfinite(it->second)) continue;
    r.depth_errors.push_back(std::abs(c.depth_m - it->second));
    if (self.count(key)) r.self_depth_errors.push_back(r.depth_errors.back());
  }
  if (!truth.empty()) r.recall = static_cast<double>(hits) / static_cast<double>(truth.size());
  if (counted > 0) r.precision = static_cast<double>(hits) / static_cast<double>(counted);
  if (!r.depth_errors.empty()) {
    double sum = 0.0, max = 0.0;
    for (double e : r.depth_errors) {
      sum += e;
      max = std::max(max, e);
    }
    r.depth_err_mean = sum / static_cast<double>(r.depth_errors.size());
    r.depth_err_max = max;
  }
  return r;
}

}  // namespace tcb
