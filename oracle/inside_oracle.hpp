#pragma once
/// Exact ground truth of which vertices are inside which other object, and
/// how deep, computed independently of method/ (CGAL only; it never calls the
/// method's geometry code). Evaluated on the positions it is given; its time
/// is the run's oracle_ms, never handling time.
///
/// For every body B some other body collides with (the same pair rule as the
/// scene: distinct bodies, not both passive), B's boundary surface at the
/// current positions becomes a CGAL Surface_mesh with an AABB tree. Each
/// vertex p of every partner A is classified by Side_of_triangle_mesh (exact
/// predicates, three-valued): inside, on the boundary, or outside. An inside
/// vertex's true depth is its distance to B's surface (AABB tree,
/// Epick: inexact constructions, error ~1e-16 relative). A vertex inside
/// several bodies is reported with the smallest body index.
/// Limits, reported in `unmeasured` rather than silently skipped: a body whose
/// surface is not closed (Side_of_triangle_mesh needs a closed, non
/// self-intersecting surface; dog.mesh's folds open its surface), and
/// self-collision (not measured by this oracle yet). Self-intersection of a
/// surface is not checked (CGAL's check costs more than the query).
/// Units: metres.

#include <string>
#include <vector>

#include "sim/world/world.hpp"

namespace tcb {

struct OraclePoint {
  std::int32_t object = -1, vertex = -1, other = -1;
  double depth_m = 0.0;
};

struct OracleFrame {
  std::vector<OraclePoint> inside;                              ///< strictly inside another body
  std::vector<std::pair<std::int32_t, std::int32_t>> boundary;  ///< (object, vertex) on another's surface, inside none
  double max_depth_m = 0.0;
  std::vector<std::string> unmeasured;  ///< what the oracle could not decide this frame, in words
};

OracleFrame compute_inside_oracle(const World& world);

}  // namespace tcb
