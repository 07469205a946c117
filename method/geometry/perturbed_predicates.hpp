#pragma once
/// Exact collision predicates with one symbolic tie-break for touching
/// geometry (Simulation of Simplicity, Edelsbrunner & Muecke 1990).
///
/// Rule: the *query* side of every test (the point tested against a tet, the
/// edge tested against a surface triangle) is taken as translated by the
/// infinitesimal vector delta = (eps, eps^2, eps^3), 0 < eps << everything.
/// Every determinant is evaluated exactly (orient3d); only when it is exactly
/// zero does the perturbation decide, through the exact signs of the
/// coefficients of eps, eps^2, eps^3. Consequences:
/// - A point exactly on a face shared by two tets is inside exactly one of
///   them (they see the face with opposite normals); on an edge or vertex
///   shared by a conforming fan of tets, inside exactly one of the fan. These
///   hold while the tets around the point are not inverted: once a tet folds
///   over its neighbour, their regions overlap and a point may lie in both.
/// - The answer depends only on coordinates: never on hashing order, on which
///   tet is tested first, or on how a tet's vertices are numbered. delta is
///   fixed in the world frame, so touching decisions are unchanged by exact
///   translations and power-of-two scalings, but a rotation of the objects
///   may change them (a plate resting exactly on another may become "just
///   inside" it): tests/method/detection/degenerate_poses_test.cpp.
/// - Point-in-tet and edge-crosses-triangle use the same delta, so a point
///   found inside an object always has its border edges cross that object's
///   surface (a closed surface) an odd number of times: again for an object
///   with no inverted tets (an inverted one's surface self-intersects).
/// Degenerate elements: a flat tet (exact orientation 0) contains nothing; an
/// inverted tet contains the region it bounds; a
/// triangle with collinear vertices is crossed by nothing. Units: any (the
/// predicates are scale-free); inputs must meet orient3d's range contract.

#include "sim/mesh/tet_mesh.hpp"

namespace tcb {

/// Sign of orient3d(a, b, c, p + delta): +1 or -1, or 0 only when a, b, c are
/// collinear (or coincide).
int orient3d_perturbed_point(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p);

/// Sign of orient3d(p + delta, q + delta, a, b). 0 only when q - p is
/// parallel to b - a (then no transversal crossing is possible).
int orient3d_perturbed_edge(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b);

/// Whether p + delta lies inside the tet (v0, v1, v2, v3), positively
/// oriented or inverted by the motion: an inverted tet still bounds its
/// region (the oracle's rule, oracle/tet_inside.hpp). Returns false for a flat
/// tet.
bool point_in_tet_perturbed(const Vec3& p, const Vec3& v0, const Vec3& v1, const Vec3& v2, const Vec3& v3);

/// Whether the segment (p + delta, q + delta) crosses triangle (a, b, c).
/// Because the perturbed segment never touches the triangle's plane or edges
/// at an end point, the answer is a clean yes or no.
bool segment_crosses_triangle_perturbed(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c);

/// Whether box [lo, hi] lies strictly apart from the box [edge_lo, edge_hi]
/// along some axis: exact comparisons, boxes that touch are not apart, and a
/// NaN coordinate decides nothing on its axis. triangle_box_apart() on the
/// triangle's box; inline for the border search, which keeps hashed boxes.
inline bool boxes_apart(const Vec3& edge_lo, const Vec3& edge_hi, const Vec3& lo, const Vec3& hi) {
  return (hi.array() < edge_lo.array()).any() || (lo.array() > edge_hi.array()).any();
}

/// Whether the box of triangle (a, b, c) lies strictly apart from the box
/// [edge_lo, edge_hi] of a segment (its end points' componentwise min and
/// max) along some axis. Then segment_crosses_triangle_perturbed() is false
/// for that segment: the perturbation is infinitesimal, so a crossing would
/// put a point in both closed boxes. Exact comparisons; boxes that touch are
/// not apart (they go on to the predicates). A cheap rejection before them.
bool triangle_box_apart(const Vec3& edge_lo, const Vec3& edge_hi, const Vec3& a, const Vec3& b, const Vec3& c);

/// The parameter t in [0, 1] where segment p->q meets the plane of (a, b, c),
/// in floating point (a construction, not a decision): t = o_p / (o_p - o_q)
/// of the two signed volumes, clamped to [0, 1]; 0 when p lies on the plane.
double segment_plane_parameter(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace tcb
