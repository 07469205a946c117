#include "sim/dynamics/rotation_extraction.hpp"

#include <cmath>

namespace tcb {

int extract_rotation(const Eigen::Matrix3d& f, Eigen::Quaterniond& q, int max_iterations) {
  constexpr double kConverged = 1.0e-9;  // rotation increment in radians
  constexpr double kTiny = 1.0e-9;       // keeps the step finite when tr(R^T F) ~ 0 (flat element)
  for (int it = 0; it < max_iterations; ++it) {
    const Eigen::Matrix3d r = q.toRotationMatrix();
    // Torque-like direction that increases tr(R^T F), scaled like a Newton step.
    const Eigen::Vector3d omega =
        (r.col(0).cross(f.col(0)) + r.col(1).cross(f.col(1)) + r.col(2).cross(f.col(2))) /
        (std::abs(r.col(0).dot(f.col(0)) + r.col(1).dot(f.col(1)) + r.col(2).dot(f.col(2))) + kTiny);
    const double angle = omega.norm();
    if (!(angle > kConverged)) return it;  // also stops on NaN input
    q = Eigen::Quaterniond(Eigen::AngleAxisd(angle, omega / angle)) * q;
    q.normalize();
  }
  return max_iterations;
}

}  // namespace tcb
