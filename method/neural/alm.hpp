#pragma once
/// Resolution by the augmented Lagrangian method (seed 002, N-Penetrate §3.3):
/// from a code z0, find the nearest code the detector calls collision-free,
///     minimise |z - z0|^2  subject to  c(z) <= 0,
/// with c the detector's logit plus a margin (c(z) = r(z) + margin: r <= 0 is
/// MLP(z) <= 0.5), so the problem has one constraint whatever the mesh size.
///
/// Method: Rockafellar's augmented Lagrangian for an inequality,
///     L(z) = |z - z0|^2 + (max(0, lambda + mu c(z))^2 - lambda^2) / (2 mu),
/// minimised over z by BFGS with an Armijo backtracking line search; then
/// lambda <- max(0, lambda + mu c(z)) and mu grows while c(z) is above the
/// tolerance. It stops when c(z) <= feasibility tolerance and the inner
/// minimisation has converged (`converged`) or its line search stalled (not
/// `converged`), or after max_outer updates; it returns its last iterate
/// either way (ALM's best effort when no feasible code is found).
///
/// Interruptible and resumable: the solver is a state machine whose unit of
/// work is one evaluation of c and its gradient (one network forward and
/// input-gradient pass), charged to the Budget as one work unit and followed
/// by a poll. alm_resume picks up exactly where the budget stopped it, so a
/// run cut into any number of pieces is bit-identical to one uninterrupted
/// run. The codes are unconstrained: z may leave the sampled box [-1, 1]^n
/// (the decoder extrapolates; the oracle judges the result, not the solver).

#include <cstdint>
#include <functional>

#include <Eigen/Dense>

#include "method/handler/budget.hpp"

namespace tcb::neural {

/// c(z) and its gradient; c(z) <= 0 is feasible.
using Constraint = std::function<double(const Eigen::VectorXd& z, Eigen::VectorXd& gradient)>;

struct AlmSettings {
  double mu_initial = 10.0;
  double mu_growth = 4.0;
  double mu_max = 1e8;
  int max_outer = 40;
  int max_inner = 60;                  ///< BFGS iterations per outer update
  double feasibility_tolerance = 1e-6; ///< c(z) <= this counts as feasible
  double gradient_tolerance = 1e-8;    ///< inner stop: |grad L| below this (relative to 1 + |z - z0|)
};

enum class AlmPhase : std::uint8_t { Evaluate, Direction, LineSearch, Done };

struct AlmState {
  Eigen::VectorXd z0, z;
  double lambda = 0.0, mu = 0.0;
  // Inner BFGS state at z: L, its gradient, c and its gradient there.
  double value = 0.0, c = 0.0;
  Eigen::VectorXd gradient, c_gradient, direction;
  Eigen::MatrixXd inverse_hessian;
  double step = 1.0;
  int inner = 0, outer = 0;
  bool stalled = false;  ///< the line search found no decrease: the inner solve is over
  AlmPhase phase = AlmPhase::Evaluate;
  std::uint64_t evaluations = 0;
  bool converged = false;  ///< stopped feasible with a converged inner solve (gradient test passed)
};

/// A solver at z0, not yet evaluated.
AlmState alm_start(const Eigen::VectorXd& z0, const AlmSettings& settings);

/// Runs until the state is Done or the budget expires (polled after every
/// evaluation). Returns true when Done.
bool alm_resume(AlmState& state, const Constraint& constraint, const AlmSettings& settings, Budget& budget);

}  // namespace tcb::neural
