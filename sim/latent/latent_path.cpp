#include "sim/latent/latent_path.hpp"

#include "sim/io/numeric_csv.hpp"

namespace tcb {

Eigen::VectorXd LatentPath::at(double t_s) const {
  return sample_linear(time_s, code, t_s);
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
