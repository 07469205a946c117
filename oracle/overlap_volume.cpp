#include "oracle/overlap_volume.hpp"
#include "oracle/surface_mesh.hpp"

// The one translation unit with the exact-constructions kernel: corefinement
// is slow to compile and to run, so nothing else pays for it.
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <cmath>
#include <limits>
#include <map>
#include <optional>

namespace tcb {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;

using oracle_detail::surface_mesh_of;

// Why a body's surface cannot bound an exact volume, or nullopt when it can.
std::optional<std::string> guard_failure(const Body& body) {
  bool ok = false;
  const auto mesh = surface_mesh_of<Epick>(body, ok);
  if (!ok) return "surface is not a manifold";
  if (!CGAL::is_closed(mesh)) return "surface is not closed";
  if (PMP::does_self_intersect(mesh)) return "surface intersects itself";
  if (!PMP::does_bound_a_volume(mesh)) return "surface does not bound a volume";
  return std::nullopt;
}

struct Box {
  Vec3 lo, hi;
};

Box box_of(const Body& body) {
  Box box{Vec3::Constant(std::numeric_limits<double>::infinity()),
          Vec3::Constant(-std::numeric_limits<double>::infinity())};
  for (const std::int32_t v : body.mesh->surface_vertices) {
    box.lo = box.lo.cwiseMin(body.x_m[v]);
    box.hi = box.hi.cwiseMax(body.x_m[v]);
  }
  return box;
}

bool overlap_with_volume(const Box& p, const Box& q) {
  for (int i = 0; i < 3; ++i)
    if (!(std::min(p.hi[i], q.hi[i]) > std::max(p.lo[i], q.lo[i]))) return false;
  return true;
}

}  // namespace

OverlapFrame compute_overlap_volumes(const World& world) {
  OverlapFrame frame;
  const std::size_t n = world.bodies.size();
  std::vector<Box> boxes;
  for (const Body& b : world.bodies) boxes.push_back(box_of(b));
  std::map<std::size_t, std::optional<std::string>> guard;  // computed once per involved body
  const auto failure = [&](std::size_t i) -> const std::optional<std::string>& {
    auto it = guard.find(i);
    if (it == guard.end()) it = guard.emplace(i, guard_failure(world.bodies[i])).first;
    return it->second;
  };
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b) {
      const Body& A = world.bodies[a];
      const Body& B = world.bodies[b];
      if (A.passive && B.passive) continue;
      if (!overlap_with_volume(boxes[a], boxes[b])) continue;
      const std::string pair = "overlap of '" + A.name + "' and '" + B.name + "': ";
      if (const auto& why = failure(a)) {
        frame.invalid.push_back(pair + "'" + A.name + "' " + *why);
        continue;
      }
      if (const auto& why = failure(b)) {
        frame.invalid.push_back(pair + "'" + B.name + "' " + *why);
        continue;
      }
      bool ok_a = false, ok_b = false;
      auto mesh_a = surface_mesh_of<Epeck>(A, ok_a);
      auto mesh_b = surface_mesh_of<Epeck>(B, ok_b);
      CGAL::Surface_mesh<Epeck::Point_3> out;
      bool done = false;
      try {
        done = PMP::corefine_and_compute_intersection(mesh_a, mesh_b, out);
      } catch (const std::exception& e) {
        frame.invalid.push_back(pair + "corefinement failed (" + e.what() + ")");
        continue;
      }
      if (!done) {
        frame.invalid.push_back(pair + "corefinement could not build the intersection");
        continue;
      }
      const double v = out.number_of_faces() == 0 ? 0.0 : CGAL::to_double(PMP::volume(out));
      frame.pairs.push_back({static_cast<std::int32_t>(a), static_cast<std::int32_t>(b), v});
      frame.total_m3 += v;
    }
  return frame;
}

double enclosed_volume_m3(const Body& body) {
  if (guard_failure(body)) return std::numeric_limits<double>::quiet_NaN();
  bool ok = false;
  const auto mesh = surface_mesh_of<Epeck>(body, ok);
  return CGAL::to_double(PMP::volume(mesh));
}

}  // namespace tcb
