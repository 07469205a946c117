#include "experiments/metrics/divergence.hpp"

#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tcb {
namespace {

struct BodyMoments {
  Vec3 centre = Vec3::Zero(), momentum = Vec3::Zero(), angular = Vec3::Zero();
};

BodyMoments moments(const std::vector<Vec3>& x, const std::vector<Vec3>& v, const std::vector<double>& m) {
  BodyMoments out;
  double total = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    out.centre += m[i] * x[i];
    out.momentum += m[i] * v[i];
    total += m[i];
  }
  out.centre = total > 0.0 ? Vec3(out.centre / total) : Vec3::Zero();
  for (std::size_t i = 0; i < x.size(); ++i) out.angular += m[i] * (x[i] - out.centre).cross(v[i]);
  return out;
}

double rotation_angle_deg(const std::vector<Vec3>& x, const Vec3& c, const std::vector<Vec3>& x_ref, const Vec3& c_ref,
                          const std::vector<double>& m) {
  if (x.size() < 3) return 0.0;
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < x.size(); ++i) h += m[i] * (x_ref[i] - c_ref) * (x[i] - c).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  const Eigen::Matrix3d r = svd.matrixV() * d * svd.matrixU().transpose();
  const double cosine = std::clamp(0.5 * (r.trace() - 1.0), -1.0, 1.0);
  return std::acos(cosine) * 180.0 / M_PI;
}

}  // namespace

Divergence compare_states(const StateView& run, const StateView& reference,
                          const std::vector<std::vector<double>>& masses_kg, const std::vector<char>& dynamic) {
  const std::size_t bodies = run.x_m.size();
  if (reference.x_m.size() != bodies || masses_kg.size() != bodies || dynamic.size() != bodies ||
      run.v_m_per_s.size() != bodies || reference.v_m_per_s.size() != bodies)
    throw std::invalid_argument("compare_states: different body counts");
  Divergence out;
  double sum2 = 0.0;
  std::size_t vertices = 0;
  for (std::size_t b = 0; b < bodies; ++b) {
    if (!dynamic[b]) continue;
    const auto& x = run.x_m[b];
    const auto& xr = reference.x_m[b];
    if (xr.size() != x.size() || masses_kg[b].size() != x.size())
      throw std::invalid_argument("compare_states: different vertex counts");
    double body2 = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double d2 = (x[i] - xr[i]).squaredNorm();
      body2 += d2;
      out.max_m = std::max(out.max_m, std::sqrt(d2));
    }
    sum2 += body2;
    vertices += x.size();
    const BodyMoments a = moments(x, run.v_m_per_s[b], masses_kg[b]);
    const BodyMoments r = moments(xr, reference.v_m_per_s[b], masses_kg[b]);
    out.com_drift_m = std::max(out.com_drift_m, (a.centre - r.centre).norm());
    out.linear_momentum_diff_n_s = std::max(out.linear_momentum_diff_n_s, (a.momentum - r.momentum).norm());
    out.angular_momentum_diff_n_m_s = std::max(out.angular_momentum_diff_n_m_s, (a.angular - r.angular).norm());
    if (body2 > 0.0)  // an identical body: exactly 0, not an SVD's rounding
      out.orientation_drift_deg = std::max(out.orientation_drift_deg, rotation_angle_deg(x, a.centre, xr, r.centre, masses_kg[b]));
  }
  out.rms_m = vertices > 0 ? std::sqrt(sum2 / static_cast<double>(vertices)) : 0.0;
  // A non-finite state is not "close": std::max would drop its NaNs.
  if (!std::isfinite(sum2) || !std::isfinite(out.linear_momentum_diff_n_s + out.angular_momentum_diff_n_m_s)) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    out = Divergence{nan, nan, nan, nan, nan, nan};
  }
  return out;
}

}  // namespace tcb
