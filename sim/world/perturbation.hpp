#pragma once
/// Perturbed initial conditions, so that seeds mean something: repeats of a
/// configuration are different samples of it, and a chaotic scene's own
/// sensitivity can be measured (the divergence noise floor).
///
/// Each dynamic body gets, from the run's seed and the project's
/// counter-based generator (sim/random/counter_random.hpp; stream = the
/// body's index, index = the draw's number below), draws u uniform in [-1, 1):
///   material  (index 9):     Young's modulus scaled by 1 + material_rel * u,
///                            the elastic model rebuilt on the unperturbed rest shape;
///   rotation  (indices 6-8): a rigid rotation about the body's centre of mass
///                            by the rotation vector r, r_k = rotation_rad * u_k
///                            (angle |r|, axis r / |r|); velocities are not rotated;
///   position  (indices 0-2): a rigid translation, offset_k = position_m * u_k;
///   velocity  (indices 3-5): added to every vertex, dv_k = velocity_m_per_s * u_k;
/// applied in that order. A jitter of 0 draws nothing and changes nothing, bit
/// for bit, whatever the seed; a body's draws do not depend on the other
/// bodies' jitters. Passive bodies (fixed or driven) are never perturbed (the
/// scene reader refuses a per-object jitter on one). Units: m, m/s, rad, and a
/// relative factor.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "sim/world/world.hpp"

namespace tcb {

/// The bounds of one body's draws; all >= 0, material_rel < 1 (a modulus stays positive).
struct Jitter {
  double position_m = 0.0;
  double velocity_m_per_s = 0.0;
  double rotation_rad = 0.0;
  double material_rel = 0.0;
  bool any() const { return position_m > 0.0 || velocity_m_per_s > 0.0 || rotation_rad > 0.0 || material_rel > 0.0; }
};

/// An object's own [object.perturb] table: the keys it sets replace the global ones.
struct JitterOverride {
  std::optional<double> position_m, velocity_m_per_s, rotation_rad, material_rel;
  Jitter over(const Jitter& base) const;
};

struct Perturbation {
  Jitter global;  ///< [perturb]
  /// By scene object name; the copies of a stacked object share its table
  /// (Body::group) and draw separately.
  std::map<std::string, JitterOverride> objects;
  Jitter for_body(const Body& body) const;
};

/// What one body was given, for run.json. Zero (factor 1) when not perturbed.
struct BodyPerturbation {
  Jitter jitter;  ///< the effective bounds (zero for passive bodies)
  Vec3 offset_m = Vec3::Zero();
  Vec3 velocity_m_per_s = Vec3::Zero();
  Vec3 rotation_rad = Vec3::Zero();
  double youngs_modulus_factor = 1.0;
};

/// Perturbs the world as the run's initial state; one entry per body.
std::vector<BodyPerturbation> perturb_world(World& world, const Perturbation& perturbation, std::uint64_t seed);

}  // namespace tcb
