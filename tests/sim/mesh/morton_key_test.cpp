// Morton keys: a layout, so what matters is that the key is the documented
// interleaving and is defined for any input.
#include "sim/mesh/morton_key.hpp"

#include <catch2/catch.hpp>

#include <limits>

using namespace tcb;

TEST_CASE("a Morton key interleaves the three scaled coordinates, x lowest; the box's corners are the extreme keys",
          "[mesh][morton]") {
  const Vec3 lo(-1.0, 0.0, 2.0), hi(1.0, 4.0, 3.0);
  CHECK(morton_key(lo, lo, hi) == 0);
  CHECK(morton_key(hi, lo, hi) == (std::uint64_t(1) << 63) - 1);  // 63 ones
  // A step of 2^-20 of the extent along one axis sets that axis's lowest bit
  // (floor(2^-20 (2^21 - 1)) = 1), x's at bit 0, y's at 1, z's at 2.
  const double step = 1.0 / 1048576.0;
  CHECK(morton_key(Vec3(-1.0 + 2.0 * step, 0.0, 2.0), lo, hi) == 1);
  CHECK(morton_key(Vec3(-1.0, 4.0 * step, 2.0), lo, hi) == 2);
  CHECK(morton_key(Vec3(-1.0, 0.0, 2.0 + step), lo, hi) == 4);
  // Just past halfway along x (t = 1/2 + 2^-21): x's top bit alone, at bit 60.
  CHECK(morton_key(Vec3(step, 0.0, 2.0), lo, hi) == std::uint64_t(1) << 60);
}

TEST_CASE("a Morton key is defined for any input: outside the box clamps, a NaN or an empty extent gives 0 on "
          "that axis",
          "[mesh][morton]") {
  const Vec3 lo(0.0, 0.0, 0.0), hi(1.0, 1.0, 1.0);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  CHECK(morton_key(Vec3(-5.0, -kInf, -1e300), lo, hi) == 0);
  CHECK(morton_key(Vec3(5.0, kInf, 1e300), lo, hi) == morton_key(hi, lo, hi));
  CHECK(morton_key(Vec3(kNaN, kNaN, kNaN), lo, hi) == 0);
  CHECK(morton_key(Vec3(kNaN, 1.0, kNaN), lo, hi) == morton_key(Vec3(0.0, 1.0, 0.0), lo, hi));
  // A flat box (all points on a plane): that axis contributes nothing.
  CHECK(morton_key(Vec3(0.5, 0.5, 7.0), Vec3(0.0, 0.0, 7.0), Vec3(1.0, 1.0, 7.0)) ==
        morton_key(Vec3(0.5, 0.5, 0.0), lo, Vec3(1.0, 1.0, 0.0)));
}

TEST_CASE("the bounding box the keys are scaled in holds every point and touches each face", "[mesh][morton]") {
  const auto [lo, hi] = bounding_box({Vec3(1.0, -2.0, 0.5), Vec3(-3.0, 4.0, 0.5), Vec3(0.0, 0.0, -7.0)});
  CHECK(lo == Vec3(-3.0, -2.0, -7.0));
  CHECK(hi == Vec3(1.0, 4.0, 0.5));
  CHECK_THROWS_AS(bounding_box({}), std::out_of_range);
}
