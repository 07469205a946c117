#pragma once
/// Mass-spring model with volume preservation (Teschner, Heidelberger,
/// Mueller, Gross, "A Versatile and Robust Model for Geometrically Complex
/// Deformable Solids", CGI 2004), the model of the student haptic system.
///
/// Energies, with rest edge length l0 and rest tet volume V0:
///   edge:   E = 1/2 k_e ((l - l0) / l0)^2
///   volume: E = 1/2 k_v ((V - V0) / V0)^2,  V the signed volume
/// Forces are -grad E. Stiffnesses (joules) follow from the material so the
/// scene keys mean the same for both models: k_e = Young's modulus times the
/// edge's share of volume (a sixth of each incident tet), k_v = bulk modulus
/// E / (3 (1 - 2 nu)) times V0. This is an approximation of the continuum,
/// not a convergent discretisation. Because V is signed, the volume term pushes
/// an inverted tet back through zero volume.
/// Damping: -alpha m v (material damping_mass_per_s).
/// Integration (explicit, so dt must resolve the stiffest spring):
///   euler_cromer: v += dt a(x, v); x += dt v
///   verlet (velocity Verlet, f_ext held over the step):
///     v+ = v + dt/2 a(x, v); x += dt v+; v = v+ + dt/2 a(x', v+)
/// As a linear step (implicit contact, elastic_model.hpp) euler_cromer is
/// M v+ = M v + dt (f(x) + f_ext - alpha M v): the springs stay explicit, the
/// contacts joined to this system are implicit. Velocity Verlet has no such
/// form (begin_linear_step returns false); scenes are told so when loaded.

#include "sim/dynamics/elastic_model.hpp"

namespace tcb {

class MassSpring final : public ElasticModel {
 public:
  MassSpring(const TetMesh& mesh, const std::vector<Vec3>& rest_m, const Material& material);

  void step(std::span<Vec3> x_m, std::span<Vec3> v_m_per_s, std::span<const Vec3> f_ext_n, double dt_s) override;
  std::unique_ptr<ElasticModel> clone() const override { return std::make_unique<MassSpring>(*this); }
  double elastic_energy_j(std::span<const Vec3> x_m) const override;
  void elastic_forces(std::span<const Vec3> x_m, std::span<Vec3> f_n) const override;
  const std::vector<double>& vertex_masses_kg() const override { return m_mass_kg; }
  bool begin_linear_step(std::span<const Vec3> x_m, std::span<const Vec3> v_m_per_s, std::span<const Vec3> f_ext_n,
                         double dt_s) override;
  void multiply(Eigen::Ref<const Eigen::VectorXd> v, Eigen::Ref<Eigen::VectorXd> out) const override;
  const Eigen::VectorXd& rhs() const override { return m_rhs; }
  Eigen::VectorXd diagonal() const override { return m_diagonal; }
  double solver_tolerance() const override { return m_material.cg_tolerance; }
  int solver_max_iterations() const override { return m_material.cg_max_iterations; }

 private:
  struct Spring {
    Edge v;
    double rest_length_m;
    double stiffness_j;
  };
  struct VolumeTerm {
    Tet v;
    double rest_volume_m3;
    double stiffness_j;
  };
  void accelerations(std::span<const Vec3> x, std::span<const Vec3> v, std::span<const Vec3> f_ext);

  Material m_material;
  std::vector<Spring> m_springs;
  std::vector<VolumeTerm> m_volumes;
  std::vector<double> m_mass_kg;
  std::vector<Vec3> m_force, m_acceleration, m_half_velocity;
  Eigen::VectorXd m_rhs, m_diagonal;  // the linear step: A = diag(m_diagonal)
};

}  // namespace tcb
