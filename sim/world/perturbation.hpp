#pragma once
/// Perturbed initial conditions, so that seeds mean something and a chaotic
/// scene's own sensitivity can be measured (the divergence noise floor).
/// Today: a rigid translation of every dynamic body, each coordinate drawn
/// uniformly from [-position_m, position_m] with the project's counter-based
/// generator (sim/random/counter_random.hpp), stream = the body's index,
/// index = the coordinate (0, 1, 2). Passive bodies (fixed or driven) stay
/// where the scene puts them. position_m = 0 changes nothing, bit for bit,
/// whatever the seed. Units: m.

#include <cstdint>
#include <vector>

#include "sim/world/world.hpp"

namespace tcb {

struct Perturbation {
  double position_m = 0.0;  ///< >= 0: the largest offset per coordinate
};

/// The offsets applied, per body (zero for passive bodies), for run.json.
std::vector<Vec3> perturb_world(World& world, const Perturbation& perturbation, std::uint64_t seed);

}  // namespace tcb
