#include "method/response/penalty_response.hpp"

#include <algorithm>

namespace tcb {

double contact_reduced_mass(const World& world, const Contact& c) {
  const double m_point = world.bodies[c.object].mass_kg[c.vertex];
  const Body& B = world.bodies[c.other];
  if (B.passive) return m_point;  // the passive side does not move: all of the motion is the point's
  const Tet& t = B.mesh->tets[c.tet];
  double m_tet = 0.0;
  for (int k = 0; k < 4; ++k) m_tet += c.barycentric[k] * B.mass_kg[t[k]];
  if (world.bodies[c.object].passive) return m_tet;  // a passive (or driven) point: all of it is the tet's
  return m_point + m_tet > 0.0 ? m_point * m_tet / (m_point + m_tet) : 0.0;
}

Vec3 penalty_force(const World& world, const Contact& c, const ResponseParams& params, double dt_s) {
  if (c.depth_source == DepthSource::None) return Vec3::Zero();
  const Body& A = world.bodies[c.object];
  const Body& B = world.bodies[c.other];
  const Tet& t = B.mesh->tets[c.tet];
  Vec3 v_tet = Vec3::Zero();
  for (int k = 0; k < 4; ++k) v_tet += c.barycentric[k] * B.v_m_per_s[t[k]];
  const Vec3 v_rel = A.v_m_per_s[c.vertex] - v_tet;
  const double v_n = v_rel.dot(c.direction);
  const double stop_per_speed = contact_reduced_mass(world, c) / dt_s;  // N per (m/s): stops the motion in one step
  const double damping = std::min(params.damping_n_s_per_m, stop_per_speed);
  const double magnitude = std::max(0.0, params.stiffness_n_per_m * c.depth_m - damping * v_n);
  Vec3 force = magnitude * c.direction;
  const Vec3 v_t = v_rel - v_n * c.direction;
  const double speed_t = v_t.norm();
  if (params.friction > 0.0 && magnitude > 0.0 && speed_t > 0.0)
    force -= std::min(params.friction * magnitude, stop_per_speed * speed_t) / speed_t * v_t;
  return force;
}

void apply_contact_force(World& world, const Contact& c, const Vec3& force_n) {
  world.bodies[c.object].contact_force_n[c.vertex] += force_n;
  Body& B = world.bodies[c.other];
  const Tet& t = B.mesh->tets[c.tet];
  for (int k = 0; k < 4; ++k) B.contact_force_n[t[k]] -= c.barycentric[k] * force_n;
}

}  // namespace tcb
