#pragma once
/// Exact overlap volume of object pairs (docs/contract.md column overlap_volume,
/// summary overlap_volume_max), part of the oracle: CGAL corefinement
/// (corefine_and_compute_intersection) and PMP::volume with the exact kernel
/// (Epeck), on the bodies' boundary surfaces at their current positions.
///
/// Contract:
/// - Pairs: distinct bodies, not both passive (the scene's pair rule).
///   Self-overlap is not a volume and is not measured here.
/// - A pair whose bounding boxes do not overlap with positive volume has
///   overlap exactly 0 (touching boxes included: two plates resting face on
///   face overlap in a set of zero volume) and costs nothing.
/// - Guard: each surface involved must be closed, free of self-intersections
///   and bound a volume (PMP::does_self_intersect, does_bound_a_volume,
///   exact predicates). A pair that fails the guard, or whose corefinement
///   fails, has no value: it is listed in `invalid` with the reason, never
///   silently treated as 0.
/// - The volume is exact up to the final rounding to double. Units: m^3.

#include <string>
#include <vector>

#include "sim/world/world.hpp"

namespace tcb {

struct PairOverlap {
  std::int32_t a = -1, b = -1;  ///< a < b
  double volume_m3 = 0.0;
};

struct OverlapFrame {
  std::vector<PairOverlap> pairs;    ///< pairs with a positive-volume box overlap and a valid result
  double total_m3 = 0.0;             ///< over the valid pairs
  std::vector<std::string> invalid;  ///< pairs without a value, in words
};

OverlapFrame compute_overlap_volumes(const World& world);

/// Exact volume enclosed by a body's boundary surface (m^3); NaN when the
/// surface fails the guard above.
double enclosed_volume_m3(const Body& body);

}  // namespace tcb
