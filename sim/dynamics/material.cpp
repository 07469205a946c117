#include "sim/dynamics/material.hpp"

namespace tcb {

std::string to_string(MaterialModel model) {
  return model == MaterialModel::CorotationalFem ? "corotational_fem" : "mass_spring";
}

std::string to_string(Integrator integrator) {
  switch (integrator) {
    case Integrator::ImplicitEuler: return "implicit_euler";
    case Integrator::EulerCromer: return "euler_cromer";
    case Integrator::VelocityVerlet: return "verlet";
  }
  return "?";
}

double lame_lambda_pa(const Material& m) {
  const double e = m.youngs_modulus_pa, nu = m.poisson_ratio;
  return e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
}

double lame_mu_pa(const Material& m) { return m.youngs_modulus_pa / (2.0 * (1.0 + m.poisson_ratio)); }

}  // namespace tcb
