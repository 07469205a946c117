#include "sim/dynamics/mass_spring.hpp"

#include <algorithm>
#include <map>

namespace tcb {

MassSpring::MassSpring(const TetMesh& mesh, const std::vector<Vec3>& rest, const Material& material)
    : m_material(material), m_mass_kg(lumped_masses_kg(mesh, rest, material.density_kg_per_m3)) {
  const double bulk_modulus = material.youngs_modulus_pa / (3.0 * (1.0 - 2.0 * material.poisson_ratio));
  const std::vector<char>& degenerate = mesh.is_degenerate;
  std::map<Edge, double> edge_volume;  // each edge's share of the incident tets' volume
  for (std::size_t i = 0; i < mesh.tet_count(); ++i) {
    if (degenerate[i]) continue;
    const Tet& t = mesh.tets[i];
    const double volume = signed_volume(rest[t[0]], rest[t[1]], rest[t[2]], rest[t[3]]);
    if (!(volume > 0.0)) continue;
    m_volumes.push_back({t, volume, bulk_modulus * volume});
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) edge_volume[{std::min(t[a], t[b]), std::max(t[a], t[b])}] += volume / 6.0;
  }
  for (const auto& [e, volume] : edge_volume) {
    const double length = (rest[e[1]] - rest[e[0]]).norm();
    if (length > 0.0) m_springs.push_back({e, length, material.youngs_modulus_pa * volume});
  }
  m_force.resize(mesh.vertex_count());
  m_acceleration.resize(mesh.vertex_count());
  m_half_velocity.resize(mesh.vertex_count());
}

void MassSpring::elastic_forces(std::span<const Vec3> x, std::span<Vec3> f) const {
  std::fill(f.begin(), f.end(), Vec3::Zero());
  for (const Spring& s : m_springs) {
    const Vec3 d = x[s.v[1]] - x[s.v[0]];
    const double length = d.norm();
    if (length == 0.0) continue;  // direction undefined; the volume terms still act
    const double strain = (length - s.rest_length_m) / s.rest_length_m;
    const Vec3 pull = (s.stiffness_j * strain / (s.rest_length_m * length)) * d;
    f[s.v[0]] += pull;
    f[s.v[1]] -= pull;
  }
  for (const VolumeTerm& t : m_volumes) {
    const Vec3 &x0 = x[t.v[0]], &x1 = x[t.v[1]], &x2 = x[t.v[2]], &x3 = x[t.v[3]];
    const Vec3 e1 = x1 - x0, e2 = x2 - x0, e3 = x3 - x0;
    const double volume = e1.dot(e2.cross(e3)) / 6.0;
    const double c = (volume - t.rest_volume_m3) / t.rest_volume_m3;
    const double scale = -t.stiffness_j * c / t.rest_volume_m3 / 6.0;
    const Vec3 g1 = e2.cross(e3), g2 = e3.cross(e1), g3 = e1.cross(e2);  // 6 dV/dx_k
    f[t.v[1]] += scale * g1;
    f[t.v[2]] += scale * g2;
    f[t.v[3]] += scale * g3;
    f[t.v[0]] -= scale * (g1 + g2 + g3);
  }
}

double MassSpring::elastic_energy_j(std::span<const Vec3> x) const {
  double energy = 0.0;
  for (const Spring& s : m_springs) {
    const double strain = ((x[s.v[1]] - x[s.v[0]]).norm() - s.rest_length_m) / s.rest_length_m;
    energy += 0.5 * s.stiffness_j * strain * strain;
  }
  for (const VolumeTerm& t : m_volumes) {
    const double volume = signed_volume(x[t.v[0]], x[t.v[1]], x[t.v[2]], x[t.v[3]]);
    const double c = (volume - t.rest_volume_m3) / t.rest_volume_m3;
    energy += 0.5 * t.stiffness_j * c * c;
  }
  return energy;
}

void MassSpring::accelerations(std::span<const Vec3> x, std::span<const Vec3> v, std::span<const Vec3> f_ext) {
  elastic_forces(x, m_force);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double m = m_mass_kg[i];
    m_acceleration[i] =
        m > 0.0 ? Vec3((m_force[i] + f_ext[i]) / m - m_material.damping_mass_per_s * v[i]) : Vec3(Vec3::Zero());
  }
}

void MassSpring::step(std::span<Vec3> x, std::span<Vec3> v, std::span<const Vec3> f_ext, double dt) {
  record_explicit_step();
  const std::size_t n = x.size();
  for (std::size_t i = 0; i < n; ++i)
    if (m_mass_kg[i] == 0.0) v[i] = Vec3::Zero();  // massless vertices never move
  if (m_material.integrator == Integrator::VelocityVerlet) {
    accelerations(x, v, f_ext);
    for (std::size_t i = 0; i < n; ++i) {
      m_half_velocity[i] = v[i] + 0.5 * dt * m_acceleration[i];
      x[i] += dt * m_half_velocity[i];
    }
    accelerations(x, m_half_velocity, f_ext);
    for (std::size_t i = 0; i < n; ++i) v[i] = m_half_velocity[i] + 0.5 * dt * m_acceleration[i];
  } else {
    accelerations(x, v, f_ext);
    for (std::size_t i = 0; i < n; ++i) {
      v[i] += dt * m_acceleration[i];
      x[i] += dt * v[i];
    }
  }
}

bool MassSpring::begin_linear_step(std::span<const Vec3> x, std::span<const Vec3> v, std::span<const Vec3> f_ext,
                                   double dt) {
  if (m_material.integrator != Integrator::EulerCromer) return false;
  const std::size_t n = x.size();
  elastic_forces(x, m_force);
  m_rhs.resize(3 * n);
  m_diagonal.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const double m = m_mass_kg[i];
    // A massless vertex is pinned: the row becomes v = 0.
    const Vec3 b = m > 0.0 ? Vec3(m * v[i] + dt * (m_force[i] + f_ext[i] - m_material.damping_mass_per_s * m * v[i]))
                           : Vec3(Vec3::Zero());
    m_rhs.segment<3>(3 * i) = b;
    m_diagonal.segment<3>(3 * i).setConstant(m > 0.0 ? m : 1.0);
  }
  return true;
}

void MassSpring::multiply(Eigen::Ref<const Eigen::VectorXd> v, Eigen::Ref<Eigen::VectorXd> out) const {
  out = m_diagonal.cwiseProduct(v);
}

}  // namespace tcb
