#pragma once
/// The axis-aligned box around a set of boxes, for the point query's first
/// test (tet_hash_detection.hpp): a point outside the union of a body's tet
/// boxes is outside each of them, so no tet of that body can pass the
/// query's box test.
///
/// Contract (units: those of the boxes, m in the detector):
///   - Exact: lo and hi are the exact minimum and maximum of the added boxes'
///     coordinates (no rounding: min and max of doubles). Empty: lo = +inf,
///     hi = -inf, so every point without a NaN coordinate is outside and
///     every box grows it. A NaN coordinate of a point decides nothing on its
///     axis (its comparisons are false), as in the query's box test; the
///     point is rejected only by another axis.
///   - Touching counts as inside: rejects(p) is true only when p is strictly
///     below lo or strictly above hi along some axis, the query's box test
///     exactly (a point on a box's face is tested).
///   - NaN: once a box holding a NaN coordinate was added, rejects()
///     nothing, as no comparison with the NaN box's own coordinate rejects
///     in the query. Caught by `probe`, the running sum of every coordinate
///     added, which a NaN makes NaN for good; inf - inf in that sum does
///     too, which only costs rejections, never makes a wrong one (with boxes
///     reaching both infinities, whether it happens may depend on the order
///     of the sum, so on how many threads built the union; answers and work
///     do not). One sum, not a NaN test in every min and max. The evidence
///     for that choice is weak on this noisy machine: as a share of the kept
///     table's refresh time (micro_collision_cycle ms_hash_tets, paired
///     against the refresh without unions), NaN tests in every min measured
///     1.09-1.16 in 3-round runs, the sum 1.09-1.10 in one 3-round run and
///     1.01-1.03 over 6 rounds, plain min and max with no NaN handling 0.99.
///   - Infinite coordinates are ordinary values.

#include <limits>

#include "sim/mesh/tet_mesh.hpp"

namespace tcb {

struct BoxUnion {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = Vec3::Constant(-std::numeric_limits<double>::infinity());
  double probe = 0.0;  ///< sum of every coordinate added (NaN once one was NaN)

  void add_box(const Vec3& box_lo, const Vec3& box_hi) {
    lo = lo.cwiseMin(box_lo);
    hi = hi.cwiseMax(box_hi);
    probe += box_lo.sum() + box_hi.sum();
  }
  void add_union(const BoxUnion& other) {
    lo = lo.cwiseMin(other.lo);
    hi = hi.cwiseMax(other.hi);
    probe += other.probe;
  }
  bool poisoned() const { return probe != probe; }
  /// Whether p is outside every added box: strictly outside along an axis.
  /// Never true once poisoned.
  bool rejects(const Vec3& p) const {
    return !poisoned() && ((p.array() < lo.array()).any() || (p.array() > hi.array()).any());
  }
  /// Whether box [box_lo, box_hi] lies strictly apart from every added box
  /// (strictly apart from the union along some axis): no point of the union
  /// is in it, touching counting as in, as for rejects(). Never true once
  /// poisoned; a NaN coordinate of the box decides nothing on its axis (only
  /// another axis can make the box miss, and then no point of the union
  /// passes the query's box test either).
  bool misses(const Vec3& box_lo, const Vec3& box_hi) const {
    return !poisoned() && ((box_hi.array() < lo.array()).any() || (box_lo.array() > hi.array()).any());
  }
  /// Whether p is outside every added box grown by margin_m, each grown as
  /// the widened query grows a tet's box (lo - margin, hi + margin, rounded
  /// to double): rounding is monotone, so lo - margin here is at or below
  /// every added box's grown lo (and hi + margin at or above its grown hi),
  /// and a p strictly outside this grown union is strictly outside each
  /// grown box. Never true for a NaN margin (a NaN bound compares false),
  /// nor for an infinite one beside an infinite bound (inf - inf is NaN);
  /// margin 0 is rejects(p).
  bool rejects(const Vec3& p, double margin_m) const {
    const Vec3 grow = Vec3::Constant(margin_m);
    const Vec3 grown_lo = lo - grow, grown_hi = hi + grow;
    return !poisoned() && ((p.array() < grown_lo.array()).any() || (p.array() > grown_hi.array()).any());
  }
};

}  // namespace tcb
