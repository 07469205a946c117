#include "method/geometry/perturbed_predicates.hpp"

#include <algorithm>

#include "sim/geometry/orient3d.hpp"

namespace tcb {

int orient3d_perturbed_point(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) {
  // orient3d(a, b, c, p + delta) = n . (p - a) + n . delta with n = (b - a) x (c - a).
  if (const int s = orient3d(a, b, c, p); s != 0) return s;
  for (int axis = 0; axis < 3; ++axis)
    if (const int s = cross_product_sign(a, b, a, c, axis); s != 0) return s;
  return 0;
}

int orient3d_perturbed_edge(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b) {
  // orient3d(p + delta, q + delta, a, b) = orient3d(p, q, a, b) + ((q - p) x (b - a)) . delta.
  if (const int s = orient3d(p, q, a, b); s != 0) return s;
  for (int axis = 0; axis < 3; ++axis)
    if (const int s = cross_product_sign(p, q, a, b, axis); s != 0) return s;
  return 0;
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
  // four differences are taken once, and orient3d's own floating-point
  // filter (orient3d_filter, the same evaluation and bound) decides each
  // face it can without a call; a face it leaves open goes the whole exact
  // way. So the answer is exactly the four calls' (the randomized test in
  // perturbed_predicates_test.cpp compares them on near-degenerate input).
  const Vec3 d0 = v0 - p, d1 = v1 - p, d2 = v2 - p, d3 = v3 - p;
  const auto face_side = [&p](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& ad, const Vec3& bd,
                              const Vec3& cd) {
    const int s = orient3d_filter(ad, bd, cd);
    return s != 0 ? s : orient3d_perturbed_point(a, b, c, p);
  };
  const int side = face_side(v1, v2, v3, d1, d2, d3);
  if (side == 0) return false;
  if (face_side(v0, v3, v2, d0, d3, d2) != side) return false;
  if (face_side(v0, v1, v3, d0, d1, d3) != side) return false;
  return face_side(v0, v2, v1, d0, d2, d1) == side;
}

bool segment_crosses_triangle_perturbed(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const int sp = orient3d_perturbed_point(a, b, c, p);
  const int sq = orient3d_perturbed_point(a, b, c, q);
  if (sp == 0 || sq == 0 || sp == sq) return false;  // degenerate triangle, or both ends on one side
  // The crossing point is inside the triangle iff the segment's line passes
  // each triangle edge on the same side.
  const int s_ab = orient3d_perturbed_edge(p, q, a, b);
  const int s_bc = orient3d_perturbed_edge(p, q, b, c);
  const int s_ca = orient3d_perturbed_edge(p, q, c, a);
  return s_ab != 0 && s_ab == s_bc && s_bc == s_ca;
}

bool triangle_box_apart(const Vec3& edge_lo, const Vec3& edge_hi, const Vec3& a, const Vec3& b, const Vec3& c) {
  return (a.cwiseMax(b).cwiseMax(c).array() < edge_lo.array()).any() ||
         (a.cwiseMin(b).cwiseMin(c).array() > edge_hi.array()).any();
}

double segment_plane_parameter(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const double op = n.dot(p - a), oq = n.dot(q - a);
  const double denominator = op - oq;
  if (denominator == 0.0) return 0.0;
  return std::clamp(op / denominator, 0.0, 1.0);
}

}  // namespace tcb
