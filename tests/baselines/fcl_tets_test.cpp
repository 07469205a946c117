// fcl_tets: forces push overlapping bodies apart and conserve momentum, the
// implicit mode hands the same pairs to the solver as links, a spent budget
// stops the pair loop (no force, cycle not done), a body's own adjacent tets
// never collide, and touching without overlap is no contact.
#include "baselines/fcl_tets_handler.hpp"

#include <catch2/catch.hpp>

#include "tests/method/test_worlds.hpp"

using namespace tcb;
using test::Placed;

namespace {

test::TestScene two_boxes() {
  return test::scene_of({{"a", "box:size=0.2x0.2x0.2,cells=3x3x3"},
                         {"b", "box:size=0.2x0.2x0.2,cells=4x2x3", Vec3(0.07, 0.05, 0.03)}});
}

Vec3 total_force(const World& world, std::size_t body) {
  Vec3 f = Vec3::Zero();
  for (const Vec3& v : world.bodies[body].contact_force_n) f += v;
  return f;
}

}  // namespace

TEST_CASE("fcl_tets: overlapping boxes are pushed apart, momentum conserved", "[fcl_tets]") {
  const test::TestScene scene = two_boxes();
  World world = build_world(scene);
  FclTetsHandler handler;
  handler.init(world, test::settings_of(world, scene));
  Budget unlimited = Budget::unlimited();
  const StepReport report = handler.step(world, unlimited);
  CHECK(report.cycle_done);
  CHECK(report.exact_forces > 0);
  CHECK(report.colliding_points >= report.exact_forces);
  const Vec3 fa = total_force(world, 0), fb = total_force(world, 1);
  CHECK((fa + fb).norm() <= 1e-9 * fa.norm());  // every reaction where its action is
  const Vec3 a_to_b = centre_of_mass_m(world.bodies[1]) - centre_of_mass_m(world.bodies[0]);
  CHECK(fa.dot(a_to_b) < 0.0);  // a is pushed away from b
  for (const Contact& c : handler.contacts()) {
    CHECK(c.depth_source == DepthSource::TetPair);
    CHECK(c.depth_m > 0.0);
    CHECK(c.direction.norm() == Approx(1.0));
  }
}

TEST_CASE("fcl_tets: implicit response gives links, not forces", "[fcl_tets]") {
  test::TestScene scene = two_boxes();
  scene.collision.response_mode = ResponseMode::Implicit;
  World world = build_world(scene);
  FclTetsHandler handler;
  handler.init(world, test::settings_of(world, scene));
  Budget unlimited = Budget::unlimited();
  const StepReport report = handler.step(world, unlimited);
  REQUIRE(report.exact_forces > 0);
  CHECK(world.contact_links.size() >= static_cast<std::size_t>(report.exact_forces));
  for (const ContactLink& link : world.contact_links) {
    CHECK(link.depth_m > 0.0);
    CHECK(link.stiffness_n_per_m <= 100.0);  // the pair's stiffness shared by tet a's weights
    CHECK(link.stiffness_n_per_m > 0.0);
  }
}

TEST_CASE("fcl_tets: a spent budget stops the pair loop with no force", "[fcl_tets]") {
  const test::TestScene scene = two_boxes();
  World world = build_world(scene);
  FclTetsHandler handler;
  handler.init(world, test::settings_of(world, scene));
  Budget none = Budget::work_units(0);
  const StepReport report = handler.step(world, none);
  CHECK_FALSE(report.cycle_done);
  CHECK(report.exact_forces == 0);
  CHECK(handler.contacts().empty());
  CHECK(total_force(world, 0) == Vec3::Zero());
  // The refit is one task: its tets were charged, then no pair.
  CHECK(report.work_units == world.bodies[0].mesh->tet_count() + world.bodies[1].mesh->tet_count());
}

TEST_CASE("fcl_tets: a body's own tets sharing a vertex never collide; touching is no contact", "[fcl_tets]") {
  const test::TestScene alone = test::scene_of({{"self", "box:size=0.2x0.2x0.2,cells=3x3x3", Vec3::Zero(), false, true}});
  World world = build_world(alone);
  FclTetsHandler handler;
  handler.init(world, test::settings_of(world, alone));
  Budget unlimited = Budget::unlimited();
  CHECK(handler.step(world, unlimited).exact_forces == 0);
  CHECK(handler.contacts().empty());

  const test::TestScene plates =
      test::scene_of({{"plate", "box:size=0.3x0.02x0.3,cells=4x2x4", Vec3::Zero(), false, false, 1.0, 2}});
  World stacked = build_world(plates);
  FclTetsHandler on_plates;
  on_plates.init(stacked, test::settings_of(stacked, plates));
  CHECK(on_plates.step(stacked, unlimited).exact_forces == 0);
}
