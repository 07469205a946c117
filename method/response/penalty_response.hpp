#pragma once
/// Penalty response (METHOD.md s.4; the paper, Heidelberger et al. 2004).
///
/// Normal force on the colliding point p (of A, inside tet T of B):
///   f_n = max(0, c_r d - c v_n) r,   v_n = (v_p - v_T(p)) . r
/// with c_r the pair's response stiffness (N/m), d the depth (m), r the
/// direction; v_T(p) interpolates T's vertex velocities with p's barycentric
/// weights. The max(0, .) keeps damping from pulling objects together.
/// Friction is Coulomb: f_t = -min(mu |f_n|, m v_t / dt) v_t / |v_t| with v_t
/// the tangential relative velocity.
/// Under explicit response (below) the whole force is applied over the next
/// step as an external force, so damping and friction are clamped to what can at most stop the relative motion within
/// one step: c = min(c_d, m / dt) and the m v_t / dt bound above, with m the
/// reduced mass of the point and the tet at p (the point's mass when B is
/// passive). Without these clamps a friction force on a gram-scale vertex
/// reverses the sliding every step and the contact chatters or explodes. The
/// stiffness is not clamped: c_r must stay below about 4 m / dt^2 (scenes say
/// so), and an explosion is reported by the run as unstable.
/// The reaction -(f_n + f_t) is spread over T's vertices by the same
/// barycentric weights (which sum to 1): the total force is zero, so momentum
/// is conserved. A contact without depth gets no force.
///
/// Two response modes (scene key collision.response):
///   explicit  the force above is added to the bodies as an external force
///             (symplectic in the contact spring; the clamps above apply);
///   implicit  (default) the normal part becomes a ContactLink
///             (sim/world/contact_link.hpp) that the integrator solves with
///             the bodies: lambda = c_r (d - h v_n+) - c v_n+ at the end of
///             the step, unclamped damping (the implicit solve needs no m/dt
///             bound), unilateral. Friction stays explicit, as above.

#include "method/handler/contact.hpp"
#include "sim/world/world.hpp"

namespace tcb {

struct ResponseParams {
  double stiffness_n_per_m = 1.0e4;
  double damping_n_s_per_m = 0.0;
  double friction = 0.0;
};

/// The penalty force on the colliding point of `contact` for a step of dt_s
/// (see file comment).
Vec3 penalty_force(const World& world, const Contact& contact, const ResponseParams& params, double dt_s);

/// Reduced mass (kg) of the contact's point and the tet at its barycentric
/// position; the point's own mass when the other body is passive, the
/// tet's when the point's body is (passive and driven bodies do not yield).
double contact_reduced_mass(const World& world, const Contact& contact);

/// Adds force to the point and the barycentric reaction to the tet's vertices.
/// This and the two link functions below do nothing for a contact of a
/// passive body with itself (a latent-driven body's self-collision): neither
/// side is integrated, so it acts on nothing.
void apply_contact_force(World& world, const Contact& contact, const Vec3& force_n);

enum class ResponseMode { Implicit, Explicit };

/// Implicit response for a force that is not computed from a depth (an
/// extrapolated or held estimate): its normal part f.n > 0 becomes a link of
/// the equivalent depth (f.n) / c_r, so the contact's spring and damper are
/// integrated implicitly like any other; the rest of the force (and all of it
/// when f.n <= 0 or c_r = 0) is added as a force.
void add_force_link(World& world, const Contact& where, const Vec3& force_n, const ResponseParams& params);

/// Implicit response: hands the world the contact's normal spring and damper
/// as a link (with the contact's depth and direction as they stand) and adds
/// its friction (the friction of penalty_force) as a force. Nothing for a
/// contact without a positive depth.
void add_contact_link(World& world, const Contact& contact, const ResponseParams& params, double dt_s);

}  // namespace tcb
