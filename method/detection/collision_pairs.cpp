#include "method/detection/collision_pairs.hpp"

#include <algorithm>

namespace tcb {

CollisionPairs::CollisionPairs(const World& world)
    : m_count(world.bodies.size()), m_enabled(m_count * m_count, 0), m_has_partner(m_count, 0) {
  for (std::size_t a = 0; a < m_count; ++a)
    for (std::size_t b = 0; b < m_count; ++b) {
      const Body &A = world.bodies[a], &B = world.bodies[b];
      const bool on = a == b ? self_collision_active(A) : !(A.passive && B.passive);
      m_enabled[a * m_count + b] = on;
      if (on) m_has_partner[b] = 1;
    }
}

std::array<double, 4> barycentric_weights(const Vec3& p, const Vec3& v0, const Vec3& v1, const Vec3& v2,
                                          const Vec3& v3) {
  std::array<double, 4> w = {signed_volume(p, v1, v2, v3), signed_volume(v0, p, v2, v3), signed_volume(v0, v1, p, v3),
                             signed_volume(v0, v1, v2, p)};
  double total = 0.0;
  for (double& x : w) {
    x = std::max(x, 0.0);
    total += x;
  }
  if (!(total > 0.0)) return {0.25, 0.25, 0.25, 0.25};
  for (double& x : w) x /= total;
  return w;
}

}  // namespace tcb
