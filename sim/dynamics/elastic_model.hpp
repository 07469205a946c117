#pragma once
/// The interface every deformation model offers the world, so a scene picks
/// the model per object: advance one step under given external forces.
///
/// Units: positions m, velocities m/s, forces N, time s, energy J.
/// Vertices with zero lumped mass (used by no non-degenerate tet) are never
/// moved: their velocity is kept at zero.

#include <memory>
#include <span>
#include <vector>

#include "sim/dynamics/material.hpp"
#include "sim/mesh/tet_mesh.hpp"

namespace tcb {

class ElasticModel {
 public:
  virtual ~ElasticModel() = default;
  /// Advances x and v by dt under the elastic forces and f_ext (per vertex).
  virtual void step(std::span<Vec3> x_m, std::span<Vec3> v_m_per_s, std::span<const Vec3> f_ext_n,
                    double dt_s) = 0;
  /// Elastic potential energy at x.
  virtual double elastic_energy_j(std::span<const Vec3> x_m) const = 0;
  /// Elastic forces at x (written, not added).
  virtual void elastic_forces(std::span<const Vec3> x_m, std::span<Vec3> f_n) const = 0;
  virtual const std::vector<double>& vertex_masses_kg() const = 0;
  /// Iterations of the last linear solve (0 for explicit models).
  virtual int last_solver_iterations() const { return 0; }
  /// False when the last linear solve stopped at its iteration limit.
  virtual bool last_solve_converged() const { return true; }
};

/// Lumped masses: each non-degenerate tet gives a quarter of density * volume
/// to each of its vertices (rest_m are the rest positions, metres).
std::vector<double> lumped_masses_kg(const TetMesh& mesh, const std::vector<Vec3>& rest_m, double density_kg_per_m3);

/// The model the material names, built on the rest shape rest_m.
std::unique_ptr<ElasticModel> make_elastic_model(const TetMesh& mesh, const std::vector<Vec3>& rest_m,
                                                 const Material& material);

}  // namespace tcb
