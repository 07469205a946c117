// Penalty response: momentum is conserved, damping and friction never exceed
// what stops the relative motion in one step, degenerate tets never produce
// NaN or infinite forces.
#include "method/response/penalty_response.hpp"

#include <catch2/catch.hpp>

#include "baselines/registry.hpp"
#include "tests/method/test_worlds.hpp"

using namespace tcb;

namespace {

Vec3 total_force(const World& world) {
  Vec3 sum = Vec3::Zero();
  for (const Body& b : world.bodies)
    for (const Vec3& f : b.contact_force_n) sum += f;
  return sum;
}

}  // namespace

TEST_CASE("penalty response conserves momentum", "[response]") {
  test::TestScene scene = test::scene_of({{"a", "box:size=0.2x0.2x0.2,cells=3x3x3"},
                                    {"b", "box:size=0.2x0.2x0.2,cells=4x2x3", Vec3(0.07, 0.05, 0.03)}});
  scene.collision.damping_n_s_per_m = 5.0;
  scene.collision.friction = 0.5;
  World world = build_world(scene.world);
  for (Vec3& v : world.bodies[0].v_m_per_s) v = Vec3(0.3, -0.2, 0.1);  // sliding and approaching
  auto handler = make_handler("full");
  handler->init(world, test::settings_of(world, scene));
  Budget unlimited = Budget::unlimited();
  const StepReport report = handler->step(world, unlimited);
  REQUIRE(report.exact_forces > 0);
  double largest = 0.0;
  for (const Contact& c : handler->contacts()) largest = std::max(largest, c.force_n.norm());
  REQUIRE(largest > 0.0);
  CHECK(total_force(world).norm() < 1e-12 * largest * static_cast<double>(report.exact_forces));
}

TEST_CASE("explicit damping and friction are clamped to one step's worth", "[response]") {
  test::TestScene scene = test::scene_of(
      {{"floor", "box:size=1x0.1x1,cells=2x1x2", Vec3::Zero(), true}, {"cube", "box:size=0.1x0.1x0.1,cells=1x1x1"}});
  World world = build_world(scene.world);
  const double dt = scene.world.dt_s;
  Contact c;  // the cube's vertex 0, 1 mm into the floor, moving fast sideways and down
  c.object = 1;
  c.vertex = 0;
  c.other = 0;
  c.tet = 0;
  c.barycentric = {0.25, 0.25, 0.25, 0.25};
  c.depth_source = DepthSource::Border;
  c.depth_m = 1e-3;
  c.direction = Vec3(0, 1, 0);
  world.bodies[1].v_m_per_s[0] = Vec3(2.0, -0.5, 0.0);
  const double m = contact_reduced_mass(world, c);
  CHECK(m == world.bodies[1].mass_kg[0]);  // the floor is passive
  const ResponseParams wild{1e3, 1e6, 10.0};  // huge damping and friction coefficients
  const Vec3 f = penalty_force(world, c, wild, dt);
  // Normal: stiffness plus damping clamped at m/dt, i.e. at most stopping the approach in one step.
  CHECK(f.y() == Approx(1e3 * 1e-3 + m / dt * 0.5));
  // Friction: at most what stops the sliding in one step.
  CHECK(-f.x() == Approx(m / dt * 2.0));
  CHECK(f.x() < 0.0);
  const ResponseParams gentle{1e3, 0.0, 0.1};
  const Vec3 g = penalty_force(world, c, gentle, dt);
  CHECK(-g.x() == Approx(0.1 * 1.0));  // Coulomb: mu |f_n|, f_n = 1 N
  c.depth_source = DepthSource::None;
  CHECK(penalty_force(world, c, wild, dt) == Vec3::Zero());
}

TEST_CASE("flat and sliver tets produce no NaN and are never claimed", "[response]") {
  // A mesh with an exactly flat tet and a near-flat sliver among good ones.
  std::vector<Vec3> x = {{0, 0, 0},   {0.1, 0, 0},   {0, 0.1, 0},        {0, 0, 0.1},
                         {0.1, 0.1, 0}, {0.1, 0, 0.1}, {0.05, 1e-9, 0.05}};
  // Two good tets, a flat one between them (all in z = 0), a sliver 1e-9 thick.
  const TetMesh odd = build_tet_mesh(x, {{0, 1, 2, 3}, {1, 4, 2, 3}, {0, 1, 4, 2}, {1, 3, 5, 6}});
  REQUIRE(odd.degenerate_tets == 1);
  test::TestScene scene = test::scene_of({{"probe", "box:size=0.08x0.08x0.08,cells=3x3x3", Vec3(0.04, 0.03, 0.03)}});
  World world = build_world(scene.world);
  Body body;
  body.name = "odd";
  body.group = "odd";
  body.mesh = std::make_shared<const TetMesh>(odd);
  body.x_m = odd.positions_m;
  body.v_m_per_s.assign(x.size(), Vec3::Zero());
  body.contact_force_n.assign(x.size(), Vec3::Zero());
  body.mass_kg = lumped_masses_kg(odd, odd.positions_m, 1000.0);
  body.model = make_elastic_model(odd, odd.positions_m, body.material);
  world.bodies.push_back(std::move(body));
  scene.world.objects.push_back(scene.world.objects[0]);
  scene.world.objects.back().name = "odd";
  auto handler = make_handler("full");
  handler->init(world, test::settings_of(world, scene));
  Budget unlimited = Budget::unlimited();
  const StepReport report = handler->step(world, unlimited);
  CHECK(report.colliding_points > 0);
  for (const Contact& c : handler->contacts()) {
    CHECK(c.force_n.allFinite());
    if (c.other == 1) CHECK(c.tet != odd.degenerate_tet_ids[0]);
  }
  for (const Body& b : world.bodies)
    for (const Vec3& f : b.contact_force_n) REQUIRE(f.allFinite());
  world.step(scene.world.dt_s);
  CHECK(std::isfinite(world.max_speed_m_per_s()));
}

TEST_CASE("a contact of a passive body with itself acts on nothing", "[response]") {
  // A latent-driven body's self-collision: neither side is integrated, so no
  // force, no link (and no work booked for the driven body).
  test::TestScene scene = test::scene_of({{"a", "box:size=0.2x0.2x0.2,cells=2x2x2", Vec3::Zero(), true, true}});
  World world = build_world(scene.world);
  Contact c;
  c.object = c.other = 0;
  c.vertex = 0;
  c.tet = 5;
  c.barycentric = {0.25, 0.25, 0.25, 0.25};
  c.depth_source = DepthSource::Border;
  c.depth_m = 0.01;
  c.direction = Vec3(0, 1, 0);
  apply_contact_force(world, c, Vec3(1, 2, 3));
  add_force_link(world, c, Vec3(0, 5, 0), ResponseParams{.stiffness_n_per_m = 100.0});
  add_contact_link(world, c, ResponseParams{.stiffness_n_per_m = 100.0}, 1e-3);
  CHECK(total_force(world) == Vec3::Zero());
  for (const Vec3& f : world.bodies[0].contact_force_n) CHECK(f == Vec3::Zero());
  CHECK(world.contact_links.empty());
  // The same contact on a dynamic body does act.
  world.bodies[0].passive = false;
  apply_contact_force(world, c, Vec3(1, 2, 3));
  double moved = 0.0;  // the point's force and the tet's reaction (vertex 0 may be both)
  for (const Vec3& f : world.bodies[0].contact_force_n) moved += f.norm();
  CHECK(moved > 1.0);
}
