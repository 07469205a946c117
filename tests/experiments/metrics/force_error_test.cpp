// Force error (experiments/metrics/force_error.hpp): the definition checked by
// hand on a synthetic two-contact case, and its edge cases.
#include "experiments/metrics/force_error.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace tcb;

TEST_CASE("force error of a synthetic two-contact case, by hand", "[force_error]") {
  // One body of 4 vertices. Full's exact points: 0 and 1. The method gave
  // point 0 a force held from an earlier step (tilted by 90 degrees and
  // halved), missed point 1, and gave point 2 an extrapolated ghost force.
  // Vertex 3 receives reactions on both sides.
  const ForceField reference = {{Vec3(0, 2, 0), Vec3(0, 1, 0), Vec3::Zero(), Vec3(0, -3, 0)}};
  const ForceField applied = {{Vec3(1, 0, 0), Vec3::Zero(), Vec3(0, 0, 2), Vec3(-1, 0, -2)}};
  const std::vector<ForcePoint> exact = {{0, 0, ForceSource::Computed}, {0, 1, ForceSource::Computed}};
  const std::vector<ForcePoint> method = {{0, 0, ForceSource::Held}, {0, 2, ForceSource::Extrapolated}};
  const ForceError e = compare_forces(applied, method, reference, exact);
  // |F_m - F_r|^2 = (1 + 4) + 1 + 4 + (1 + 9 + 4) = 24; |F_r|^2 = 4 + 1 + 9 = 14.
  REQUIRE(e.relative_l2.has_value());
  CHECK(*e.relative_l2 == Approx(std::sqrt(24.0 / 14.0)));
  CHECK(e.reference_norm_n == Approx(std::sqrt(14.0)));
  CHECK(e.reference_points == 2);
  CHECK(e.applied_points == 2);
  CHECK(e.missed == 1);  // point 1
  CHECK(e.ghosts == 1);  // point 2
  REQUIRE(e.angle_deg.size() == 1);  // only point 0 is in both sets
  CHECK(e.angle_deg[0] == Approx(90.0));
  const SourceForceError& held = e.by_source[static_cast<std::size_t>(ForceSource::Held)];
  const SourceForceError& extrapolated = e.by_source[static_cast<std::size_t>(ForceSource::Extrapolated)];
  CHECK(held.points == 1);
  CHECK(held.ghosts == 0);
  CHECK(held.squared_error_n2 == Approx(5.0));
  CHECK(extrapolated.points == 1);
  CHECK(extrapolated.ghosts == 1);
  CHECK(extrapolated.squared_error_n2 == Approx(4.0));
  CHECK(extrapolated.angle_deg.empty());
  CHECK(e.by_source[static_cast<std::size_t>(ForceSource::Computed)].points == 0);
}

TEST_CASE("force error: identical fields are 0, an empty reference is 0 or undefined", "[force_error]") {
  const ForceField f = {{Vec3(1, 2, 3), Vec3(-1, 0, 0)}, {Vec3(0, 0, 1e-12)}};
  const std::vector<ForcePoint> points = {{0, 0, ForceSource::Computed}, {1, 0, ForceSource::Computed}};
  const ForceError same = compare_forces(f, points, f, points);
  CHECK(same.relative_l2 == 0.0);
  CHECK(same.missed == 0);
  CHECK(same.ghosts == 0);
  for (double a : same.angle_deg) CHECK(a == 0.0);  // atan2 form: exactly 0 for parallel forces

  const ForceField zero = {{Vec3::Zero(), Vec3::Zero()}, {Vec3::Zero()}};
  CHECK(compare_forces(zero, {}, zero, {}).relative_l2 == 0.0);
  const ForceError ghost_only = compare_forces(f, points, zero, {});
  CHECK_FALSE(ghost_only.relative_l2.has_value());
  CHECK(ghost_only.ghosts == 2);
  // Opposite forces: 180 degrees, not NaN.
  const ForceField opposite = {{Vec3(-1, -2, -3), Vec3(-1, 0, 0)}, {Vec3(0, 0, 1e-12)}};
  const ForceError flipped = compare_forces(opposite, points, f, points);
  REQUIRE(flipped.angle_deg.size() == 2);
  CHECK(flipped.angle_deg[0] == Approx(180.0));
  CHECK_THROWS(compare_forces(f, points, ForceField{{Vec3::Zero()}}, points));
}
