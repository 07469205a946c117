#include "sim/world/trajectory.hpp"

#include "sim/io/numeric_csv.hpp"

namespace tcb {

Vec3 Trajectory::at(double t_s) const {
  return sample_linear(time_s, position_m, t_s);
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
