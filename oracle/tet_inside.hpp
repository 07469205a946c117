#pragma once
/// Exact classification of points against the tetrahedra of one body: the
/// oracle's answer where a surface test cannot be used (self-collision, and
/// bodies whose boundary surface is not closed), and what a CGAL user would
/// write for "which points lie in which tet" (CGAL box_intersection_d over
/// closed boxes, then exact orientation predicates, Epick: exact on double
/// input). Independent of method/: no symbolic perturbation here.
///
/// Contract, for a point p and the body's non-degenerate tets T (exactly flat
/// tets have no interior and are ignored):
/// - p is *inside* when it lies strictly inside some tet of T, or lies on the
///   closed boundary of some tet of T but on no boundary triangle of the body
///   (a point on an interior face, edge or vertex is inside the union);
/// - p is *on the boundary* when it lies on no tet's interior and on a closed
///   boundary triangle of the body;
/// - otherwise p is *outside*.
/// The tets are taken at the body's current positions: a tet inverted by the
/// motion still bounds the same region; a tet flat at the current positions
/// has no interior and is ignored. Ties are decided exactly: there are no
/// tolerances. For self-collision (classify_self_points) the same rule holds
/// with the tets incident to the queried vertex left out, so in a conforming,
/// undeformed mesh no vertex is inside its own body. Units: metres.

#include <cstdint>
#include <functional>
#include <vector>

#include "sim/world/world.hpp"

namespace tcb {

enum class TetSide : std::int8_t { Outside = 0, Boundary = 1, Inside = 2 };

/// For every point: its side of `body`'s tets at the body's current positions.
std::vector<TetSide> classify_points_in_tets(const Body& body, const std::vector<Vec3>& points_m);

/// For every vertex of `body`: its side of the body's own tets not incident to it.
std::vector<TetSide> classify_self_points(const Body& body);

/// For every vertex v of `body`: its side of the body's own tets t not
/// incident to v for which counts(v, t) holds (the same rule, the other tets
/// left out; boundary triangles stay the body's).
std::vector<TetSide> classify_self_points_among(const Body& body,
                                                const std::function<bool(std::int32_t, std::int32_t)>& counts);

}  // namespace tcb
