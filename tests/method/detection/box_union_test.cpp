// The box around boxes, the point query's first test: exact, touching
// counts as inside, a NaN box makes it reject nothing.
#include "method/detection/box_union.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

using namespace tcb;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}  // namespace

TEST_CASE("an empty union rejects every point; a box's union is that box, its faces inside", "[detection][box_union]") {
  BoxUnion u;
  CHECK(u.rejects(Vec3::Zero()));
  CHECK(u.rejects(Vec3(1e300, -1e300, 0.0)));
  u.add_box(Vec3(-1.0, 0.0, 2.0), Vec3(1.0, 0.5, 3.0));
  CHECK(u.lo == Vec3(-1.0, 0.0, 2.0));
  CHECK(u.hi == Vec3(1.0, 0.5, 3.0));
  CHECK_FALSE(u.rejects(Vec3(0.0, 0.25, 2.5)));
  CHECK_FALSE(u.rejects(Vec3(-1.0, 0.0, 2.0)));  // a corner: touching is inside
  CHECK_FALSE(u.rejects(Vec3(1.0, 0.5, 3.0)));
  CHECK(u.rejects(Vec3(std::nextafter(-1.0, -2.0), 0.25, 2.5)));  // one ulp out
  CHECK(u.rejects(Vec3(0.0, std::nextafter(0.5, 1.0), 2.5)));
  CHECK(u.rejects(Vec3(0.0, 0.25, std::nextafter(3.0, 4.0))));
}

TEST_CASE("a union is exact at any scale, and merging unions is adding their boxes", "[detection][box_union]") {
  for (const double scale : {1e-12, 1.0, 1e12}) {
    INFO("scale " << scale);
    BoxUnion all, first, second;
    const Vec3 boxes[4][2] = {{Vec3(0, 0, 0), Vec3(1, 1, 1)},
                              {Vec3(-3, 0.5, 0.25), Vec3(-2, 0.75, 0.5)},
                              {Vec3(0.1, -7, 0.3), Vec3(0.2, -6, 9)},
                              {Vec3(0.3, 0.3, -1e-3), Vec3(0.4, 0.4, 0.4)}};
    for (int i = 0; i < 4; ++i) {
      all.add_box(scale * boxes[i][0], scale * boxes[i][1]);
      (i < 2 ? first : second).add_box(scale * boxes[i][0], scale * boxes[i][1]);
    }
    BoxUnion merged = first;
    merged.add_union(second);
    merged.add_union(BoxUnion{});  // an empty union changes nothing
    CHECK(merged.lo == all.lo);
    CHECK(merged.hi == all.hi);
    CHECK(all.lo == scale * Vec3(-3, -7, -1e-3));
    CHECK(all.hi == scale * Vec3(1, 1, 9));
    CHECK_FALSE(all.poisoned());
  }
}

TEST_CASE("a NaN box, added or merged, makes the union reject nothing, for good; infinite boxes are ordinary",
          "[detection][box_union]") {
  BoxUnion u;
  u.add_box(Vec3(0, 0, 0), Vec3(1, 1, 1));
  u.add_box(Vec3(0.5, kNaN, 0.5), Vec3(0.6, 0.6, 0.6));
  CHECK(u.poisoned());
  CHECK_FALSE(u.rejects(Vec3(100, 100, 100)));  // far outside every finite box
  u.add_box(Vec3(2, 2, 2), Vec3(3, 3, 3));
  CHECK_FALSE(u.rejects(Vec3(-100, 0.5, 0.5)));  // still
  BoxUnion clean, merged;
  clean.add_box(Vec3(0, 0, 0), Vec3(1, 1, 1));
  merged = clean;
  merged.add_union(u);
  CHECK_FALSE(merged.rejects(Vec3(100, 100, 100)));
  // A box reaching to infinity on one side: ordinary (its sum is -inf, not NaN).
  BoxUnion half;
  half.add_box(Vec3(-kInf, 0, 0), Vec3(1, 1, 1));
  CHECK_FALSE(half.poisoned());
  CHECK_FALSE(half.rejects(Vec3(-1e300, 0.5, 0.5)));
  CHECK(half.rejects(Vec3(2, 0.5, 0.5)));
  // Both infinities: the sum is NaN, so the union stops rejecting (a lost
  // rejection, never a wrong one).
  half.add_box(Vec3(0, 0, 0), Vec3(kInf, 1, 1));
  CHECK_FALSE(half.rejects(Vec3(2, 5, 0.5)));
}

TEST_CASE("a union grown by a margin rejects a point only when every box grown as the query grows it would, "
          "at any scale; a NaN margin rejects nothing",
          "[detection][box_union]") {
  // The widened query grows each stored box by the margin (lo - m, hi + m,
  // rounded) and rejects p outside it. The grown union must never reject a
  // point some grown box holds, and should reject one ulp beyond the
  // extreme grown face (the rounding is the same there).
  for (const double scale : {1e-12, 1.0, 1e12})
    for (const double margin_scale : {0.0, 1e-17, 0.3, 7.0}) {
      const double margin = margin_scale * scale;
      INFO("scale " << scale << ", margin " << margin);
      const Vec3 boxes[3][2] = {{Vec3(0.1, 0.2, 0.3), Vec3(1, 1, 1)},
                                {Vec3(-3.3, 0.5, 0.25), Vec3(-2, 0.75, 0.5)},
                                {Vec3(0.1, -7.7, 0.3), Vec3(0.2, -6, 9.1)}};
      BoxUnion u;
      for (const auto& b : boxes) u.add_box(scale * b[0], scale * b[1]);
      const auto some_grown_box_holds = [&](const Vec3& p) {
        for (const auto& b : boxes) {
          const Vec3 lo = scale * b[0] - Vec3::Constant(margin), hi = scale * b[1] + Vec3::Constant(margin);
          if ((p.array() >= lo.array()).all() && (p.array() <= hi.array()).all()) return true;
        }
        return false;
      };
      // The extreme grown faces, each touched (held) and one ulp beyond (rejected).
      for (int axis = 0; axis < 3; ++axis)
        for (const bool low : {true, false})
          for (const auto& b : boxes) {
            const Vec3 lo = scale * b[0], hi = scale * b[1];
            if ((low ? lo[axis] != u.lo[axis] : hi[axis] != u.hi[axis])) continue;  // not the extreme box
            Vec3 p = 0.5 * (lo + hi);
            p[axis] = low ? lo[axis] - margin : hi[axis] + margin;
            CHECK(some_grown_box_holds(p));
            CHECK_FALSE(u.rejects(p, margin));
            p[axis] = std::nextafter(p[axis], low ? -kInf : kInf);
            CHECK_FALSE(some_grown_box_holds(p));
            CHECK(u.rejects(p, margin));
          }
      // A grid of points over the grown union and beyond: never a rejection
      // where a grown box holds p.
      int held = 0, rejected = 0;
      const Vec3 from = u.lo - Vec3::Constant(margin + scale), to = u.hi + Vec3::Constant(margin + scale);
      const Vec3 step = (to - from) / 23.0;
      for (int i = 0; i <= 23; ++i)
        for (int j = 0; j <= 23; ++j)
          for (int k = 0; k <= 23; ++k) {
            const Vec3 p = from + Vec3(i * step.x(), j * step.y(), k * step.z());
            const bool holds = some_grown_box_holds(p);
            if (holds) CHECK_FALSE(u.rejects(p, margin));
            held += holds;
            rejected += u.rejects(p, margin);
          }
      CHECK(held > 0);
      CHECK(rejected > 0);
      for (const Vec3& p : {Vec3(scale * Vec3(0.5, 0.5, 0.5)), Vec3(scale * Vec3(-2.5, 0.6, 0.3)), Vec3(scale * Vec3(9, 9, 9))})
        CHECK(u.rejects(p, 0.0) == u.rejects(p));
      CHECK_FALSE(u.rejects(scale * Vec3(100, 100, 100), kNaN));
    }
}
