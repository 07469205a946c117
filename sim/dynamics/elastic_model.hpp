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
  /// A copy with the same state (warm starts included), so a copied world
  /// steps bit for bit like the original (clone_world, world.hpp).
  virtual std::unique_ptr<ElasticModel> clone() const = 0;
  /// Advances x and v by dt under the elastic forces and f_ext (per vertex).
  virtual void step(std::span<Vec3> x_m, std::span<Vec3> v_m_per_s, std::span<const Vec3> f_ext_n,
                    double dt_s) = 0;
  /// Elastic potential energy at x. A model may keep what it computes here for
  /// the next step (CorotationalFem keeps its rotations), so this and
  /// elastic_forces() must not run concurrently on one model.
  virtual double elastic_energy_j(std::span<const Vec3> x_m) const = 0;
  /// Elastic forces at x (written, not added).
  virtual void elastic_forces(std::span<const Vec3> x_m, std::span<Vec3> f_n) const = 0;
  virtual const std::vector<double>& vertex_masses_kg() const = 0;
  /// Iterations of the last linear solve: the model's own, or those a coupled
  /// contact solve reported to it (0 for an explicit step).
  int last_solver_iterations() const { return m_last_iterations; }
  /// False when the last linear solve stopped at its iteration limit.
  bool last_solve_converged() const { return m_last_converged; }

  // The step as a linear system in the new velocities, A v+ = b (3 entries
  // per vertex), so that contact terms coupling bodies can join one solve
  // (sim/world/coupled_solve.hpp). step() is begin + a solve of its own + end.
  /// Assembles A and b for the step from x, v under f_ext; false when the
  /// model's integrator has no such form (explicit velocity Verlet).
  virtual bool begin_linear_step(std::span<const Vec3> x_m, std::span<const Vec3> v_m_per_s,
                                 std::span<const Vec3> f_ext_n, double dt_s) = 0;
  /// out = A v (after begin_linear_step); out has v's size and does not
  /// overlap it. Segments of a longer vector bind without a copy (a coupled
  /// solve multiplies each body's part of its unknowns in place).
  virtual void multiply(Eigen::Ref<const Eigen::VectorXd> v, Eigen::Ref<Eigen::VectorXd> out) const = 0;
  /// b, and the diagonal of A (for preconditioning).
  virtual const Eigen::VectorXd& rhs() const = 0;
  virtual Eigen::VectorXd diagonal() const = 0;
  /// Solver tolerance (relative residual) and iteration limit of the model.
  virtual double solver_tolerance() const = 0;
  virtual int solver_max_iterations() const = 0;
  /// Takes the solved velocities: v = v+, x += dt v+ (take_velocities), and
  /// records the solver's iterations and convergence.
  void end_linear_step(std::span<Vec3> x_m, std::span<Vec3> v_m_per_s, const Eigen::VectorXd& v_new, double dt_s,
                       int iterations, bool converged);

 protected:
  /// The solver record of a step without a linear solve (explicit integrators).
  void record_explicit_step() {
    m_last_iterations = 0;
    m_last_converged = true;
  }

 private:
  int m_last_iterations = 0;
  bool m_last_converged = true;
};

/// The end of a linear step: v = v_new (3 entries per vertex), x += dt v.
void take_velocities(std::span<Vec3> x_m, std::span<Vec3> v_m_per_s, const Eigen::VectorXd& v_new, double dt_s);

/// Lumped masses: each non-degenerate tet gives a quarter of density * volume
/// to each of its vertices (rest_m are the rest positions, metres).
std::vector<double> lumped_masses_kg(const TetMesh& mesh, const std::vector<Vec3>& rest_m, double density_kg_per_m3);

/// The model the material names, built on the rest shape rest_m.
std::unique_ptr<ElasticModel> make_elastic_model(const TetMesh& mesh, const std::vector<Vec3>& rest_m,
                                                 const Material& material);

}  // namespace tcb
