#include "method/handler/collision_handler.hpp"

namespace tcb {

std::vector<char> CollisionHandler::self_collision_verdicts(const World& world) const {
  std::vector<char> verdict(world.bodies.size(), 0);
  for (const Contact& c : contacts())
    if (c.object == c.other && c.object >= 0 && static_cast<std::size_t>(c.object) < verdict.size() && !c.separated)
      verdict[static_cast<std::size_t>(c.object)] = 1;
  return verdict;
}

}  // namespace tcb
