// multiply_block_rows() against Eigen's compressed row-major product, bit for
// bit, on the FEM's own pattern (3x3 blocks per tet, diagonal entries for
// every vertex), with a vertex in no tet and values whose sums round
// differently in any other order.
#include <catch2/catch.hpp>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>

#include <cstring>
#include <random>

#include "sim/dynamics/block_rows.hpp"
#include "sim/dynamics/corotational_fem.hpp"
#include "sim/mesh/box_mesh.hpp"
#include "tests/sim/dynamics/fixtures.hpp"

using namespace tcb;
using test::soft_material;

namespace {

using SparseMatrix = CorotationalFem::SparseMatrix;

// A box mesh and one vertex in no tet: massless, so pinned, and its rows
// hold only their diagonal (a row triple that is not whole blocks).
TetMesh box_and_isolated_vertex(int nx, int ny, int nz) {
  const TetMesh box = make_box_mesh(Vec3(0.3, 0.2, 0.25), nx, ny, nz);
  std::vector<Vec3> positions = box.positions_m;
  positions.push_back(Vec3(0.5, 0.5, 0.5));
  return build_tet_mesh(positions, box.tets);
}

// CorotationalFem's own pattern for this mesh, with random values spread
// over many binades (and some exact zeros).
SparseMatrix fem_pattern(const TetMesh& mesh, unsigned seed) {
  SparseMatrix m = CorotationalFem(mesh, mesh.positions_m, soft_material()).system();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-30, 30), zero(0, 19);
  for (Eigen::Index k = 0; k < m.nonZeros(); ++k)
    m.valuePtr()[k] = zero(rng) == 0 ? 0.0 : std::ldexp(mantissa(rng), exponent(rng));
  return m;
}

Eigen::VectorXd random_vector(Eigen::Index size, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-20, 20);
  Eigen::VectorXd v(size);
  for (Eigen::Index i = 0; i < size; ++i) v[i] = std::ldexp(mantissa(rng), exponent(rng));
  return v;
}

bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), static_cast<std::size_t>(a.size()) * sizeof(double)) == 0;
}

Eigen::VectorXd block_product(const BlockRows& blocks, const SparseMatrix& m, const Eigen::VectorXd& x) {
  Eigen::VectorXd out = Eigen::VectorXd::Constant(x.size(), 12345.0);
  multiply_block_rows(blocks, m.outerIndexPtr(), m.innerIndexPtr(), m.valuePtr(), x.data(), out.data());
  return out;
}

BlockRows blocks_of(const SparseMatrix& m) {
  return block_rows_of({m.outerIndexPtr(), static_cast<std::size_t>(m.rows()) + 1},
                       {m.innerIndexPtr(), static_cast<std::size_t>(m.nonZeros())});
}

}  // namespace

TEST_CASE("block rows: the same bits as Eigen's product on an FEM pattern", "[dynamics][block_rows]") {
  const TetMesh mesh = box_and_isolated_vertex(5, 4, 3);
  REQUIRE(mesh.isolated_vertices == 1);
  const std::size_t n = mesh.vertex_count();
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const SparseMatrix m = fem_pattern(mesh, seed);
    const BlockRows blocks = blocks_of(m);
    REQUIRE(blocks.regular.size() == n);
    for (std::size_t i = 0; i + 1 < n; ++i) REQUIRE(blocks.regular[i] == 1);
    CHECK(blocks.regular[n - 1] == 0);
    const Eigen::VectorXd x = random_vector(m.cols(), 1000 + seed);
    Eigen::VectorXd expected(m.rows());
    expected.noalias() = m * x;
    CHECK(same_bits(block_product(blocks, m, x), expected));
  }
}

TEST_CASE("block rows: the order of the sums is Eigen's, not just the value", "[dynamics][block_rows]") {
  // One row triple of two blocks, all ones, x = (1e16, 0, 0, -1e16, 1, 0).
  // Term by term, as Eigen sums, each row gives 1; a block's three terms
  // summed before joining the row (-1e16 + 1 rounds to -1e16) give 0, and so
  // would summing the blocks from the last.
  SparseMatrix m(6, 6);
  std::vector<Eigen::Triplet<double>> entries;
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) entries.emplace_back(r, c, 1.0);
  m.setFromTriplets(entries.begin(), entries.end());
  m.makeCompressed();
  Eigen::VectorXd x(6);
  x << 1e16, 0.0, 0.0, -1e16, 1.0, 0.0;
  Eigen::VectorXd expected(6);
  expected.noalias() = m * x;
  REQUIRE(expected[0] == 1.0);
  CHECK(same_bits(block_product(blocks_of(m), m, x), expected));
}

TEST_CASE("block rows: row triples that are not whole blocks are multiplied row by row", "[dynamics][block_rows]") {
  // Rows 0-2 share columns 0-2 but row 1 lacks column 2; rows 3-5 are whole.
  SparseMatrix m(6, 6);
  std::vector<Eigen::Triplet<double>> entries;
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c)
      if (!(r == 1 && c == 2) && (r / 3 == c / 3 || r >= 3)) entries.emplace_back(r, c, 0.5 + r - 0.25 * c);
  m.setFromTriplets(entries.begin(), entries.end());
  m.makeCompressed();
  const BlockRows blocks = blocks_of(m);
  CHECK(blocks.regular == std::vector<std::uint8_t>{0, 1});
  CHECK(blocks.columns == std::vector<std::int32_t>{0, 3});
  const Eigen::VectorXd x = random_vector(6, 7);
  Eigen::VectorXd expected(6);
  expected.noalias() = m * x;
  CHECK(same_bits(block_product(blocks, m, x), expected));
}

TEST_CASE("block rows: a row count that is not a multiple of 3 is refused", "[dynamics][block_rows]") {
  const std::vector<std::int32_t> outer{0, 1, 2, 3, 4}, inner{0, 1, 2, 3};
  CHECK_THROWS_AS(block_rows_of(outer, inner), std::invalid_argument);
  CHECK_THROWS_AS(block_rows_of({}, {}), std::invalid_argument);
}

TEST_CASE("block rows: CorotationalFem::multiply() is its system's Eigen product, bit for bit",
          "[dynamics][block_rows]") {
  const TetMesh mesh = make_box_mesh(Vec3(0.3, 0.2, 0.25), 4, 3, 3);
  CorotationalFem fem(mesh, mesh.positions_m, soft_material());
  // Deformed and rotating, so every block is a rotated, non-trivial one.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  std::vector<Vec3> x = mesh.positions_m, v(mesh.vertex_count()), f(mesh.vertex_count(), Vec3::Zero());
  for (std::size_t i = 0; i < x.size(); ++i) {
    x[i] = Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()) * x[i] + Vec3(u(rng), u(rng), u(rng));
    v[i] = Vec3(u(rng), u(rng), u(rng));
  }
  REQUIRE(fem.begin_linear_step(x, v, f, 1e-3));
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Eigen::VectorXd p = random_vector(fem.system().cols(), seed);
    Eigen::VectorXd expected(p.size()), got = Eigen::VectorXd::Constant(p.size(), 12345.0);
    expected.noalias() = fem.system() * p;
    fem.multiply(p, got);
    CHECK(same_bits(got, expected));
  }
  // An Eigen::Ref cannot grow: a wrong size or an overlap is refused, not
  // written past.
  Eigen::VectorXd q = random_vector(fem.system().cols(), 9), short_out(3);
  CHECK_THROWS_AS(fem.multiply(q, short_out), std::invalid_argument);
  CHECK_THROWS_AS(fem.multiply(q, q), std::invalid_argument);
}

TEST_CASE("block rows: CorotationalFem::step() is Eigen's conjugate gradients on the compressed system, bit for bit",
          "[dynamics][block_rows]") {
  // The reference is step() as it was before the product was read by blocks:
  // assemble, then Eigen's ConjugateGradient (Jacobi, Lower | Upper) on the
  // compressed matrix, warm-started from v.
  const TetMesh mesh = box_and_isolated_vertex(4, 3, 3);
  REQUIRE(mesh.isolated_vertices == 1);
  const Material material = soft_material();
  CorotationalFem fem(mesh, mesh.positions_m, material), reference(mesh, mesh.positions_m, material);
  std::vector<Vec3> x = mesh.positions_m, v(mesh.vertex_count(), Vec3::Zero()), f(mesh.vertex_count());
  // Gravity, and a pull along x on the upper part: it bends and swings.
  for (std::size_t i = 0; i < x.size(); ++i)
    f[i] = fem.vertex_masses_kg()[i] * Vec3(x[i].y() > 0.1 ? 20.0 : 0.0, -9.81, 0.0);
  std::vector<Vec3> rx = x, rv = v;
  int total_iterations = 0;
  for (int s = 0; s < 20; ++s) {
    fem.step(x, v, f, 1e-3);
    REQUIRE(reference.begin_linear_step(rx, rv, f, 1e-3));
    Eigen::VectorXd guess(3 * static_cast<Eigen::Index>(rv.size()));
    for (std::size_t i = 0; i < rv.size(); ++i)
      guess.segment<3>(3 * static_cast<Eigen::Index>(i)) = reference.vertex_masses_kg()[i] > 0.0 ? rv[i] : Vec3(Vec3::Zero());
    Eigen::ConjugateGradient<CorotationalFem::SparseMatrix, Eigen::Lower | Eigen::Upper,
                             Eigen::DiagonalPreconditioner<double>>
        cg;
    cg.setTolerance(material.cg_tolerance);
    cg.setMaxIterations(material.cg_max_iterations);
    cg.compute(reference.system());
    const Eigen::VectorXd solved = cg.solveWithGuess(reference.rhs(), guess);
    reference.end_linear_step(rx, rv, solved, 1e-3, static_cast<int>(cg.iterations()), cg.info() == Eigen::Success);
    REQUIRE(fem.last_solver_iterations() == reference.last_solver_iterations());
    total_iterations += fem.last_solver_iterations();
    REQUIRE(test::same_bits(x, rx));
    REQUIRE(test::same_bits(v, rv));
  }
  CHECK(total_iterations > 20);  // the solves did iterate
}
