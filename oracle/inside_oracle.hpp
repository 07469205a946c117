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
/// A body whose surface is not closed (Side_of_triangle_mesh needs a closed,
/// non self-intersecting surface; dog.mesh's folds open its surface) is
/// decided by its tets instead (tet_inside.hpp: the same three-valued answer
/// for a well-formed body, tested), and its depths are distances to its
/// boundary triangles. Self-collision (bodies with self_collision, not
/// passive): a vertex inside its own body's tets not incident to it
/// (tet_inside.hpp). Its true depth is defined by the body's parts
/// (self_depth.hpp: distance to the surface of the parts outside the point's
/// own neighbourhood); a self-collision point inside its own or a
/// neighbouring part only, or of a body without parts, has none (NaN, left
/// out of depth errors and max_depth), and `unmeasured` says so. Recall and
/// precision of self-collision points are exact either way.
/// Self-intersection of a surface is not checked (CGAL's check costs more
/// than the query).
/// Units: metres.

#include <string>
#include <vector>

#include "sim/world/world.hpp"

namespace tcb {

struct OraclePoint {
  std::int32_t object = -1, vertex = -1, other = -1;
  double depth_m = 0.0;  ///< NaN for self-collision points without a true depth (self_depth.hpp)
};

struct OracleFrame {
  std::vector<OraclePoint> inside;                              ///< strictly inside another body
  std::vector<std::pair<std::int32_t, std::int32_t>> boundary;  ///< (object, vertex) on another's surface, inside none
  double max_depth_m = 0.0;
  std::vector<std::string> unmeasured;  ///< what the oracle could not decide this frame, in words
};

OracleFrame compute_inside_oracle(const World& world);

}  // namespace tcb
