#include "sim/latent/latent_path.hpp"

#include <algorithm>

#include "sim/io/numeric_csv.hpp"

namespace tcb {

Eigen::VectorXd LatentPath::at(double t_s) const {
  if (t_s <= time_s.front()) return code.front();
  if (t_s >= time_s.back()) return code.back();
  const auto hi = static_cast<std::size_t>(std::upper_bound(time_s.begin(), time_s.end(), t_s) - time_s.begin());
  const std::size_t lo = hi - 1;
  const double w = (t_s - time_s[lo]) / (time_s[hi] - time_s[lo]);
  return (1.0 - w) * code[lo] + w * code[hi];
}

LatentPath read_latent_path_csv(const std::filesystem::path& path, int latent_size) {
  std::string header = "time_s";
  for (int k = 0; k < latent_size; ++k) header += ",z" + std::to_string(k);
  LatentPath p;
  for (const std::vector<double>& row : read_numeric_csv(path, header, "latent path")) {
    p.time_s.push_back(row[0]);
    p.code.push_back(Eigen::Map<const Eigen::VectorXd>(row.data() + 1, latent_size));
  }
  return p;
}

std::vector<Vec3> LatentDrive::positions_m(const Eigen::VectorXd& z) const {
  std::vector<Vec3> x = finger->decode(z);
  for (Vec3& p : x) p = scale * p + position_m;
  return x;
}

}  // namespace tcb
