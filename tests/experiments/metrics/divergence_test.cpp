// Divergence (experiments/metrics/divergence.hpp) on states built by hand.
#include "experiments/metrics/divergence.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <cmath>

using namespace tcb;

namespace {

struct State {
  std::vector<std::vector<Vec3>> x, v;
};

State cube() {
  State s;
  std::vector<Vec3> x;
  for (int i = 0; i < 8; ++i) x.emplace_back(0.1 * (i & 1), 0.1 * ((i >> 1) & 1), 0.1 * ((i >> 2) & 1));
  s.x = {x, {Vec3(5, 5, 5)}};
  s.v = {std::vector<Vec3>(8, Vec3(0.0, -1.0, 0.0)), {Vec3::Zero()}};
  return s;
}

const std::vector<std::vector<double>> kMasses = {std::vector<double>(8, 0.5), {1.0}};
const std::vector<char> kDynamic = {1, 0};  // the second body is passive: never counted

}  // namespace

TEST_CASE("divergence of a state against itself is 0 in every field", "[divergence]") {
  const State a = cube();
  const Divergence d = compare_states({a.x, a.v}, {a.x, a.v}, kMasses, kDynamic);
  CHECK(d.rms_m == 0.0);
  CHECK(d.max_m == 0.0);
  CHECK(d.com_drift_m == 0.0);
  CHECK(d.orientation_drift_deg == 0.0);
  CHECK(d.linear_momentum_diff_n_s == 0.0);
  CHECK(d.angular_momentum_diff_n_m_s == 0.0);
}

TEST_CASE("divergence of a translated, rotated and sped-up body, by hand", "[divergence]") {
  const State reference = cube();
  State run = cube();
  const Vec3 centre(0.05, 0.05, 0.05);
  const Eigen::Matrix3d r = Eigen::AngleAxisd(10.0 * M_PI / 180.0, Vec3(0, 0, 1)).toRotationMatrix();
  for (Vec3& p : run.x[0]) p = centre + r * (p - centre) + Vec3(0.03, 0.0, 0.04);
  for (Vec3& v : run.v[0]) v += Vec3(0.2, 0.0, 0.0);
  run.x[1][0] += Vec3(100, 0, 0);  // passive: ignored
  const Divergence d = compare_states({run.x, run.v}, {reference.x, reference.v}, kMasses, kDynamic);
  CHECK(d.com_drift_m == Approx(0.05));          // |(0.03, 0, 0.04)|
  CHECK(d.orientation_drift_deg == Approx(10.0));
  CHECK(d.linear_momentum_diff_n_s == Approx(8 * 0.5 * 0.2));
  // Every vertex moved by the offset plus its rotation about the centre.
  double sum2 = 0.0, max = 0.0;
  for (std::size_t i = 0; i < 8; ++i) {
    const double e = (run.x[0][i] - reference.x[0][i]).norm();
    sum2 += e * e;
    max = std::max(max, e);
  }
  CHECK(d.rms_m == Approx(std::sqrt(sum2 / 8)));
  CHECK(d.max_m == Approx(max));
  // Uniform velocities carry no angular momentum about the centre, before and after.
  CHECK(d.angular_momentum_diff_n_m_s == Approx(0.0).margin(1e-12));
  CHECK_THROWS(compare_states({run.x, run.v}, {reference.x, reference.v}, {kMasses[0]}, kDynamic));
  // A non-finite state is NaN everywhere, never a small divergence.
  run.x[0][3] = Vec3(std::nan(""), 0, 0);
  const Divergence bad = compare_states({run.x, run.v}, {reference.x, reference.v}, kMasses, kDynamic);
  CHECK(std::isnan(bad.rms_m));
  CHECK(std::isnan(bad.max_m));
  CHECK(std::isnan(bad.com_drift_m));
}
