#include "method/neural/alm.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tcb::neural {
namespace {

// L(z) and its gradient given c(z), grad c(z).
double lagrangian(const AlmState& s, const Eigen::VectorXd& z, double c, const Eigen::VectorXd& c_grad,
                  Eigen::VectorXd& grad) {
  const double shifted = std::max(0.0, s.lambda + s.mu * c);
  grad = 2.0 * (z - s.z0) + shifted * c_grad;
  return (z - s.z0).squaredNorm() + (shifted * shifted - s.lambda * s.lambda) / (2.0 * s.mu);
}

}  // namespace

AlmState alm_start(const Eigen::VectorXd& z0, const AlmSettings& settings) {
  if (!(settings.mu_initial > 0.0) || !(settings.mu_growth >= 1.0) || settings.max_outer < 1 || settings.max_inner < 1)
    throw std::invalid_argument("alm_start: needs mu_initial > 0, mu_growth >= 1, max_outer and max_inner >= 1");
  AlmState s;
  s.z0 = z0;
  s.z = z0;
  s.mu = settings.mu_initial;
  s.inverse_hessian = Eigen::MatrixXd::Identity(z0.size(), z0.size()) * 0.5;
  return s;
}

bool alm_resume(AlmState& s, const Constraint& constraint, const AlmSettings& settings, Budget& budget) {
  const Eigen::Index n = s.z0.size();
  while (s.phase != AlmPhase::Done) {
    if (budget.expired()) return false;
    switch (s.phase) {
      case AlmPhase::Evaluate: {
        s.c = constraint(s.z, s.c_gradient);
        budget.charge(1), ++s.evaluations;
        s.value = lagrangian(s, s.z, s.c, s.c_gradient, s.gradient);
        s.phase = AlmPhase::Direction;
        break;
      }
      case AlmPhase::Direction: {
        const bool small_gradient = s.gradient.norm() <= settings.gradient_tolerance * (1.0 + (s.z - s.z0).norm());
        const bool stationary = s.stalled || small_gradient;
        const bool inner_done = stationary || s.inner >= settings.max_inner;
        if (!inner_done) {
          s.direction = -s.inverse_hessian * s.gradient;
          if (s.direction.dot(s.gradient) >= 0.0) {  // lost descent: restart the curvature
            s.inverse_hessian = Eigen::MatrixXd::Identity(n, n) * 0.5;
            s.direction = -s.inverse_hessian * s.gradient;
          }
          s.step = 1.0;
          s.phase = AlmPhase::LineSearch;
          break;
        }
        // The inner problem is solved: multiplier update, or stop.
        if (s.c <= settings.feasibility_tolerance && stationary) {
          s.converged = small_gradient;  // a stalled line search stops, but is not called converged
          s.phase = AlmPhase::Done;
          break;
        }
        s.lambda = std::max(0.0, s.lambda + s.mu * s.c);
        if (s.c > settings.feasibility_tolerance) s.mu = std::min(s.mu * settings.mu_growth, settings.mu_max);
        ++s.outer;
        s.inner = 0;
        s.stalled = false;
        s.inverse_hessian = Eigen::MatrixXd::Identity(n, n) * 0.5;
        // c and its gradient at z are known: only L changes with lambda and mu.
        s.value = lagrangian(s, s.z, s.c, s.c_gradient, s.gradient);
        s.phase = s.outer >= settings.max_outer ? AlmPhase::Done : AlmPhase::Direction;
        break;
      }
      case AlmPhase::LineSearch: {
        const Eigen::VectorXd trial = s.z + s.step * s.direction;
        Eigen::VectorXd c_grad, grad;
        const double c = constraint(trial, c_grad);
        budget.charge(1), ++s.evaluations;
        const double value = lagrangian(s, trial, c, c_grad, grad);
        if (value <= s.value + 1e-4 * s.step * s.gradient.dot(s.direction)) {
          const Eigen::VectorXd step = trial - s.z, change = grad - s.gradient;
          const double curvature = step.dot(change);
          if (curvature > 1e-12 * step.norm() * change.norm()) {  // BFGS update of the inverse Hessian
            const double rho = 1.0 / curvature;
            const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
            s.inverse_hessian = (I - rho * step * change.transpose()) * s.inverse_hessian *
                                    (I - rho * change * step.transpose()) +
                                rho * step * step.transpose();
          }
          s.z = trial, s.c = c, s.c_gradient = c_grad, s.value = value, s.gradient = grad;
          ++s.inner;
          s.phase = AlmPhase::Direction;
        } else if ((s.step *= 0.5) < 1e-12) {
          s.stalled = true;  // no decrease along a descent direction: as stationary as doubles allow
          s.phase = AlmPhase::Direction;
        }
        break;
      }
      case AlmPhase::Done: break;
    }
  }
  return true;
}

}  // namespace tcb::neural
