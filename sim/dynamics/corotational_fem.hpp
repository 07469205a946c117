#pragma once
/// Corotational linear FEM on linear tets (Mueller & Gross, "Interactive
/// Virtual Materials", GI 2004), the framework of the paper.
///
/// Per element e with rest positions x0_e and linear-elastic stiffness K_e
/// (12x12, Lame lambda/mu, constant strain), the rotation R_e is extracted from
/// the deformation gradient (rotation_extraction.hpp) and the elastic force is
///   f_e = -R_e K_e (R_e^T x_e - x0_e),
/// which vanishes for any rigid motion of the element. Time integration is
/// linearised implicit Euler with Rayleigh damping C = alpha M + beta K:
///   (M + dt C + dt^2 K) v' = M v + dt (f_el(x) + f_ext),   x' = x + dt v'
/// with K = sum_e R_e K_e R_e^T assembled into a sparse matrix whose pattern is
/// built once, solved by Jacobi-preconditioned conjugate gradients warm-started
/// from v. Degenerate (flat) tets get no stiffness and no mass.
/// Cost per step: O(T) assembly + CG iterations over a matrix with ~45 nonzeros
/// per row. multiply() reads that matrix by 3x3 blocks (block_rows.hpp), with
/// Eigen's product's result bit for bit.
/// The rotations that elastic_energy_j() and elastic_forces() extract at x are
/// kept, with a copy of x (32 bytes an element, 24 a vertex), and the next
/// begin_linear_step() takes them instead of extracting again when it gets x
/// bit for bit: a run measures the energy at the positions its next step
/// starts from. Extraction is a function of F(x) and the warm start alone, and
/// both compute F(x) with the same function, so the step's numbers are the
/// same either way (in the project's builds, which fuse no multiply-adds: a
/// build that does must fuse both call sites alike). The kept rotations make
/// those const calls unsafe to make concurrently on one model; nothing does.

#include <Eigen/Geometry>
#include <Eigen/SparseCore>

#include <cstdint>

#include "sim/dynamics/block_rows.hpp"
#include "sim/dynamics/elastic_model.hpp"

namespace tcb {

class CorotationalFem final : public ElasticModel {
 public:
  CorotationalFem(const TetMesh& mesh, const std::vector<Vec3>& rest_m, const Material& material);

  void step(std::span<Vec3> x_m, std::span<Vec3> v_m_per_s, std::span<const Vec3> f_ext_n, double dt_s) override;
  std::unique_ptr<ElasticModel> clone() const override { return std::make_unique<CorotationalFem>(*this); }
  double elastic_energy_j(std::span<const Vec3> x_m) const override;
  void elastic_forces(std::span<const Vec3> x_m, std::span<Vec3> f_n) const override;
  const std::vector<double>& vertex_masses_kg() const override { return m_mass_kg; }
  bool begin_linear_step(std::span<const Vec3> x_m, std::span<const Vec3> v_m_per_s, std::span<const Vec3> f_ext_n,
                         double dt_s) override;
  void multiply(Eigen::Ref<const Eigen::VectorXd> v, Eigen::Ref<Eigen::VectorXd> out) const override;
  const Eigen::VectorXd& rhs() const override { return m_rhs; }
  Eigen::VectorXd diagonal() const override;
  using SparseMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;
  /// A as begin_linear_step() assembled it, compressed: what step()'s own
  /// solve uses, and what multiply() reads by blocks (tests and benchmarks
  /// compare the two products).
  const SparseMatrix& system() const { return m_system; }
  /// Steps that took kept rotations instead of extracting (tests check the
  /// saving happens where it should, and only there).
  std::int64_t kept_rotations_taken() const { return m_kept_rotations_taken; }
  double solver_tolerance() const override { return m_material.cg_tolerance; }
  int solver_max_iterations() const override { return m_material.cg_max_iterations; }

 private:
  struct Element {
    Tet v;
    Eigen::Matrix3d rest_edges_inverse;    // Dm^-1 with Dm = [x1-x0, x2-x0, x3-x0]
    Eigen::Matrix<double, 12, 12> stiffness;  // K_e, N/m
    std::array<Vec3, 4> rest_m;
    Eigen::Quaterniond rotation;           // warm start for the next extraction
  };

  Eigen::Matrix3d deformation_gradient(const Element& e, std::span<const Vec3> x) const;
  /// Each element's rotation at x, extracted from its warm start (which stays
  /// as it is), or the ones kept from the last call at the same x.
  const std::vector<Eigen::Quaterniond>& rotations_at(std::span<const Vec3> x) const;
  bool rotations_kept_for(std::span<const Vec3> x) const;
  void build_pattern(std::size_t vertex_count);

  Material m_material;
  std::vector<Element> m_elements;
  std::vector<double> m_mass_kg;
  SparseMatrix m_system;
  BlockRows m_blocks;  // m_system's pattern by 3x3 blocks, for multiply() (both solves)
  // For each element, the value offsets of its 16 3x3 blocks: entry
  // (i*4 + j)*3 + r is where row 3*v_i + r, column 3*v_j starts.
  std::vector<std::array<int, 48>> m_block_slots;
  std::vector<std::array<int, 3>> m_diagonal_slots;
  Eigen::VectorXd m_rhs, m_velocity;
  // What rotations_at() last extracted, from the warm starts as they are now,
  // and at which positions; begin_linear_step() moves the warm starts on and
  // drops them.
  mutable std::vector<Eigen::Quaterniond> m_kept_rotations;
  mutable std::vector<Vec3> m_kept_x_m;
  mutable bool m_rotations_kept = false;
  std::int64_t m_kept_rotations_taken = 0;
};

}  // namespace tcb
