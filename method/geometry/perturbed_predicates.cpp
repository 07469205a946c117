#include "method/geometry/perturbed_predicates.hpp"

#include <algorithm>

#include "sim/geometry/orient3d.hpp"

namespace tcb {
namespace {

// The symbolic tie-breaks, for an exactly zero determinant (the header's
// rule): the signs of the eps-coefficients.
int point_tie_break(const Vec3& a, const Vec3& b, const Vec3& c) {
  // orient3d(a, b, c, p + delta) = n . (p - a) + n . delta with n = (b - a) x (c - a).
  for (int axis = 0; axis < 3; ++axis)
    if (const int s = cross_product_sign(a, b, a, c, axis); s != 0) return s;
  return 0;
}

int edge_tie_break(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b) {
  // orient3d(p + delta, q + delta, a, b) = orient3d(p, q, a, b) + ((q - p) x (b - a)) . delta.
  for (int axis = 0; axis < 3; ++axis)
    if (const int s = cross_product_sign(p, q, a, b, axis); s != 0) return s;
  return 0;
}

// The signs the filter below leaves open: the rest of the exact way
// (orient3d_unfiltered: the filter not repeated), then the tie-break. Kept
// out of line so that the filter's inline code stays small.
[[gnu::noinline]] int point_side_open(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) {
  if (const int s = orient3d_unfiltered(a, b, c, p); s != 0) return s;
  return point_tie_break(a, b, c);
}

[[gnu::noinline]] int edge_side_open(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b) {
  if (const int s = orient3d_unfiltered(p, q, a, b); s != 0) return s;
  return edge_tie_break(p, q, a, b);
}

// orient3d_perturbed_point(a, b, c, p), given the differences a - p, b - p,
// c - p: orient3d's own floating-point filter (orient3d_filter, the same
// evaluation and bound orient3d() starts with) decides the easy cases in
// the caller's code, without a call (hence always_inline: GCC left it a
// call); a sign it certifies is orient3d's, so the answer is exactly the
// function's.
[[gnu::always_inline]] inline int point_side(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p,
                                             const Vec3& ap, const Vec3& bp, const Vec3& cp) {
  const int s = orient3d_filter(ap, bp, cp);
  return s != 0 ? s : point_side_open(a, b, c, p);
}

// orient3d_perturbed_edge(p, q, a, b) the same way (orient3d(p, q, a, b)'s
// differences are p - b, q - b, a - b).
[[gnu::always_inline]] inline int edge_side(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b) {
  const int s = orient3d_filter(p - b, q - b, a - b);
  return s != 0 ? s : edge_side_open(p, q, a, b);
}

}  // namespace

int orient3d_perturbed_point(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) {
  if (const int s = orient3d(a, b, c, p); s != 0) return s;
  return point_tie_break(a, b, c);
}

int orient3d_perturbed_edge(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b) {
  if (const int s = orient3d(p, q, a, b); s != 0) return s;
  return edge_tie_break(p, q, a, b);
}

bool point_in_tet_perturbed(const Vec3& p, const Vec3& v0, const Vec3& v1, const Vec3& v2, const Vec3& v3) {
  // Inside iff p + delta is on the same side of all four faces (the faces of
  // tet_faces(): face k opposite vertex k): the inner side of every outward
  // face of a positively oriented tet (all -1), or of an inverted one (all
  // +1). The four perturbed volumes sum to the tet's, independent of p (the
  // faces' area vectors sum to zero, so the eps-coefficients cancel), so a
  // flat tet (volume 0: the zero polynomial) never has four equal signs: it
  // contains nothing.
  // Every face's orient3d(a, b, c, p) starts from a - p, b - p, c - p: the
  // four differences are taken once (point_side: the filter inline, the
  // answer exactly the four calls'; the randomized test in
  // perturbed_predicates_test.cpp compares them on near-degenerate input).
  const Vec3 d0 = v0 - p, d1 = v1 - p, d2 = v2 - p, d3 = v3 - p;
  const int side = point_side(v1, v2, v3, p, d1, d2, d3);
  if (side == 0) return false;
  if (point_side(v0, v3, v2, p, d0, d3, d2) != side) return false;
  if (point_side(v0, v1, v3, p, d0, d1, d3) != side) return false;
  return point_side(v0, v2, v1, p, d0, d2, d1) == side;
}

bool segment_crosses_triangle_perturbed(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const int sp = point_side(a, b, c, p, a - p, b - p, c - p);
  const int sq = point_side(a, b, c, q, a - q, b - q, c - q);
  if (sp == 0 || sq == 0 || sp == sq) return false;  // degenerate triangle, or both ends on one side
  // The crossing point is inside the triangle iff the segment's line passes
  // each triangle edge on the same side.
  // Each side is asked only while the answer is open: a side that differs
  // decides it, and on plates20's stagger (points on the neighbour's face
  // diagonals) a side can cost the exact way. (The calls are out of line, so
  // the compiler could not drop the later ones itself.)
  const int s_ab = edge_side(p, q, a, b);
  if (s_ab == 0 || edge_side(p, q, b, c) != s_ab) return false;
  return edge_side(p, q, c, a) == s_ab;
}

bool triangle_box_apart(const Vec3& edge_lo, const Vec3& edge_hi, const Vec3& a, const Vec3& b, const Vec3& c) {
  return boxes_apart(edge_lo, edge_hi, a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c));
}

double segment_plane_parameter(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const double op = n.dot(p - a), oq = n.dot(q - a);
  const double denominator = op - oq;
  if (denominator == 0.0) return 0.0;
  return std::clamp(op / denominator, 0.0, 1.0);
}

}  // namespace tcb
