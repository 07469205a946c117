#include "oracle/tet_inside.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>

namespace tcb {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::int32_t>;

Point point_of(const Vec3& x) { return Point(x.x(), x.y(), x.z()); }

// Per tet, bit i set when the face opposite local vertex i is a boundary triangle.
std::vector<std::uint8_t> boundary_face_masks(const TetMesh& mesh) {
  std::vector<std::uint8_t> mask(mesh.tet_count(), 0);
  for (std::size_t f = 0; f < mesh.surface.size(); ++f) {
    const Tet& t = mesh.tets[mesh.surface_tet[f]];
    const Triangle& tri = mesh.surface[f];
    for (int i = 0; i < 4; ++i)
      if (std::find(tri.begin(), tri.end(), t[i]) == tri.end()) mask[mesh.surface_tet[f]] |= std::uint8_t(1u << i);
  }
  return mask;
}

struct Touch {
  bool strictly_inside = false, touches = false, on_boundary_face = false;
};

// `self`: the points are the body's vertices, and a tet incident to the
// queried vertex, or one `counts` rejects, is left out.
using TetFilter = std::function<bool(std::int32_t, std::int32_t)>;

std::vector<TetSide> classify(const Body& body, const std::vector<Vec3>& points_m, bool self,
                              const TetFilter& counts = nullptr) {
  const TetMesh& mesh = *body.mesh;
  const std::vector<std::uint8_t> masks = boundary_face_masks(mesh);
  std::vector<Box> point_boxes, tet_boxes;
  point_boxes.reserve(points_m.size());
  for (std::size_t i = 0; i < points_m.size(); ++i)
    point_boxes.emplace_back(point_of(points_m[i]).bbox(), static_cast<std::int32_t>(i));
  std::vector<Point> x(body.x_m.size());
  for (std::size_t v = 0; v < x.size(); ++v) x[v] = point_of(body.x_m[v]);
  std::vector<CGAL::Orientation> tet_orientation(mesh.tet_count());
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    const Tet& tet = mesh.tets[t];
    tet_orientation[t] = CGAL::orientation(x[tet[0]], x[tet[1]], x[tet[2]], x[tet[3]]);
    if (tet_orientation[t] == CGAL::COPLANAR) continue;  // flat now: no interior
    tet_boxes.emplace_back(x[tet[0]].bbox() + x[tet[1]].bbox() + x[tet[2]].bbox() + x[tet[3]].bbox(),
                           static_cast<std::int32_t>(t));
  }
  std::vector<Touch> touch(points_m.size());
  const auto test = [&](const Box& pb, const Box& tb) {
    const std::int32_t i = pb.info(), t = tb.info();
    const Tet& tet = mesh.tets[t];
    if (self && std::find(tet.begin(), tet.end(), i) != tet.end()) return;  // incident to the queried vertex
    if (counts && !counts(i, t)) return;
    const Point p = point_of(points_m[i]);
    const CGAL::Orientation o = tet_orientation[t];
    bool zero[4];
    for (int k = 0; k < 4; ++k) {
      Point q[4] = {x[tet[0]], x[tet[1]], x[tet[2]], x[tet[3]]};
      q[k] = p;  // p in place of vertex k: the side of the face opposite k
      const CGAL::Orientation s = CGAL::orientation(q[0], q[1], q[2], q[3]);
      if (s == -o) return;  // outside this tet
      zero[k] = s == CGAL::COPLANAR;
    }
    Touch& r = touch[i];
    if (!(zero[0] || zero[1] || zero[2] || zero[3])) {
      r.strictly_inside = true;
      return;
    }
    r.touches = true;
    // In the closed tet and on the plane of face k means on the closed face k.
    for (int k = 0; k < 4; ++k)
      if (zero[k] && (masks[t] >> k & 1u)) r.on_boundary_face = true;
  };
  // Closed boxes (the default): a point on a box's side still meets it.
  CGAL::box_intersection_d(point_boxes.begin(), point_boxes.end(), tet_boxes.begin(), tet_boxes.end(), test);
  std::vector<TetSide> sides(points_m.size(), TetSide::Outside);
  for (std::size_t i = 0; i < touch.size(); ++i) {
    if (touch[i].strictly_inside) sides[i] = TetSide::Inside;
    else if (touch[i].touches) sides[i] = touch[i].on_boundary_face ? TetSide::Boundary : TetSide::Inside;
  }
  return sides;
}

}  // namespace

std::vector<TetSide> classify_points_in_tets(const Body& body, const std::vector<Vec3>& points_m) {
  return classify(body, points_m, false);
}

std::vector<TetSide> classify_self_points(const Body& body) { return classify(body, body.x_m, true); }

std::vector<TetSide> classify_self_points_among(const Body& body, const TetFilter& counts) {
  return classify(body, body.x_m, true, counts);
}

}  // namespace tcb
