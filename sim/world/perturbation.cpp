#include "sim/world/perturbation.hpp"

#include <Eigen/Geometry>

#include "sim/dynamics/elastic_model.hpp"
#include "sim/random/counter_random.hpp"

namespace tcb {
namespace {

// Draw numbers within a body's stream; position keeps 0-2 so the noise-floor
// runs made before the other jitters existed are drawn the same.
constexpr std::uint64_t kPosition = 0, kVelocity = 3, kRotation = 6, kMaterial = 9;

Vec3 draw_vec3(std::uint64_t seed, std::uint64_t stream, std::uint64_t first, double bound) {
  Vec3 v;
  for (int k = 0; k < 3; ++k) v[k] = bound * uniform_pm1(seed, stream, first + static_cast<std::uint64_t>(k));
  return v;
}

}  // namespace

Jitter JitterOverride::over(const Jitter& base) const {
  Jitter j = base;
  if (position_m) j.position_m = *position_m;
  if (velocity_m_per_s) j.velocity_m_per_s = *velocity_m_per_s;
  if (rotation_rad) j.rotation_rad = *rotation_rad;
  if (material_rel) j.material_rel = *material_rel;
  return j;
}

Jitter Perturbation::for_body(const Body& body) const {
  if (body.passive) return Jitter{};
  const auto own = objects.find(body.group.empty() ? body.name : body.group);
  return own == objects.end() ? global : own->second.over(global);
}

std::vector<BodyPerturbation> perturb_world(World& world, const Perturbation& perturbation, std::uint64_t seed) {
  std::vector<BodyPerturbation> drawn(world.bodies.size());
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    Body& body = world.bodies[b];
    BodyPerturbation& d = drawn[b];
    d.jitter = perturbation.for_body(body);
    if (!d.jitter.any()) continue;
    const std::uint64_t stream = b;
    if (d.jitter.material_rel > 0.0) {
      d.youngs_modulus_factor = 1.0 + d.jitter.material_rel * uniform_pm1(seed, stream, kMaterial);
      body.material.youngs_modulus_pa *= d.youngs_modulus_factor;
      body.model = make_elastic_model(*body.mesh, body.x_m, body.material);  // rest shape: as built
    }
    if (d.jitter.rotation_rad > 0.0) {
      d.rotation_rad = draw_vec3(seed, stream, kRotation, d.jitter.rotation_rad);
      const double angle = d.rotation_rad.norm();
      if (angle > 0.0) {
        const Eigen::Matrix3d r = Eigen::AngleAxisd(angle, d.rotation_rad / angle).toRotationMatrix();
        const Vec3 centre = centre_of_mass_m(body);
        for (Vec3& x : body.x_m) x = centre + r * (x - centre);
      }
    }
    if (d.jitter.position_m > 0.0) {
      d.offset_m = draw_vec3(seed, stream, kPosition, d.jitter.position_m);
      for (Vec3& x : body.x_m) x += d.offset_m;
    }
    if (d.jitter.velocity_m_per_s > 0.0) {
      d.velocity_m_per_s = draw_vec3(seed, stream, kVelocity, d.jitter.velocity_m_per_s);
      for (Vec3& v : body.v_m_per_s) v += d.velocity_m_per_s;
    }
  }
  return drawn;
}

}  // namespace tcb
