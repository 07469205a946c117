// Perturbed initial conditions: none at 0, a rigid offset within the bound
// for dynamic bodies only, the same for the same seed.
#include "sim/world/perturbation.hpp"

#include <catch2/catch.hpp>

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
    desc.objects.push_back(o);
  }
  ObjectDesc floor;
  floor.name = "floor";
  floor.mesh = "box:size=1x0.1x1,cells=2x1x2";
  floor.passive = true;
  desc.objects.push_back(floor);
  return build_world(desc);
}

}  // namespace

TEST_CASE("perturbation 0 changes nothing, whatever the seed", "[perturb]") {
  World a = two_boxes_and_a_floor();
  const World b = two_boxes_and_a_floor();
  const auto offsets = perturb_world(a, Perturbation{}, 12345);
  for (std::size_t k = 0; k < a.bodies.size(); ++k) {
    CHECK(offsets[k] == Vec3::Zero());
    CHECK(a.bodies[k].x_m == b.bodies[k].x_m);
  }
}

TEST_CASE("perturbation translates each dynamic body rigidly within the bound, reproducibly", "[perturb]") {
  const double bound = 1e-3;
  World a = two_boxes_and_a_floor(), again = two_boxes_and_a_floor(), other = two_boxes_and_a_floor();
  const World original = two_boxes_and_a_floor();
  const auto offsets = perturb_world(a, Perturbation{bound}, 1);
  CHECK(perturb_world(again, Perturbation{bound}, 1) == offsets);
  CHECK(perturb_world(other, Perturbation{bound}, 2) != offsets);
  CHECK(offsets[0] != offsets[1]);  // bodies draw from their own streams
  CHECK(offsets[2] == Vec3::Zero());  // passive
  for (std::size_t k = 0; k < a.bodies.size(); ++k) {
    CHECK(offsets[k].cwiseAbs().maxCoeff() <= bound);
    for (std::size_t v = 0; v < a.bodies[k].x_m.size(); ++v)
      CHECK((a.bodies[k].x_m[v] - (original.bodies[k].x_m[v] + offsets[k])).norm() == 0.0);
  }
  CHECK(offsets[0].norm() > 0.0);
}
