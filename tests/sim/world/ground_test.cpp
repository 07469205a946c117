// The ground's projection, vertex by vertex: what it does to a vertex below
// the plane (lifted, its fall stopped, Coulomb friction on the tangential
// velocity), and that it leaves rising vertices' velocity and vertices above
// the plane alone.
#include "sim/world/ground.hpp"

#include <catch2/catch.hpp>

#include <vector>

using namespace tcb;

TEST_CASE("ground: a falling vertex below the plane is lifted and its fall stopped; one above is untouched",
          "[ground]") {
  const GroundPlane ground{0.0, 0.0};  // frictionless: only the normal velocity goes
  std::vector<Vec3> x{Vec3(0.0, -0.01, 0.0), Vec3(1.0, 0.5, 0.0), Vec3(2.0, 0.0, 0.0)};
  std::vector<Vec3> v{Vec3(2.0, -3.0, 0.0), Vec3(0.0, -3.0, 0.0), Vec3(0.0, -1.0, 0.0)};
  CHECK(apply_ground(ground, x, v) == 1);  // on the plane is not below it
  CHECK(x[0] == Vec3(0.0, 0.0, 0.0));
  CHECK(v[0] == Vec3(2.0, 0.0, 0.0));
  CHECK(x[1] == Vec3(1.0, 0.5, 0.0));
  CHECK(v[1] == Vec3(0.0, -3.0, 0.0));
  CHECK(v[2] == Vec3(0.0, -1.0, 0.0));
}

TEST_CASE("ground: a vertex below the plane that already rises is lifted, its velocity kept", "[ground]") {
  const GroundPlane ground{0.1, 0.5};
  std::vector<Vec3> x{Vec3(0.0, 0.05, 0.0)};
  std::vector<Vec3> v{Vec3(1.0, 0.2, 0.0)};
  CHECK(apply_ground(ground, x, v) == 1);
  CHECK(x[0].y() == 0.1);
  CHECK(v[0] == Vec3(1.0, 0.2, 0.0));  // friction acts only with the normal velocity it removes
}

TEST_CASE("ground: friction removes at most mu times the removed normal speed, and sticks below it", "[ground]") {
  const GroundPlane ground{0.0, 0.5};
  std::vector<Vec3> x{Vec3(0.0, -1e-3, 0.0), Vec3(0.0, -1e-3, 0.0)};
  std::vector<Vec3> v{Vec3(3.0, -2.0, 4.0), Vec3(0.3, -2.0, 0.4)};
  CHECK(apply_ground(ground, x, v) == 2);
  // |v_t| = 5, reduced by 0.5 * 2 = 1: kept direction, speed 4.
  CHECK(v[0].x() == Approx(2.4));
  CHECK(v[0].z() == Approx(3.2));
  CHECK(v[0].y() == 0.0);
  // |v_t| = 0.5 < 1: sticks.
  CHECK(v[1] == Vec3::Zero());
}
