#include "sim/world/trajectory.hpp"

#include <algorithm>

#include "sim/io/numeric_csv.hpp"

namespace tcb {

Vec3 Trajectory::at(double t_s) const {
  if (t_s <= time_s.front()) return position_m.front();
  if (t_s >= time_s.back()) return position_m.back();
  const auto hi = static_cast<std::size_t>(std::upper_bound(time_s.begin(), time_s.end(), t_s) - time_s.begin());
  const std::size_t lo = hi - 1;
  const double w = (t_s - time_s[lo]) / (time_s[hi] - time_s[lo]);
  return (1.0 - w) * position_m[lo] + w * position_m[hi];
}

Trajectory read_trajectory_csv(const std::filesystem::path& path) {
  Trajectory t;
  for (const std::vector<double>& row : read_numeric_csv(path, "time_s,x_m,y_m,z_m", "trajectory")) {
    t.time_s.push_back(row[0]);
    t.position_m.emplace_back(row[1], row[2], row[3]);
  }
  return t;
}

}  // namespace tcb
