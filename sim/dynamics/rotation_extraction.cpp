#include "sim/dynamics/rotation_extraction.hpp"

#include <cmath>

namespace tcb {
namespace {

// Solves H w = g for a symmetric H if H is positive definite (Sylvester's
// criterion); returns false otherwise.
bool solve_positive_definite(const Eigen::Matrix3d& h, const Eigen::Vector3d& g, Eigen::Vector3d& w) {
  const double m1 = h(0, 0);
  const double m2 = h(0, 0) * h(1, 1) - h(0, 1) * h(1, 0);
  const double m3 = h.determinant();
  if (!(m1 > 0.0 && m2 > 0.0 && m3 > 0.0)) return false;
  w = h.inverse() * g;
  return w.allFinite();
}

}  // namespace

int extract_rotation(const Eigen::Matrix3d& f, Eigen::Quaterniond& q, int max_iterations) {
  constexpr double kConverged = 1.0e-9;   // rotation increment in radians
  constexpr double kTiny = 1.0e-9;        // keeps the gradient step finite when tr(B) ~ 0 (flat element)
  constexpr double kMaxNewtonStep = 0.5;  // radians; larger Newton steps are not trusted
  for (int it = 0; it < max_iterations; ++it) {
    const Eigen::Matrix3d b = f * q.toRotationMatrix().transpose();
    const Eigen::Vector3d g(b(2, 1) - b(1, 2), b(0, 2) - b(2, 0), b(1, 0) - b(0, 1));
    const double trace = b.trace();
    const Eigen::Matrix3d h = trace * Eigen::Matrix3d::Identity() - 0.5 * (b + b.transpose());
    Eigen::Vector3d w;
    if (!solve_positive_definite(h, g, w) || w.norm() > kMaxNewtonStep) w = g / (std::abs(trace) + kTiny);
    const double angle = w.norm();
    if (!(angle > kConverged)) return it;  // also stops on NaN input
    q = Eigen::Quaterniond(1.0, 0.5 * w.x(), 0.5 * w.y(), 0.5 * w.z()) * q;
    q.normalize();
  }
  return max_iterations;
}

}  // namespace tcb
