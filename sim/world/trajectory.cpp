#include "sim/world/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "sim/io/input_error.hpp"

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
  std::ifstream in(path);
  if (!in) throw InputError(path.string(), 0, "cannot open the trajectory file");
  Trajectory t;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (number == 1) {
      if (line != "time_s,x_m,y_m,z_m") throw InputError(path.string(), 1, "expected the header time_s,x_m,y_m,z_m");
      continue;
    }
    if (line.empty()) continue;
    std::stringstream cells(line);
    double v[4];
    for (int k = 0; k < 4; ++k) {
      std::string cell;
      if (!std::getline(cells, cell, ',')) throw InputError(path.string(), number, "expected 4 values");
      try {
        std::size_t used = 0;
        v[k] = std::stod(cell, &used);
        if (used != cell.size()) throw std::invalid_argument(cell);
      } catch (const std::exception&) {
        throw InputError(path.string(), number, "'" + cell + "' is not a number");
      }
      if (!std::isfinite(v[k])) throw InputError(path.string(), number, "values must be finite");
    }
    std::string extra;
    if (std::getline(cells, extra, ',')) throw InputError(path.string(), number, "expected 4 values");
    if (!t.time_s.empty() && !(v[0] > t.time_s.back()))
      throw InputError(path.string(), number, "times must increase strictly");
    t.time_s.push_back(v[0]);
    t.position_m.emplace_back(v[1], v[2], v[3]);
  }
  if (t.time_s.empty()) throw InputError(path.string(), number, "no samples");
  return t;
}

}  // namespace tcb
