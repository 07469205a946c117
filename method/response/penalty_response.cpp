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

namespace {

// The relative velocity of the point against the tet at its barycentric position.
Vec3 relative_velocity(const World& world, const Contact& c) {
  const Body& A = world.bodies[c.object];
  const Body& B = world.bodies[c.other];
  const Tet& t = B.mesh->tets[c.tet];
  Vec3 v_tet = Vec3::Zero();
  for (int k = 0; k < 4; ++k) v_tet += c.barycentric[k] * B.v_m_per_s[t[k]];
  return A.v_m_per_s[c.vertex] - v_tet;
}

// The normal magnitude (clamped damping) and what friction needs.
struct ExplicitParts {
  double magnitude;
  Vec3 v_t;               // tangential relative velocity
  double speed_t;
  double stop_per_speed;  // N per (m/s): stops the relative motion in one step
  bool has_friction(const ResponseParams& p) const { return p.friction > 0.0 && magnitude > 0.0 && speed_t > 0.0; }
  double friction_scale(const ResponseParams& p) const {
    return std::min(p.friction * magnitude, stop_per_speed * speed_t) / speed_t;
  }
};

ExplicitParts explicit_parts(const World& world, const Contact& c, const ResponseParams& params, double dt_s) {
  const Vec3 v_rel = relative_velocity(world, c);
  const double v_n = v_rel.dot(c.direction);
  const double stop_per_speed = contact_reduced_mass(world, c) / dt_s;
  const double damping = std::min(params.damping_n_s_per_m, stop_per_speed);
  const double magnitude = std::max(0.0, params.stiffness_n_per_m * c.depth_m - damping * v_n);
  const Vec3 v_t = v_rel - v_n * c.direction;
  return {magnitude, v_t, v_t.norm(), stop_per_speed};
}

}  // namespace

Vec3 penalty_force(const World& world, const Contact& c, const ResponseParams& params, double dt_s) {
  if (c.depth_source == DepthSource::None) return Vec3::Zero();
  const ExplicitParts p = explicit_parts(world, c, params, dt_s);
  Vec3 force = p.magnitude * c.direction;
  if (p.has_friction(params)) force -= p.friction_scale(params) * p.v_t;
  return force;
}

namespace {

ContactLink link_of(const World& world, const Contact& c, double depth_m, const ResponseParams& params) {
  ContactLink link;
  link.point_body = c.object;
  link.vertex = c.vertex;
  link.tet_body = c.other;
  link.tet_vertices = world.bodies[c.other].mesh->tets[c.tet];
  link.weights = c.barycentric;
  link.normal = c.direction;
  link.depth_m = depth_m;
  link.stiffness_n_per_m = params.stiffness_n_per_m;
  link.damping_n_s_per_m = params.damping_n_s_per_m;
  return link;
}

// A contact of a passive body with itself (a latent-driven body's
// self-collision) acts on nothing: neither side is integrated. Applying it
// would only book work the driven body never did on anything.
bool acts_on_nothing(const World& world, const Contact& c) {
  return c.object == c.other && world.bodies[static_cast<std::size_t>(c.object)].passive;
}

}  // namespace

void add_force_link(World& world, const Contact& where, const Vec3& force_n, const ResponseParams& params) {
  if (acts_on_nothing(world, where)) return;
  const double normal = force_n.dot(where.direction);
  if (!(normal > 0.0) || !(params.stiffness_n_per_m > 0.0)) {
    apply_contact_force(world, where, force_n);
    return;
  }
  world.contact_links.push_back(link_of(world, where, normal / params.stiffness_n_per_m, params));
  const Vec3 rest = force_n - normal * where.direction;
  if (rest != Vec3::Zero()) apply_contact_force(world, where, rest);
}

void add_contact_link(World& world, const Contact& c, const ResponseParams& params, double dt_s) {
  if (acts_on_nothing(world, c)) return;
  if (c.depth_source == DepthSource::None || !(c.depth_m > 0.0)) return;
  // A link with neither spring nor damper does nothing but couple the bodies' solves.
  if (!(params.stiffness_n_per_m > 0.0) && !(params.damping_n_s_per_m > 0.0)) return;
  world.contact_links.push_back(link_of(world, c, c.depth_m, params));
  const ExplicitParts p = explicit_parts(world, c, params, dt_s);
  if (p.has_friction(params)) apply_contact_force(world, c, -p.friction_scale(params) * p.v_t);
}

void apply_contact_force(World& world, const Contact& c, const Vec3& force_n) {
  if (acts_on_nothing(world, c)) return;
  world.bodies[c.object].contact_force_n[c.vertex] += force_n;
  Body& B = world.bodies[c.other];
  const Tet& t = B.mesh->tets[c.tet];
  for (int k = 0; k < 4; ++k) B.contact_force_n[t[k]] -= c.barycentric[k] * force_n;
}

}  // namespace tcb
