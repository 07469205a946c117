#include "sim/dynamics/rotation_extraction.hpp"

#include <catch2/catch.hpp>

#include <random>

using namespace tcb;

namespace {
Eigen::Matrix3d random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n;
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  q.normalize();
  return q.toRotationMatrix();
}
}  // namespace

TEST_CASE("rotation extraction recovers the rotation of rotated stretches", "[dynamics]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> stretch(0.5, 2.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Matrix3d q = random_rotation(rng);
    const Eigen::Matrix3d u = random_rotation(rng);
    const Eigen::Matrix3d s = u * Eigen::Vector3d(stretch(rng), stretch(rng), stretch(rng)).asDiagonal() * u.transpose();
    Eigen::Quaterniond r = Eigen::Quaterniond::Identity();
    extract_rotation(q * s, r, 200);
    REQUIRE((r.toRotationMatrix() - q).norm() < 1e-7);
  }
}

TEST_CASE("rotation extraction returns a proper rotation for flat and inverted F", "[dynamics]") {
  Eigen::Matrix3d flat = Eigen::Matrix3d::Identity();
  flat(2, 2) = 0.0;
  Eigen::Matrix3d inverted = Eigen::Matrix3d::Identity();
  inverted(1, 1) = -0.5;
  for (const Eigen::Matrix3d& f : {flat, inverted, Eigen::Matrix3d(Eigen::Matrix3d::Zero())}) {
    Eigen::Quaterniond r = Eigen::Quaterniond::Identity();
    extract_rotation(f, r);
    const Eigen::Matrix3d m = r.toRotationMatrix();
    CHECK(m.allFinite());
    CHECK(m.determinant() == Approx(1.0));
  }
}
