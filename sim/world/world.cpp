#include "sim/world/world.hpp"

#include <cmath>
#include <limits>

namespace tcb {

World clone_world(const World& world) {
  World copy;
  copy.gravity_m_per_s2 = world.gravity_m_per_s2;
  copy.ground = world.ground;
  copy.time_s = world.time_s;
  copy.step_index = world.step_index;
  copy.contact_links = world.contact_links;
  copy.last_contact_solve = world.last_contact_solve;
  copy.driven_work_j = world.driven_work_j;
  copy.bodies.reserve(world.bodies.size());
  for (const Body& b : world.bodies) {
    Body c;
    c.name = b.name;
    c.group = b.group;
    c.mesh = b.mesh;
    c.x_m = b.x_m;
    c.v_m_per_s = b.v_m_per_s;
    c.contact_force_n = b.contact_force_n;
    c.applied_contact_force_n = b.applied_contact_force_n;
    c.mass_kg = b.mass_kg;
    c.material = b.material;
    c.passive = b.passive;
    c.self_collision = b.self_collision;
    c.model = b.model ? b.model->clone() : nullptr;
    c.trajectory = b.trajectory;
    c.shape_m = b.shape_m;
    c.latent = b.latent;
    c.latent_code = b.latent_code;
    c.external_force_n = b.external_force_n;
    copy.bodies.push_back(std::move(c));
  }
  return copy;
}

Vec3 centre_of_mass_m(const Body& b) {
  Vec3 c = Vec3::Zero(), plain = Vec3::Zero();
  double m = 0.0;
  for (std::size_t i = 0; i < b.x_m.size(); ++i) {
    c += b.mass_kg[i] * b.x_m[i];
    plain += b.x_m[i];
    m += b.mass_kg[i];
  }
  if (m > 0.0) return c / m;
  return b.x_m.empty() ? plain : Vec3(plain / static_cast<double>(b.x_m.size()));
}

void World::step(double dt_s) {
  for (Body& body : bodies) {
    body.applied_contact_force_n = body.contact_force_n;
    if (body.passive || !body.model) continue;
    body.external_force_n.resize(body.x_m.size());
    for (std::size_t i = 0; i < body.x_m.size(); ++i)
      body.external_force_n[i] = body.mass_kg[i] * gravity_m_per_s2 + body.contact_force_n[i];
  }
  std::vector<char> integrated(bodies.size(), 0);
  last_contact_solve = contact_links.empty() ? ContactSolveStats{}
                                             : step_linked_bodies(*this, contact_links, dt_s, integrated);
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    Body& body = bodies[b];
    if (body.passive || !body.model) continue;
    if (!integrated[b]) body.model->step(body.x_m, body.v_m_per_s, body.external_force_n, dt_s);
    if (ground) apply_ground(*ground, body.x_m, body.v_m_per_s);
  }
  contact_links.clear();
  for (Body& body : bodies) std::fill(body.contact_force_n.begin(), body.contact_force_n.end(), Vec3::Zero());
  for (Body& body : bodies) {
    if (!body.trajectory && !body.latent) continue;
    const auto move_to = [&](std::size_t i, const Vec3& next) {
      driven_work_j -= body.applied_contact_force_n[i].dot(next - body.x_m[i]);
      body.v_m_per_s[i] = (next - body.x_m[i]) / dt_s;
      body.x_m[i] = next;
    };
    if (body.latent) {
      body.latent_code = body.latent->path.at(time_s + dt_s);
      const std::vector<Vec3> next = body.latent->positions_m(body.latent_code);
      for (std::size_t i = 0; i < body.x_m.size(); ++i) move_to(i, next[i]);
    } else {
      const Vec3 at = body.trajectory->at(time_s + dt_s);  // no copy of the shape per step
      for (std::size_t i = 0; i < body.x_m.size(); ++i) move_to(i, body.shape_m[i] + at);
    }
  }
  time_s += dt_s;
  ++step_index;
}

std::optional<Vec3> World::driven_contact_force_n() const {
  std::optional<Vec3> sum;
  for (const Body& b : bodies) {
    if (!b.trajectory) continue;
    if (!sum) sum = Vec3::Zero();
    for (const Vec3& f : b.applied_contact_force_n) *sum += f;
  }
  return sum;
}

double World::kinetic_energy_j() const {
  double e = 0.0;
  for (const Body& b : bodies)
    if (!b.passive)
      for (std::size_t i = 0; i < b.x_m.size(); ++i) e += 0.5 * b.mass_kg[i] * b.v_m_per_s[i].squaredNorm();
  return e;
}

double World::elastic_energy_j() const {
  double e = 0.0;
  for (const Body& b : bodies)
    if (!b.passive && b.model) e += b.model->elastic_energy_j(b.x_m);
  return e;
}

double World::gravity_potential_j() const {
  double e = 0.0;
  for (const Body& b : bodies)
    if (!b.passive)
      for (std::size_t i = 0; i < b.x_m.size(); ++i) e -= b.mass_kg[i] * gravity_m_per_s2.dot(b.x_m[i]);
  return e;
}

double World::max_speed_m_per_s() const {
  double max_speed = 0.0;
  for (const Body& b : bodies) {
    if (b.passive) continue;
    for (std::size_t i = 0; i < b.x_m.size(); ++i) {
      if (!b.x_m[i].allFinite() || !b.v_m_per_s[i].allFinite()) return std::numeric_limits<double>::quiet_NaN();
      max_speed = std::max(max_speed, b.v_m_per_s[i].norm());
    }
  }
  return max_speed;
}

std::size_t World::vertex_count() const {
  std::size_t n = 0;
  for (const Body& b : bodies) n += b.x_m.size();
  return n;
}

}  // namespace tcb
