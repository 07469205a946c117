#include "sim/dynamics/elastic_model.hpp"

#include <algorithm>

#include "sim/dynamics/corotational_fem.hpp"
#include "sim/dynamics/mass_spring.hpp"

namespace tcb {

std::vector<double> lumped_masses_kg(const TetMesh& mesh, const std::vector<Vec3>& x, double density) {
  std::vector<double> m(mesh.vertex_count(), 0.0);
  const std::vector<char>& degenerate = mesh.is_degenerate;
  for (std::size_t i = 0; i < mesh.tet_count(); ++i) {
    if (degenerate[i]) continue;
    const Tet& t = mesh.tets[i];
    const double quarter = density * std::abs(signed_volume(x[t[0]], x[t[1]], x[t[2]], x[t[3]])) / 4.0;
    for (int k = 0; k < 4; ++k) m[t[k]] += quarter;
  }
  return m;
}

std::unique_ptr<ElasticModel> make_elastic_model(const TetMesh& mesh, const std::vector<Vec3>& rest_m,
                                                 const Material& material) {
  if (material.model == MaterialModel::MassSpring) return std::make_unique<MassSpring>(mesh, rest_m, material);
  return std::make_unique<CorotationalFem>(mesh, rest_m, material);
}

void take_velocities(std::span<Vec3> x, std::span<Vec3> v, const Eigen::VectorXd& v_new, double dt) {
  for (std::size_t i = 0; i < x.size(); ++i) {
    v[i] = v_new.segment<3>(3 * static_cast<Eigen::Index>(i));
    x[i] += dt * v[i];
  }
}

void ElasticModel::end_linear_step(std::span<Vec3> x, std::span<Vec3> v, const Eigen::VectorXd& v_new, double dt,
                                   int iterations, bool converged) {
  m_last_iterations = iterations;
  m_last_converged = converged;
  take_velocities(x, v, v_new, dt);
}

}  // namespace tcb
