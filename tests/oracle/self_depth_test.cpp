// The true depth of self-collision points (oracle/self_depth.hpp): against a
// brute force (tests/oracle/brute_self_depth.hpp: exact orient3d per tet, CGAL point-triangle
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
#include "tests/oracle/brute_self_depth.hpp"

using namespace tcb;
namespace fs = std::filesystem;

namespace {

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

}  // namespace

TEST_CASE("self depth: a hairpin fold, by hand and by brute force", "[oracle]") {
  // 0.1 x 1.2 x 0.1 m, 12 cells along y in 6 parts of 0.2 m; 2 cells in z so
  // the faces' middle row (z = 0) is off every edge of the other leg.
  const World world = folded_bar("box:size=0.1x1.2x0.1,cells=1x12x2,parts=1x6x1");
  const Body& bar = world.bodies[0];
  const std::vector<TetSide> sides = classify_self_points(bar);
  const SelfDepths self = self_collision_depths(bar, sides);
  const std::vector<double> expected = test::brute_force_depths(bar, sides);
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
