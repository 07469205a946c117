#include "method/handler/contact.hpp"

#include "sim/world/world.hpp"

namespace tcb {

Vec3 contact_offset_m(const World& world, const Contact& c) {
  const Body& B = world.bodies[c.other];
  const Tet& t = B.mesh->tets[c.tet];
  Vec3 x = Vec3::Zero();
  for (int k = 0; k < 4; ++k) x += c.barycentric[k] * B.x_m[t[k]];
  return world.bodies[c.object].x_m[c.vertex] - x;
}

double tracked_depth_m(const World& world, const Contact& c) {
  return c.depth_m - (contact_offset_m(world, c) - c.depth_offset_m).dot(c.direction);
}

}  // namespace tcb
