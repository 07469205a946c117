#pragma once
/// Tunnelling: pairs of objects that ended up passing through each other.
/// A pair counts when the centre of mass of one lies strictly inside the other
/// (exact Side_of_triangle_mesh on the other's closed surface). Pairs whose
/// centres were already inside each other at the start do not count (the
/// caller records them with interlocked_pairs() before the run). Bodies with open surfaces cannot be
/// judged and are listed in `unmeasured`. Part of the oracle: independent of
/// method/.

#include <string>
#include <vector>

#include "sim/world/world.hpp"

namespace tcb {

struct TunnelingResult {
  std::int64_t pairs = 0;
  std::vector<std::string> unmeasured;
};

using BodyPairs = std::vector<std::pair<std::size_t, std::size_t>>;

/// Sorted (a, b), a < b, where one centre lies strictly inside the other.
BodyPairs interlocked_pairs(const World& world);

TunnelingResult count_tunneling(const BodyPairs& initially_interlocked, const World& final_world);

}  // namespace tcb
