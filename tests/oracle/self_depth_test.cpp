// The true depth of self-collision points (oracle/self_depth.hpp): against a
// brute force written here (exact orient3d per tet, CGAL point-triangle
// distance per triangle, no boxes, no trees), against a hairpin fold whose
// depths are known by hand, and against the oracle's depth for the same
// geometry given as two bodies.
#include "oracle/self_depth.hpp"

#include <catch2/catch.hpp>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <set>

#include "oracle/inside_oracle.hpp"
#include "sim/geometry/orient3d.hpp"
#include "sim/mesh/box_mesh.hpp"
#include "sim/mesh/medit_io.hpp"
#include "tests/method/test_worlds.hpp"

using namespace tcb;
namespace fs = std::filesystem;

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

// A bar along y bent into a hairpin: y <= 0 stays; the next pi*R of it turns
// around a circle of centreline radius R centred at (R, 0); the rest runs back
// down at x' = 2R - x. With R = 0.04 and a 0.1 m thick bar, the returning leg
// overlaps the standing one by 2 cm in x.
Vec3 hairpin(const Vec3& p, double radius_m) {
  const double bend = std::numbers::pi * radius_m;
  if (p.y() <= 0.0) return p;
  if (p.y() >= bend) return {2.0 * radius_m - p.x(), -(p.y() - bend), p.z()};
  const double theta = p.y() / radius_m, r = radius_m - p.x();
  return {radius_m - r * std::cos(theta), r * std::sin(theta), p.z()};
}

World folded_bar(const std::string& mesh) {
  World world = build_world(test::scene_of({{"bar", mesh, Vec3::Zero(), false, true}}).world);
  Body& bar = world.bodies[0];
  for (Vec3& x : bar.x_m) x = hairpin(x, 0.04);
  return world;
}

// The contract of self_depth.hpp, written out directly.
std::vector<double> brute_force_depths(const Body& body, const std::vector<TetSide>& self_sides) {
  const TetMesh& mesh = *body.mesh;
  std::vector<double> depth(body.x_m.size(), std::nan(""));
  for (std::size_t v = 0; v < body.x_m.size(); ++v) {
    if (self_sides[v] != TetSide::Inside) continue;
    std::set<std::int32_t> own, hood;
    for (std::size_t t = 0; t < mesh.tet_count(); ++t)
      if (std::count(mesh.tets[t].begin(), mesh.tets[t].end(), static_cast<std::int32_t>(v))) own.insert(mesh.tet_part[t]);
    for (std::size_t t = 0; t < mesh.tet_count(); ++t)
      for (const std::int32_t u : mesh.tets[t])
        for (std::size_t s = 0; s < mesh.tet_count(); ++s)
          if (own.count(mesh.tet_part[s]) && std::count(mesh.tets[s].begin(), mesh.tets[s].end(), u))
            hood.insert(mesh.tet_part[t]);
    // Strictly inside a far tet, or in a closed far tet and on no boundary
    // triangle of the body (the tet_inside rule over the far tets).
    bool strictly = false, touches = false, on_surface = false;
    for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
      const Tet& tet = mesh.tets[t];
      if (hood.count(mesh.tet_part[t]) || std::count(tet.begin(), tet.end(), static_cast<std::int32_t>(v))) continue;
      const Vec3 q[4] = {body.x_m[tet[0]], body.x_m[tet[1]], body.x_m[tet[2]], body.x_m[tet[3]]};
      const int o = orient3d(q[0], q[1], q[2], q[3]);
      if (o == 0) continue;
      int s[4];
      for (int k = 0; k < 4; ++k) {
        Vec3 r[4] = {q[0], q[1], q[2], q[3]};
        r[k] = body.x_m[v];
        s[k] = orient3d(r[0], r[1], r[2], r[3]) * o;
      }
      if (s[0] < 0 || s[1] < 0 || s[2] < 0 || s[3] < 0) continue;
      if (s[0] > 0 && s[1] > 0 && s[2] > 0 && s[3] > 0) strictly = true;
      else touches = true;
      for (int k = 0; k < 4; ++k) {
        if (s[k] != 0) continue;
        const auto face = tet_faces(tet)[k];  // opposite vertex k, as the tets are stored
        for (const Triangle& f : mesh.surface) {
          Triangle a = f, b = face;
          std::sort(a.begin(), a.end()), std::sort(b.begin(), b.end());
          if (a == b) on_surface = true;
        }
      }
    }
    if (!(strictly || (touches && !on_surface))) continue;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t f = 0; f < mesh.surface.size(); ++f) {
      if (hood.count(mesh.tet_part[mesh.surface_tet[f]])) continue;
      const auto P = [&](std::int32_t i) { return K::Point_3(body.x_m[i].x(), body.x_m[i].y(), body.x_m[i].z()); };
      const Triangle& tri = mesh.surface[f];
      const K::Point_3 p(body.x_m[v].x(), body.x_m[v].y(), body.x_m[v].z());
      best = std::min(best, CGAL::to_double(CGAL::squared_distance(p, K::Triangle_3(P(tri[0]), P(tri[1]), P(tri[2])))));
    }
    depth[v] = std::sqrt(best);
  }
  return depth;
}

}  // namespace

TEST_CASE("self depth: a hairpin fold, by hand and by brute force", "[oracle]") {
  // 0.1 x 1.2 x 0.1 m, 12 cells along y in 6 parts of 0.2 m; 2 cells in z so
  // the faces' middle row (z = 0) is off every edge of the other leg.
  const World world = folded_bar("box:size=0.1x1.2x0.1,cells=1x12x2,parts=1x6x1");
  const Body& bar = world.bodies[0];
  const std::vector<TetSide> sides = classify_self_points(bar);
  const SelfDepths self = self_collision_depths(bar, sides);
  const std::vector<double> expected = brute_force_depths(bar, sides);
  // By hand: the face vertices (x = +0.05 at rest, z = 0) that end up 2 cm
  // inside the other leg are deep where that leg's part there lies outside
  // their neighbourhood: of the standing leg y = -0.4, -0.3, -0.2, -0.1 (at
  // y = 0 the returning leg there is part 3, a neighbour); of the returning
  // leg rest y = 0.3, 0.4, 0.5, 0.6 (at 0.2 the standing leg's part 2 is a
  // neighbour). Each is 2 cm from the other leg's nearest face.
  CHECK(self.deep == 8);
  std::int64_t inside = 0, deep = 0;
  for (std::size_t v = 0; v < sides.size(); ++v) {
    if (sides[v] != TetSide::Inside) {
      CHECK(std::isnan(self.depth_m[v]));
      continue;
    }
    ++inside;
    INFO("vertex " << v << " at rest " << bar.mesh->positions_m[v].transpose());
    REQUIRE(std::isnan(self.depth_m[v]) == std::isnan(expected[v]));
    if (std::isnan(expected[v])) continue;
    ++deep;
    CHECK(self.depth_m[v] == Approx(expected[v]).margin(1e-14));
    const Vec3& rest = bar.mesh->positions_m[v];
    CHECK(rest.x() == 0.05);
    CHECK(rest.z() == 0.0);
    CHECK(self.depth_m[v] == Approx(0.02).margin(1e-12));
  }
  CHECK(self.deep == deep);
  CHECK(self.shallow == inside - deep);
  // The oracle reports these depths.
  const OracleFrame frame = compute_inside_oracle(world);
  std::int64_t with_depth = 0;
  for (const OraclePoint& p : frame.inside) {
    CHECK(p.object == 0);
    CHECK(p.other == 0);
    if (std::isnan(p.depth_m)) continue;
    ++with_depth;
    CHECK(p.depth_m == self.depth_m[p.vertex]);
  }
  CHECK(with_depth == self.deep);
  CHECK(frame.max_depth_m == Approx(0.02).margin(1e-12));
}

TEST_CASE("self depth: without parts there is none, and the oracle says so", "[oracle]") {
  const World world = folded_bar("box:size=0.1x1.2x0.1,cells=1x12x2");
  const std::vector<TetSide> sides = classify_self_points(world.bodies[0]);
  const SelfDepths self = self_collision_depths(world.bodies[0], sides);
  CHECK(self.deep == 0);
  CHECK(self.shallow == std::count(sides.begin(), sides.end(), TetSide::Inside));
  CHECK(self.shallow > 10);
  const OracleFrame frame = compute_inside_oracle(world);
  REQUIRE(frame.unmeasured.size() == 1);
  CHECK_THAT(frame.unmeasured[0], Catch::Matchers::Contains("has no parts"));
}

TEST_CASE("self depth: two components as parts of one body equal two bodies", "[oracle]") {
  // Box b overlaps box a; once as two bodies, once as one self-colliding body
  // read from a MEDIT file whose element references are the components.
  const TetMesh a = make_box_mesh(Vec3(0.2, 0.2, 0.2), 3, 3, 3);
  const TetMesh b = make_box_mesh(Vec3(0.2, 0.2, 0.2), 4, 2, 3);
  const Vec3 offset(0.07, 0.05, 0.03);
  std::vector<Vec3> x = a.positions_m;
  std::vector<Tet> tets = a.tets;
  for (const Vec3& p : b.positions_m) x.push_back(p + offset);
  const auto shift = static_cast<std::int32_t>(a.vertex_count());
  for (Tet t : b.tets) {
    for (std::int32_t& i : t) i += shift;
    tets.push_back(t);
  }
  TetMesh both = build_tet_mesh(x, tets);
  both.tet_part.assign(a.tet_count(), 1);
  both.tet_part.resize(both.tet_count(), 2);
  const fs::path dir = fs::temp_directory_path() / ("tcbench_self_depth_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  write_medit(dir / "both.mesh", both);
  const World one = build_world(test::scene_of({{"both", (dir / "both.mesh").string(), Vec3::Zero(), false, true}}).world);
  fs::remove_all(dir);
  const World two = build_world(test::scene_of({{"a", "box:size=0.2x0.2x0.2,cells=3x3x3"},
                                                 {"b", "box:size=0.2x0.2x0.2,cells=4x2x3", offset}}).world);
  const OracleFrame self = compute_inside_oracle(one), pair = compute_inside_oracle(two);
  REQUIRE(pair.inside.size() > 10);
  REQUIRE(self.inside.size() == pair.inside.size());
  for (std::size_t i = 0; i < pair.inside.size(); ++i) {
    const OraclePoint &p = pair.inside[i], &s = self.inside[i];
    const std::int32_t vertex = p.object == 0 ? p.vertex : p.vertex + shift;
    REQUIRE(s.vertex == vertex);
    CHECK(s.depth_m == Approx(p.depth_m).margin(1e-15));
  }
  CHECK(self.boundary.size() == pair.boundary.size());
  CHECK(self.unmeasured.empty());
}
