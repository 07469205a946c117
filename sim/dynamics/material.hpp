#pragma once
/// Material of one deformable object, as a scene gives it. SI units.

#include <string>

namespace tcb {

enum class MaterialModel { CorotationalFem, MassSpring };
/// corotational_fem integrates with implicit Euler only; mass_spring with
/// Euler-Cromer (symplectic Euler, the default) or velocity Verlet.
enum class Integrator { ImplicitEuler, EulerCromer, VelocityVerlet };

struct Material {
  MaterialModel model = MaterialModel::CorotationalFem;
  Integrator integrator = Integrator::ImplicitEuler;
  double youngs_modulus_pa = 1.0e5;
  double poisson_ratio = 0.3;
  double density_kg_per_m3 = 1000.0;
  double damping_mass_per_s = 0.0;  ///< Rayleigh alpha: force -alpha * m * v
  double damping_stiffness_s = 0.0; ///< Rayleigh beta (FEM only): -beta * K * v
  double cg_tolerance = 1.0e-6;     ///< FEM: relative residual of the velocity solve
  int cg_max_iterations = 300;
};

std::string to_string(MaterialModel model);
std::string to_string(Integrator integrator);

/// Lame parameters (Pa) from Young's modulus and Poisson's ratio.
double lame_lambda_pa(const Material& m);
double lame_mu_pa(const Material& m);

}  // namespace tcb
