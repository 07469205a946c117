#pragma once
/// The simulated world: deformable and passive bodies, gravity, an optional
/// ground. It owns all simulation state; collision handlers read positions and
/// add forces into Body::contact_force_n before World::step().
///
/// One step: for each dynamic body, f_ext = m g + contact forces, the body's
/// elastic model advances it, then the ground projects it. Bodies with
/// contact links (implicit penalty contact, contact_link.hpp) are advanced
/// together with the bodies they touch (coupled_solve.hpp); a body without
/// links takes its model's own step, exactly as without contacts. Passive bodies are
/// never integrated (their positions stay as built) but still collide; a
/// driven passive body moves to its trajectory's position at the new time,
/// with the velocity of that motion; a latent-driven one (latent_path.hpp)
/// to the decoded shape of its path's code at the new time, likewise.
/// Contact forces and links are cleared at the end of every step; the force
/// that contacts actually applied in it (explicit forces plus the links'
/// solved forces) stays in Body::applied_contact_force_n. Units: SI.
///
/// Energy bookkeeping: total_energy_j() of the dynamic bodies (kinetic +
/// elastic + gravitational) changes only by the work of driven bodies
/// (driven_work_j) and by what the integrator, the contacts and the ground
/// projection dissipate or inject; experiments/metrics/energy_meter.hpp
/// judges the rest.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sim/dynamics/elastic_model.hpp"
#include "sim/world/contact_link.hpp"
#include "sim/world/coupled_solve.hpp"
#include "sim/world/ground.hpp"
#include "sim/latent/latent_path.hpp"
#include "sim/world/trajectory.hpp"

namespace tcb {

struct Body {
  std::string name;
  std::string group;                    ///< the scene object it came from (stacks share one)
  std::shared_ptr<const TetMesh> mesh;  ///< topology; shared by copies of one mesh
  std::vector<Vec3> x_m;                ///< current positions
  std::vector<Vec3> v_m_per_s;
  std::vector<Vec3> contact_force_n;    ///< accumulated by the handler, cleared each step
  /// What contacts applied in the last step: contact_force_n plus the links' solved forces.
  std::vector<Vec3> applied_contact_force_n;
  std::vector<double> mass_kg;          ///< lumped
  Material material;
  bool passive = false;
  bool self_collision = false;
  std::unique_ptr<ElasticModel> model;  ///< null for passive bodies
  /// Driven bodies (passive): positions are shape_m + trajectory->at(t) at every step.
  std::shared_ptr<const Trajectory> trajectory;
  std::vector<Vec3> shape_m;            ///< the scaled mesh before translation (driven bodies)
  /// Latent-driven bodies (passive): positions are latent->positions_m(z(t))
  /// at every step, z(t) = latent->path.at(t), which latent_code holds.
  std::shared_ptr<const LatentDrive> latent;
  Eigen::VectorXd latent_code;
  std::vector<Vec3> external_force_n;   ///< scratch of step()
};

/// Whether a body's self-collision is handled: enabled for it, and its shape
/// can change (a dynamic body, or one driven through a latent path). A fixed
/// or rigidly driven body cannot come to collide with itself.
inline bool self_collision_active(const Body& body) {
  return body.self_collision && (!body.passive || body.latent != nullptr);
}

/// Mass-weighted centre of a body's vertices (m); the plain mean when it has no mass.
Vec3 centre_of_mass_m(const Body& body);

class World {
 public:
  std::vector<Body> bodies;
  Vec3 gravity_m_per_s2 = Vec3(0.0, -9.81, 0.0);
  std::optional<GroundPlane> ground;
  double time_s = 0.0;
  std::int64_t step_index = 0;
  /// Implicit penalty contacts for the next step, added by the handler.
  std::vector<ContactLink> contact_links;
  /// What build_world found in the objects and did about it (inverted tets
  /// reoriented, flat tets inert, massless vertices held still), in words,
  /// for the run's warnings.
  std::vector<std::string> build_warnings;
  /// What the implicit contact solves of the last step did.
  ContactSolveStats last_contact_solve;
  /// Work the driven bodies did on the dynamic ones through their contacts
  /// since the world was built (J): per step, -f . dx summed over the driven
  /// vertices, f the contact force the step applied to a driven vertex and dx
  /// its travel over the step. The only work done from outside: a static
  /// passive body or the ground does none (it does not move where it
  /// touches; it can only take energy away).
  double driven_work_j = 0.0;

  void step(double dt_s);

  double kinetic_energy_j() const;          ///< of the dynamic bodies
  double elastic_energy_j() const;          ///< of the dynamic bodies; not concurrently (elastic_model.hpp)
  double gravity_potential_j() const;       ///< -m g . x over dynamic bodies
  /// kinetic + elastic + gravitational energy of the dynamic bodies (the
  /// elastic part costs a rotation extraction per tet, which a corotational
  /// body's next step skips if it starts from these positions).
  double total_energy_j() const { return kinetic_energy_j() + elastic_energy_j() + gravity_potential_j(); }
  /// Largest vertex speed of the dynamic bodies; NaN if any state is not finite.
  double max_speed_m_per_s() const;
  std::size_t vertex_count() const;
  /// Sum of the contact forces the last step applied to the driven bodies
  /// (what a haptic device would render); nullopt without driven bodies.
  std::optional<Vec3> driven_contact_force_n() const;
};

/// A deep copy of the world's whole state (bodies, their models' warm starts,
/// pending contact forces and links): it steps bit for bit like the
/// original. For measurements on a shadow of the run (the force reference);
/// World itself is not copyable, so no step copies it by accident.
World clone_world(const World& world);

}  // namespace tcb
