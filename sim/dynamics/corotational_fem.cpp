#include "sim/dynamics/corotational_fem.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/LU>

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

#include "sim/dynamics/rotation_extraction.hpp"

// step()'s own solve is Eigen's ConjugateGradient with its matrix read by
// blocks: Eigen's matrix-free interface (a matrix type whose product Eigen
// asks us for) around the assembled system, and Eigen's Jacobi
// preconditioner on the compressed matrix itself. The rest of the solve is
// Eigen's vector arithmetic on the same values. Its two products take
// different paths than for a SparseMatrix but give the same bits:
// `tmp = mat * p` zeroes tmp and adds 1 * (A p) in both; `r = b - mat * x`
// is r = b, r += -1 * (A x) for a SparseMatrix, and a temporary 0 + 1 * (A x)
// subtracted from b here, the same numbers since b - y == b + (-y) exactly
// and A x is never -0.0 (block_rows.hpp). Only a NaN's sign bit could differ.
// tests/sim/dynamics/block_rows_test.cpp compares 20 steps bit for bit.
namespace tcb {
namespace {
class BlockSystem;
}  // namespace
}  // namespace tcb

template <>
struct Eigen::internal::traits<tcb::BlockSystem> : traits<tcb::CorotationalFem::SparseMatrix> {};

namespace tcb {
namespace {

class BlockSystem : public Eigen::EigenBase<BlockSystem> {
 public:
  using Scalar = double;
  using RealScalar = double;
  using StorageIndex = int;
  enum { ColsAtCompileTime = Eigen::Dynamic, MaxColsAtCompileTime = Eigen::Dynamic, IsRowMajor = true };

  explicit BlockSystem(const CorotationalFem& fem) : m_fem(&fem), m_product(fem.system().rows()) {}
  Eigen::Index rows() const { return m_fem->system().rows(); }
  Eigen::Index cols() const { return m_fem->system().cols(); }
  const CorotationalFem::SparseMatrix& sparse() const { return m_fem->system(); }

  template <typename Rhs>
  Eigen::Product<BlockSystem, Rhs, Eigen::AliasFreeProduct> operator*(const Eigen::MatrixBase<Rhs>& x) const {
    return Eigen::Product<BlockSystem, Rhs, Eigen::AliasFreeProduct>(*this, x.derived());
  }

  // dst += alpha * A x, A x's entries as Eigen's row loop sums them, with
  // its final `dst(i) += alpha * sum` (SparseDenseProduct.h; file comment).
  template <typename Dest>
  void scale_and_add(Dest& dst, Eigen::Ref<const Eigen::VectorXd> x, double alpha) const {
    m_fem->multiply(x, m_product);
    for (Eigen::Index i = 0; i < dst.size(); ++i) dst.coeffRef(i) += alpha * m_product[i];
  }

 private:
  const CorotationalFem* m_fem;
  mutable Eigen::VectorXd m_product;  // scratch: one solve, one thread
};

// Eigen's Jacobi preconditioner, computed from the compressed matrix itself.
class SystemDiagonal : public Eigen::DiagonalPreconditioner<double> {
 public:
  SystemDiagonal() = default;
  SystemDiagonal& analyzePattern(const BlockSystem&) { return *this; }
  SystemDiagonal& factorize(const BlockSystem& a) {
    DiagonalPreconditioner::factorize(a.sparse());
    return *this;
  }
  SystemDiagonal& compute(const BlockSystem& a) { return factorize(a); }
};

}  // namespace
}  // namespace tcb

namespace Eigen::internal {
template <typename Rhs>
struct generic_product_impl<tcb::BlockSystem, Rhs, SparseShape, DenseShape, GemvProduct>
    : generic_product_impl_base<tcb::BlockSystem, Rhs, generic_product_impl<tcb::BlockSystem, Rhs>> {
  template <typename Dest>
  static void scaleAndAddTo(Dest& dst, const tcb::BlockSystem& lhs, const Rhs& rhs, const double& alpha) {
    lhs.scale_and_add(dst, rhs, alpha);
  }
};
}  // namespace Eigen::internal

namespace tcb {

CorotationalFem::CorotationalFem(const TetMesh& mesh, const std::vector<Vec3>& rest_m, const Material& material)
    : m_material(material), m_mass_kg(lumped_masses_kg(mesh, rest_m, material.density_kg_per_m3)) {
  const double lambda = lame_lambda_pa(material), mu = lame_mu_pa(material);
  const std::vector<char>& degenerate = mesh.is_degenerate;
  m_elements.reserve(mesh.tet_count());
  for (std::size_t i = 0; i < mesh.tet_count(); ++i) {
    if (degenerate[i]) continue;
    Element e;
    e.v = mesh.tets[i];
    for (int k = 0; k < 4; ++k) e.rest_m[k] = rest_m[e.v[k]];
    Eigen::Matrix3d dm;
    dm << e.rest_m[1] - e.rest_m[0], e.rest_m[2] - e.rest_m[0], e.rest_m[3] - e.rest_m[0];
    const double volume = dm.determinant() / 6.0;
    if (!(volume > 0.0)) continue;  // flat in floating point although not exactly: inert
    e.rest_edges_inverse = dm.inverse();
    // Shape-function gradients: rows of Dm^-1 for vertices 1..3; vertex 0 the negative sum.
    std::array<Vec3, 4> g;
    for (int k = 0; k < 3; ++k) g[k + 1] = e.rest_edges_inverse.row(k).transpose();
    g[0] = -(g[1] + g[2] + g[3]);
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        e.stiffness.block<3, 3>(3 * a, 3 * b) =
            volume * (lambda * g[a] * g[b].transpose() + mu * g[b] * g[a].transpose() +
                      mu * g[a].dot(g[b]) * Eigen::Matrix3d::Identity());
    e.rotation = Eigen::Quaterniond::Identity();
    m_elements.push_back(e);
  }
  build_pattern(mesh.vertex_count());
}

void CorotationalFem::build_pattern(std::size_t n) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(m_elements.size() * 144 + 3 * n);
  for (const Element& e : m_elements)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) entries.emplace_back(3 * e.v[a] + r, 3 * e.v[b] + c, 0.0);
  for (std::size_t i = 0; i < 3 * n; ++i) entries.emplace_back(i, i, 0.0);
  m_system.resize(3 * n, 3 * n);
  m_system.setFromTriplets(entries.begin(), entries.end());
  m_system.makeCompressed();
  m_blocks = block_rows_of({m_system.outerIndexPtr(), static_cast<std::size_t>(m_system.rows()) + 1},
                           {m_system.innerIndexPtr(), static_cast<std::size_t>(m_system.nonZeros())});

  const int* outer = m_system.outerIndexPtr();
  const int* inner = m_system.innerIndexPtr();
  const auto slot = [&](int row, int col) {
    const int* found = std::lower_bound(inner + outer[row], inner + outer[row + 1], col);
    return static_cast<int>(found - inner);
  };
  m_block_slots.resize(m_elements.size());
  for (std::size_t i = 0; i < m_elements.size(); ++i)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        for (int r = 0; r < 3; ++r)
          m_block_slots[i][(a * 4 + b) * 3 + r] = slot(3 * m_elements[i].v[a] + r, 3 * m_elements[i].v[b]);
  m_diagonal_slots.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    for (int r = 0; r < 3; ++r) m_diagonal_slots[i][r] = slot(3 * i + r, 3 * i + r);
  m_rhs.resize(3 * n);
  m_velocity.resize(3 * n);
}

Eigen::Matrix3d CorotationalFem::deformation_gradient(const Element& e, std::span<const Vec3> x) const {
  Eigen::Matrix3d ds;
  ds << x[e.v[1]] - x[e.v[0]], x[e.v[2]] - x[e.v[0]], x[e.v[3]] - x[e.v[0]];
  return ds * e.rest_edges_inverse;
}

bool CorotationalFem::rotations_kept_for(std::span<const Vec3> x) const {
  // The same bits, not ==: the kept rotations are certain to be the ones the
  // step would extract only from the very same bits (+0.0 == -0.0, NaN != NaN).
  return m_rotations_kept && x.size() == m_kept_x_m.size() &&
         (x.empty() || std::memcmp(x.data(), m_kept_x_m.data(), x.size() * sizeof(Vec3)) == 0);
}

const std::vector<Eigen::Quaterniond>& CorotationalFem::rotations_at(std::span<const Vec3> x) const {
  if (rotations_kept_for(x)) return m_kept_rotations;
  m_rotations_kept = false;  // stays false if an exception leaves the copy half made
  m_kept_rotations.resize(m_elements.size());
  for (std::size_t ei = 0; ei < m_elements.size(); ++ei) {
    const Element& e = m_elements[ei];
    m_kept_rotations[ei] = e.rotation;
    extract_rotation(deformation_gradient(e, x), m_kept_rotations[ei]);
  }
  m_kept_x_m.assign(x.begin(), x.end());
  m_rotations_kept = true;
  return m_kept_rotations;
}

void CorotationalFem::elastic_forces(std::span<const Vec3> x, std::span<Vec3> f) const {
  std::fill(f.begin(), f.end(), Vec3::Zero());
  const std::vector<Eigen::Quaterniond>& rotations = rotations_at(x);
  for (std::size_t ei = 0; ei < m_elements.size(); ++ei) {
    const Element& e = m_elements[ei];
    const Eigen::Matrix3d r = rotations[ei].toRotationMatrix();
    Eigen::Matrix<double, 12, 1> u;
    for (int k = 0; k < 4; ++k) u.segment<3>(3 * k) = r.transpose() * x[e.v[k]] - e.rest_m[k];
    const Eigen::Matrix<double, 12, 1> local = e.stiffness * u;
    for (int k = 0; k < 4; ++k) f[e.v[k]] -= r * local.segment<3>(3 * k);
  }
}

double CorotationalFem::elastic_energy_j(std::span<const Vec3> x) const {
  double energy = 0.0;
  const std::vector<Eigen::Quaterniond>& rotations = rotations_at(x);
  for (std::size_t ei = 0; ei < m_elements.size(); ++ei) {
    const Element& e = m_elements[ei];
    const Eigen::Matrix3d r = rotations[ei].toRotationMatrix();
    Eigen::Matrix<double, 12, 1> u;
    for (int k = 0; k < 4; ++k) u.segment<3>(3 * k) = r.transpose() * x[e.v[k]] - e.rest_m[k];
    energy += 0.5 * u.dot(e.stiffness * u);
  }
  return energy;
}

bool CorotationalFem::begin_linear_step(std::span<const Vec3> x, std::span<const Vec3> v,
                                        std::span<const Vec3> f_ext, double dt) {
  const std::size_t n = x.size();
  const double stiffness_factor = dt * m_material.damping_stiffness_s + dt * dt;
  const double mass_factor = 1.0 + dt * m_material.damping_mass_per_s;
  double* values = m_system.valuePtr();
  std::fill(values, values + m_system.nonZeros(), 0.0);

  // rhs = M v + dt (f_el(x) + f_ext); f_el accumulated per element below.
  for (std::size_t i = 0; i < n; ++i) m_rhs.segment<3>(3 * i) = dt * f_ext[i];
  // The energy measured after the last step extracted these rotations already.
  const bool kept = rotations_kept_for(x);
  m_rotations_kept = false;  // the warm starts move on below
  m_kept_rotations_taken += kept;
  for (std::size_t ei = 0; ei < m_elements.size(); ++ei) {
    Element& e = m_elements[ei];
    if (kept)
      e.rotation = m_kept_rotations[ei];
    else
      extract_rotation(deformation_gradient(e, x), e.rotation);
    const Eigen::Matrix3d r = e.rotation.toRotationMatrix();
    Eigen::Matrix<double, 12, 1> u;
    for (int k = 0; k < 4; ++k) u.segment<3>(3 * k) = r.transpose() * x[e.v[k]] - e.rest_m[k];
    const Eigen::Matrix<double, 12, 1> local = e.stiffness * u;
    for (int k = 0; k < 4; ++k) m_rhs.segment<3>(3 * e.v[k]) -= dt * (r * local.segment<3>(3 * k));
    const auto& slots = m_block_slots[ei];
    const auto scatter = [&](int a, int b, const Eigen::Matrix3d& block) {
      for (int row = 0; row < 3; ++row) {
        double* dst = values + slots[(a * 4 + b) * 3 + row];
        dst[0] += block(row, 0);
        dst[1] += block(row, 1);
        dst[2] += block(row, 2);
      }
    };
    // K_e is symmetric, so block (b, a) of R K_e R^T is block (a, b) transposed.
    for (int a = 0; a < 4; ++a)
      for (int b = a; b < 4; ++b) {
        const Eigen::Matrix3d block = stiffness_factor * (r * e.stiffness.block<3, 3>(3 * a, 3 * b) * r.transpose());
        scatter(a, b, block);
        if (b != a) scatter(b, a, block.transpose());
      }
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double m = m_mass_kg[i];
    for (int r = 0; r < 3; ++r) {
      // A massless vertex is pinned: the row becomes v = 0.
      values[m_diagonal_slots[i][r]] += m > 0.0 ? mass_factor * m : 1.0;
      if (m == 0.0) m_rhs[3 * i + r] = 0.0;
    }
    if (m > 0.0) m_rhs.segment<3>(3 * i) += m * v[i];
    m_velocity.segment<3>(3 * i) = m > 0.0 ? v[i] : Vec3::Zero();
  }
  return true;
}

void CorotationalFem::multiply(Eigen::Ref<const Eigen::VectorXd> v, Eigen::Ref<Eigen::VectorXd> out) const {
  // A Ref cannot be resized: a wrong size would write past the caller's vector.
  if (v.size() != m_system.cols() || out.size() != m_system.rows())
    throw std::invalid_argument("CorotationalFem::multiply: vectors of " + std::to_string(v.size()) + " and " +
                                std::to_string(out.size()) + " entries for a system of " +
                                std::to_string(m_system.rows()));
  if (v.data() < out.data() + out.size() && out.data() < v.data() + v.size())
    throw std::invalid_argument("CorotationalFem::multiply: v and out overlap");
  // What `out.noalias() = m_system * v` gives, bit for bit, read by blocks.
  multiply_block_rows(m_blocks, m_system.outerIndexPtr(), m_system.innerIndexPtr(), m_system.valuePtr(), v.data(),
                      out.data());
}

Eigen::VectorXd CorotationalFem::diagonal() const { return m_system.diagonal(); }

void CorotationalFem::step(std::span<Vec3> x, std::span<Vec3> v, std::span<const Vec3> f_ext, double dt) {
  begin_linear_step(x, v, f_ext, dt);
  const BlockSystem system(*this);
  Eigen::ConjugateGradient<BlockSystem, Eigen::Lower | Eigen::Upper, SystemDiagonal> cg;
  cg.setTolerance(m_material.cg_tolerance);
  cg.setMaxIterations(m_material.cg_max_iterations);
  cg.compute(system);
  m_velocity = cg.solveWithGuess(m_rhs, m_velocity);
  end_linear_step(x, v, m_velocity, dt, static_cast<int>(cg.iterations()), cg.info() == Eigen::Success);
}

}  // namespace tcb
