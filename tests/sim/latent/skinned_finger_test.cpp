// The skinned finger latent family: rest code reproduces the rest mesh, the
// analytic Jacobian matches central differences, the base stays put, rigidly
// skinned vertices move rigidly, presets and bad input.
#include "sim/latent/skinned_finger.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <stdexcept>

#include "sim/random/counter_random.hpp"

using namespace tcb;

namespace {

Eigen::VectorXd random_code(const SkinnedFinger& finger, std::uint64_t index) {
  Eigen::VectorXd z(finger.latent_size());
  for (Eigen::Index i = 0; i < z.size(); ++i)
    z[i] = uniform_pm1(2, index, static_cast<std::uint64_t>(i));
  return z;
}

}  // namespace

TEST_CASE("skinned finger: the rest code decodes to the rest mesh, all tets positive", "[skinned_finger]") {
  for (const char* name : {"finger_small", "finger_large"}) {
    const SkinnedFinger finger(finger_preset(name));
    const auto& rest = finger.mesh()->positions_m;
    const std::vector<Vec3> x = finger.decode(finger.rest_code());
    REQUIRE(x.size() == rest.size());
    double worst_m = 0.0;
    for (std::size_t v = 0; v < x.size(); ++v) worst_m = std::max(worst_m, (x[v] - rest[v]).norm());
    CHECK(worst_m <= 1e-12);
    for (const Tet& t : finger.mesh()->tets) REQUIRE(signed_volume(x[t[0]], x[t[1]], x[t[2]], x[t[3]]) > 0.0);
    CHECK(finger.latent_size() == 12);
    CHECK(part_count(*finger.mesh()) == 7);
  }
}

TEST_CASE("skinned finger: analytic jacobian matches central differences", "[skinned_finger]") {
  SkinnedFingerDesc desc = finger_preset("finger_small");
  const SkinnedFinger finger(desc);
  const double h = 1e-5;
  for (std::uint64_t sample = 0; sample < 5; ++sample) {
    Eigen::VectorXd z = random_code(finger, sample);
    if (sample == 4) z *= 1.5;  // outside [-1, 1]: the map extrapolates
    const Eigen::MatrixXd jac = finger.jacobian(z);
    REQUIRE(jac.rows() == static_cast<Eigen::Index>(3 * finger.mesh()->vertex_count()));
    REQUIRE(jac.cols() == finger.latent_size());
    Eigen::MatrixXd numeric(jac.rows(), jac.cols());
    for (int c = 0; c < finger.latent_size(); ++c) {
      Eigen::VectorXd plus = z, minus = z;
      plus[c] += h;
      minus[c] -= h;
      const std::vector<Vec3> xp = finger.decode(plus), xm = finger.decode(minus);
      for (std::size_t v = 0; v < xp.size(); ++v)
        numeric.block<3, 1>(static_cast<Eigen::Index>(3 * v), c) = (xp[v] - xm[v]) / (2.0 * h);
    }
    const double relative = (jac - numeric).norm() / numeric.norm();
    INFO("sample " << sample << " relative error " << relative);
    CHECK(relative < 1e-6);
  }
}

TEST_CASE("skinned finger: base-bone vertices never move", "[skinned_finger]") {
  const SkinnedFinger finger(finger_preset("finger_small"));
  const auto& rest = finger.mesh()->positions_m;
  int base_vertices = 0;
  for (std::uint64_t sample = 0; sample < 10; ++sample) {
    const Eigen::VectorXd z = random_code(finger, 100 + sample);
    const std::vector<Vec3> x = finger.decode(z);
    const Eigen::MatrixXd jac = finger.jacobian(z);
    base_vertices = 0;
    for (std::size_t v = 0; v < x.size(); ++v) {
      const auto& s = finger.skin()[v];
      if (s.proximal_bone != 0 || s.distal_bone != 0) continue;
      ++base_vertices;
      REQUIRE(x[v] == rest[v]);
      REQUIRE(jac.block(static_cast<Eigen::Index>(3 * v), 0, 3, jac.cols()).isZero(0.0));
    }
  }
  CHECK(base_vertices > 0);
  // The base's far end (x min) is in bone 0 only.
  for (std::size_t v = 0; v < rest.size(); ++v)
    if (rest[v].x() == -0.5 * finger.desc().size_m.x()) CHECK(finger.skin()[v].distal_bone == 0);
}

TEST_CASE("skinned finger: vertices on a single bone keep their pairwise distances", "[skinned_finger]") {
  const SkinnedFinger finger(finger_preset("finger_small"));
  const auto& rest = finger.mesh()->positions_m;
  const auto& skin = finger.skin();
  for (std::uint64_t sample = 0; sample < 5; ++sample) {
    const std::vector<Vec3> x = finger.decode(random_code(finger, 200 + sample));
    for (int bone = 0; bone < finger.desc().bones; ++bone) {
      std::vector<std::size_t> members;
      for (std::size_t v = 0; v < rest.size(); ++v)
        if (skin[v].proximal_bone == bone && skin[v].distal_bone == bone) members.push_back(v);
      REQUIRE(members.size() >= 2);
      double worst_m = 0.0;
      for (std::size_t a = 0; a < members.size(); ++a)
        for (std::size_t b = a + 1; b < members.size(); ++b)
          worst_m = std::max(worst_m, std::abs((x[members[a]] - x[members[b]]).norm() -
                                               (rest[members[a]] - rest[members[b]]).norm()));
      INFO("bone " << bone);
      CHECK(worst_m < 1e-12);
    }
  }
}

TEST_CASE("skinned finger: the full curl moves the tip far from rest", "[skinned_finger]") {
  const SkinnedFinger finger(finger_preset("finger_small"));
  const Eigen::VectorXd z = finger.full_curl_code();
  const std::vector<double> angles = finger.joint_angles_rad(z);
  for (std::size_t j = 0; j < angles.size(); ++j) {
    if (j % 2 == 0)
      CHECK(angles[j] == Approx(finger.desc().flex_max_deg * 3.141592653589793 / 180.0));
    else
      CHECK(angles[j] == 0.0);
  }
  // Curling towards -y: the tip's vertices end up below the bar's centre line.
  const std::vector<Vec3> x = finger.decode(z);
  const auto& rest = finger.mesh()->positions_m;
  double lowest_y = 0.0;
  for (std::size_t v = 0; v < x.size(); ++v) lowest_y = std::min(lowest_y, x[v].y());
  CHECK(lowest_y < -finger.desc().size_m.y());
  CHECK(x.size() == rest.size());
}

TEST_CASE("skinned finger: presets keep every tet positive over the code box", "[skinned_finger]") {
  // The blend is wide enough for the whole flexion range (see the header);
  // check random codes and the box's flexion/side-bend corners.
  for (const char* name : {"finger_small", "finger_large"}) {
    const SkinnedFinger finger(finger_preset(name));
    std::vector<Eigen::VectorXd> codes;
    for (std::uint64_t sample = 0; sample < 20; ++sample) codes.push_back(random_code(finger, 300 + sample));
    for (double side : {-1.0, 1.0}) {
      Eigen::VectorXd z = finger.full_curl_code();
      for (Eigen::Index i = 1; i < z.size(); i += 2) z[i] = side;
      codes.push_back(z);
    }
    codes.push_back(finger.full_curl_code());
    for (const Eigen::VectorXd& z : codes) {
      const std::vector<Vec3> x = finger.decode(z);
      for (const Tet& t : finger.mesh()->tets) REQUIRE(signed_volume(x[t[0]], x[t[1]], x[t[2]], x[t[3]]) > 0.0);
    }
  }
}

TEST_CASE("skinned finger: preset sizes, wrong-size codes and unknown presets", "[skinned_finger]") {
  const SkinnedFinger small(finger_preset("finger_small"));
  const SkinnedFinger large(finger_preset("finger_large"));
  CHECK(small.mesh()->vertex_count() >= 200);
  CHECK(small.mesh()->vertex_count() <= 600);
  CHECK(large.mesh()->vertex_count() >= 1000);
  CHECK(large.mesh()->vertex_count() <= 5000);

  CHECK_THROWS_AS(small.decode(Eigen::VectorXd::Zero(11)), std::invalid_argument);
  CHECK_THROWS_AS(small.jacobian(Eigen::VectorXd::Zero(13)), std::invalid_argument);
  CHECK_THROWS_AS(small.joint_angles_rad(Eigen::VectorXd()), std::invalid_argument);

  try {
    (void)finger_preset("finger_huge");
    FAIL("no throw");
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    CHECK(what.find("finger_small") != std::string::npos);
    CHECK(what.find("finger_large") != std::string::npos);
  }

  SkinnedFingerDesc bad = finger_preset("finger_small");
  bad.bones = 1;
  CHECK_THROWS_AS(SkinnedFinger(bad), std::invalid_argument);
  bad = finger_preset("finger_small");
  bad.flex_max_deg = bad.flex_min_deg;
  CHECK_THROWS_AS(SkinnedFinger(bad), std::invalid_argument);
  bad = finger_preset("finger_small");
  bad.blend_width_m = 1.0;
  CHECK_THROWS_AS(SkinnedFinger(bad), std::invalid_argument);
  bad = finger_preset("finger_small");
  bad.size_m.y() = 0.0;
  CHECK_THROWS_AS(SkinnedFinger(bad), std::invalid_argument);
}
