// Perturbed initial conditions: nothing at 0 whatever the seed; each jitter
// within its bound, rigid where it should be, drawn from the body's own
// stream, the same for the same seed; per-object tables; passive bodies never.
#include "sim/world/perturbation.hpp"

#include <catch2/catch.hpp>

#include "sim/random/counter_random.hpp"
#include "sim/world/world_desc.hpp"

using namespace tcb;

namespace {

World two_boxes_and_a_floor() {
  WorldDesc desc;
  for (const char* name : {"a", "b"}) {
    ObjectDesc o;
    o.name = name;
    o.mesh = "box:size=0.1x0.1x0.1,cells=2x2x2";
    o.position_m = Vec3(name[0] == 'a' ? 0.0 : 0.3, 0.2, 0.0);
    o.velocity_m_per_s = Vec3(0.0, -1.0, 0.0);
    desc.objects.push_back(o);
  }
  ObjectDesc floor;
  floor.name = "floor";
  floor.mesh = "box:size=1x0.1x1,cells=2x1x2";
  floor.passive = true;
  desc.objects.push_back(floor);
  return build_world(desc);
}

Perturbation all(double position_m, double velocity_m_per_s, double rotation_rad, double material_rel) {
  Perturbation p;
  p.global = Jitter{position_m, velocity_m_per_s, rotation_rad, material_rel};
  return p;
}

// Elastic energy of body b displaced by a fixed stretch: it grows with the modulus.
double stretched_energy(World& world, std::size_t b) {
  Body& body = world.bodies[b];
  const std::vector<Vec3> x = body.x_m;
  for (Vec3& p : body.x_m) p.x() *= 1.01;
  const double e = body.model->elastic_energy_j(body.x_m);
  body.x_m = x;
  return e;
}

}  // namespace

TEST_CASE("perturbation 0 changes nothing, whatever the seed", "[perturb]") {
  World a = two_boxes_and_a_floor();
  const World b = two_boxes_and_a_floor();
  for (std::uint64_t seed : {0ull, 1ull, 12345ull, ~0ull}) {
    const auto drawn = perturb_world(a, Perturbation{}, seed);
    for (std::size_t k = 0; k < a.bodies.size(); ++k) {
      CHECK(drawn[k].offset_m == Vec3::Zero());
      CHECK(drawn[k].youngs_modulus_factor == 1.0);
      CHECK(a.bodies[k].x_m == b.bodies[k].x_m);
      CHECK(a.bodies[k].v_m_per_s == b.bodies[k].v_m_per_s);
      CHECK(a.bodies[k].material.youngs_modulus_pa == b.bodies[k].material.youngs_modulus_pa);
    }
  }
}

TEST_CASE("the generator against fixed reference values: the same draws on every build", "[perturb][random]") {
  // Computed by an independent Python transcription of the definitions in
  // counter_random.hpp (the report's statistics use the same generator); a
  // change of generator or distribution changes every perturbed run, so it
  // must change these too, deliberately.
  CHECK(counter_bits(0, 0, 0) == 0x238275bc38fcbe91ull);
  CHECK(counter_bits(1, 2, 3) == 0xd0734750fde362b3ull);
  CHECK(uniform_pm1(0, 0, 0) == -0.7225811797088915);
  CHECK(uniform_pm1(7, 1, 9) == 0.3256278125684342);
}

TEST_CASE("position jitter translates each dynamic body rigidly within the bound, reproducibly", "[perturb]") {
  const double bound = 1e-3;
  World a = two_boxes_and_a_floor(), again = two_boxes_and_a_floor(), other = two_boxes_and_a_floor();
  const World original = two_boxes_and_a_floor();
  const auto drawn = perturb_world(a, all(bound, 0, 0, 0), 1);
  const auto drawn_again = perturb_world(again, all(bound, 0, 0, 0), 1);
  const auto drawn_other = perturb_world(other, all(bound, 0, 0, 0), 2);
  CHECK(drawn_again[0].offset_m == drawn[0].offset_m);
  CHECK(drawn_other[0].offset_m != drawn[0].offset_m);
  CHECK(drawn[0].offset_m != drawn[1].offset_m);  // bodies draw from their own streams
  CHECK(drawn[2].offset_m == Vec3::Zero());       // passive
  for (std::size_t k = 0; k < a.bodies.size(); ++k) {
    CHECK(drawn[k].offset_m.cwiseAbs().maxCoeff() <= bound);
    for (std::size_t v = 0; v < a.bodies[k].x_m.size(); ++v)
      CHECK((a.bodies[k].x_m[v] - (original.bodies[k].x_m[v] + drawn[k].offset_m)).norm() == 0.0);
  }
  // The offset is the documented draw: body index as stream, coordinates 0..2.
  for (int c = 0; c < 3; ++c) CHECK(drawn[1].offset_m[c] == bound * uniform_pm1(1, 1, static_cast<std::uint64_t>(c)));
  CHECK(drawn[0].offset_m.norm() > 0.0);
}

TEST_CASE("velocity jitter adds one draw to every vertex and moves nothing", "[perturb]") {
  World a = two_boxes_and_a_floor();
  const World original = two_boxes_and_a_floor();
  const auto drawn = perturb_world(a, all(0, 0.05, 0, 0), 3);
  for (std::size_t k = 0; k < 2; ++k) {
    CHECK(drawn[k].velocity_m_per_s.cwiseAbs().maxCoeff() <= 0.05);
    CHECK(drawn[k].velocity_m_per_s.norm() > 0.0);
    CHECK(a.bodies[k].x_m == original.bodies[k].x_m);
    for (std::size_t v = 0; v < a.bodies[k].v_m_per_s.size(); ++v)
      CHECK(a.bodies[k].v_m_per_s[v] == original.bodies[k].v_m_per_s[v] + drawn[k].velocity_m_per_s);
  }
  CHECK(a.bodies[2].v_m_per_s == original.bodies[2].v_m_per_s);
}

TEST_CASE("rotation jitter turns a body rigidly about its centre of mass", "[perturb]") {
  const double bound = 0.1;
  World a = two_boxes_and_a_floor();
  const World original = two_boxes_and_a_floor();
  const auto drawn = perturb_world(a, all(0, 0, bound, 0), 4);
  for (std::size_t k = 0; k < 2; ++k) {
    const Body& now = a.bodies[k];
    const Body& before = original.bodies[k];
    CHECK(drawn[k].rotation_rad.cwiseAbs().maxCoeff() <= bound);
    CHECK((centre_of_mass_m(now) - centre_of_mass_m(before)).norm() < 1e-15);
    double moved = 0.0;
    for (std::size_t v = 0; v < now.x_m.size(); ++v) {
      moved = std::max(moved, (now.x_m[v] - before.x_m[v]).norm());
      for (std::size_t w = v + 1; w < now.x_m.size(); w += 7)
        CHECK((now.x_m[v] - now.x_m[w]).norm() == Approx((before.x_m[v] - before.x_m[w]).norm()).epsilon(1e-12));
    }
    // A corner 0.087 m from the centre moves by at most |r| times that.
    CHECK(moved > 0.0);
    CHECK(moved <= drawn[k].rotation_rad.norm() * 0.0867);
    CHECK(now.v_m_per_s == before.v_m_per_s);
  }
}

TEST_CASE("material jitter scales Young's modulus within the bound and rebuilds the model at rest", "[perturb]") {
  World a = two_boxes_and_a_floor(), original = two_boxes_and_a_floor();
  const auto drawn = perturb_world(a, all(0, 0, 0, 0.2), 5);
  for (std::size_t k = 0; k < 2; ++k) {
    const double f = drawn[k].youngs_modulus_factor;
    CHECK(f >= 0.8);
    CHECK(f < 1.2);
    CHECK(f != 1.0);
    CHECK(a.bodies[k].material.youngs_modulus_pa == original.bodies[k].material.youngs_modulus_pa * f);
    CHECK(a.bodies[k].model->elastic_energy_j(a.bodies[k].x_m) == Approx(0.0).margin(1e-12));  // still at rest
    // Linear elasticity: the energy of one stretch scales with the modulus.
    CHECK(stretched_energy(a, k) == Approx(f * stretched_energy(original, k)).epsilon(1e-9));
  }
  CHECK(a.bodies[2].model == nullptr);  // passive: no model, none built
}

TEST_CASE("an object's own jitter replaces the global one for it and its stack copies only", "[perturb]") {
  WorldDesc desc;
  ObjectDesc plate;
  plate.name = "plate";
  plate.mesh = "box:size=0.1x0.02x0.1,cells=1x1x1";
  plate.stack.count = 3;
  desc.objects.push_back(plate);
  ObjectDesc ball = plate;
  ball.name = "ball";
  ball.stack.count = 1;
  ball.position_m = Vec3(1, 0, 0);
  desc.objects.push_back(ball);
  World world = build_world(desc);
  REQUIRE(world.bodies.size() == 4);
  Perturbation p = all(1e-3, 0, 0, 0);
  p.objects["plate"].velocity_m_per_s = 0.1;
  const auto drawn = perturb_world(world, p, 6);
  for (std::size_t k = 0; k < 3; ++k) {
    CHECK(drawn[k].jitter.velocity_m_per_s == 0.1);
    CHECK(drawn[k].jitter.position_m == 1e-3);
    CHECK(drawn[k].velocity_m_per_s.norm() > 0.0);
  }
  CHECK(drawn[0].velocity_m_per_s != drawn[1].velocity_m_per_s);  // copies draw separately
  CHECK(drawn[3].jitter.velocity_m_per_s == 0.0);
  CHECK(drawn[3].velocity_m_per_s == Vec3::Zero());
  CHECK(drawn[3].offset_m.norm() > 0.0);
}
