#pragma once
/// Implicit penalty contact: the bodies joined by contact links
/// (contact_link.hpp) take one implicit Euler step together.
///
/// Bodies are grouped into components: two dynamic bodies linked by a contact
/// are in one component; a body whose links all lead to passive (or driven)
/// bodies is a component of its own. For each component the bodies' linear
/// steps (ElasticModel::begin_linear_step: A_b v+ = b_b) are joined with the
/// links' terms, h (h k + c) J^T n n^T J on the left and h k d J^T n (minus the
/// known part of passive sides' velocities) on the right, and solved by
/// Jacobi-preconditioned conjugate gradients, matrix-free, warm-started from
/// the current velocities, to the smallest relative residual any of its
/// bodies asks for. Unilateral contact: a link whose force would pull comes
/// out with lambda < 0; such links are dropped and the component is solved
/// once more (no further rounds: a link still pulling after that is kept and
/// counted). Bodies without links are not touched here: World::step gives
/// them their own solve, bit for bit as without contacts.
///
/// The force each kept link applied (lambda n on the point, -w_k lambda n on
/// the tet's vertices) is added to Body::applied_contact_force_n.
/// Cost: per CG iteration one product with every body's matrix and O(links).

#include <span>
#include <vector>

#include "sim/world/contact_link.hpp"

namespace tcb {

class World;

/// What the implicit contact solves of one step did.
struct ContactSolveStats {
  std::int64_t links = 0;        ///< links handed in
  std::int64_t components = 0;   ///< coupled solves
  std::int64_t resolved = 0;     ///< components solved a second time after dropping pulling links
  std::int64_t dropped = 0;      ///< links dropped for pulling
  std::int64_t still_pulling = 0;  ///< links that pulled after the second solve too
  std::int64_t iterations = 0;   ///< CG iterations over all components and solves
  bool converged = true;
};

/// Integrates every dynamic body that has a link, with its component;
/// `integrated[b]` is set for them. Throws std::logic_error when a linked
/// body's model has no linear step (scenes are refused before that).
ContactSolveStats step_linked_bodies(World& world, std::span<const ContactLink> links, double dt_s,
                                     std::vector<char>& integrated);

}  // namespace tcb
