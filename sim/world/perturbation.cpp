#include "sim/world/perturbation.hpp"

#include "sim/random/counter_random.hpp"

namespace tcb {

std::vector<Vec3> perturb_world(World& world, const Perturbation& perturbation, std::uint64_t seed) {
  std::vector<Vec3> offsets(world.bodies.size(), Vec3::Zero());
  if (!(perturbation.position_m > 0.0)) return offsets;
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    Body& body = world.bodies[b];
    if (body.passive) continue;
    for (int k = 0; k < 3; ++k)
      offsets[b][k] = perturbation.position_m * uniform_pm1(seed, b, static_cast<std::uint64_t>(k));
    for (Vec3& x : body.x_m) x += offsets[b];
  }
  return offsets;
}

}  // namespace tcb
