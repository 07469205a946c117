#include "method/handler/force_extrapolation.hpp"

#include <catch2/catch.hpp>

using namespace tcb;

namespace {
Contact with_force(const Vec3& f) {
  Contact c;
  c.force_n = f;
  return c;
}
}  // namespace

TEST_CASE("a linearly growing depth-based force is extrapolated exactly", "[extrapolation]") {
  // Depth-based forces f(s) = (2 + 0.5 s, -s, 3) at the ends of cycles of n = 4 steps.
  const auto truth = [](double s) { return Vec3(2.0 + 0.5 * s, -s, 3.0); };
  ForceHistory h;
  record_depth_force(h, with_force(truth(4)), 4, 4);
  CHECK(extrapolated_force(h, 6) == truth(4));  // one force only: held
  record_depth_force(h, with_force(truth(8)), 8, 4);
  for (int s = 9; s <= 12; ++s) {
    const Vec3 f = extrapolated_force(h, s);
    CHECK((f - truth(s)).norm() < 1e-12);
  }
}

TEST_CASE("a decreasing force is clamped to zero instead of flipping", "[extrapolation]") {
  ForceHistory h;
  record_depth_force(h, with_force(Vec3(0, 3, 0)), 1, 1);
  record_depth_force(h, with_force(Vec3(0, 2, 0)), 2, 1);  // df = (0, -1, 0) per step
  CHECK(extrapolated_force(h, 3) == Vec3(0, 1, 0));
  CHECK(extrapolated_force(h, 4) == Vec3(0, 0, 0));
  CHECK(extrapolated_force(h, 5) == Vec3::Zero());  // would be (0, -1, 0): clamped
  CHECK(h.stopped);
  CHECK(extrapolated_force(h, 6) == Vec3::Zero());  // and stays zero
  CHECK(extrapolated_force(h, 3) == Vec3::Zero());  // until the next depth-based force
  record_depth_force(h, with_force(Vec3(0, 0.5, 0)), 7, 5);
  CHECK_FALSE(h.stopped);
  CHECK(h.f2 == Vec3(0, 2, 0));  // history holds depth-based forces only
  CHECK(extrapolated_force(h, 7) == Vec3(0, 0.5, 0));
}

TEST_CASE("an increasing force may pass through nothing odd; no history gives nothing", "[extrapolation]") {
  ForceHistory empty;
  CHECK(extrapolated_force(empty, 10) == Vec3::Zero());
  ForceHistory h;
  record_depth_force(h, with_force(Vec3(1, 0, 0)), 1, 2);
  record_depth_force(h, with_force(Vec3(3, 0, 0)), 3, 2);
  CHECK(extrapolated_force(h, 5) == Vec3(5, 0, 0));
  CHECK_FALSE(h.stopped);
}
