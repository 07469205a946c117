// One implicit corotational FEM step (rotation extraction, assembly, CG
// solve) of a deforming object, for the FEM cost per step the issues report.
//   build/release/experiments/micro/micro_fem_step --benchmark_repetitions=5
// Objects: a structured box of 10,368 tets and the real dog.mesh (34,072).
// BM_SystemProductPaired/<object> times the CG's matrix-vector product on the
// same assembled system two ways, alternated within one loop: Eigen's
// compressed-row product (what both implicit solves used before) and
// CorotationalFem::multiply() (block_rows.hpp); both answers are compared
// bit for bit after every pair.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <random>

#include "sim/dynamics/corotational_fem.hpp"
#include "sim/mesh/box_mesh.hpp"
#include "sim/mesh/medit_io.hpp"

namespace {

using namespace tcb;

Material fem_material() {
  Material material;
  material.youngs_modulus_pa = 1e5;
  material.damping_mass_per_s = 0.5;
  return material;
}

// A steady pull along x on the upper half keeps the object deforming and
// rotating, so the warm starts do not make later steps trivially cheap.
std::vector<Vec3> pull_on_upper_half(const TetMesh& mesh, const CorotationalFem& fem) {
  double top = -1e30;
  for (const Vec3& p : mesh.positions_m) top = std::max(top, p.y());
  std::vector<Vec3> force(mesh.vertex_count(), Vec3::Zero());
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i)
    if (mesh.positions_m[i].y() > 0.5 * top) force[i] = Vec3(fem.vertex_masses_kg()[i] * 20.0, 0, 0);
  return force;
}

void run_fem(benchmark::State& state, const TetMesh& mesh) {
  CorotationalFem fem(mesh, mesh.positions_m, fem_material());
  std::vector<Vec3> x = mesh.positions_m, v(mesh.vertex_count(), Vec3::Zero());
  const std::vector<Vec3> force = pull_on_upper_half(mesh, fem);
  long iterations = 0;
  for (auto _ : state) {
    fem.step(x, v, force, 1e-3);
    iterations += fem.last_solver_iterations();
    benchmark::ClobberMemory();
  }
  state.counters["tets"] = static_cast<double>(mesh.tet_count());
  state.counters["cg_iterations"] = benchmark::Counter(static_cast<double>(iterations), benchmark::Counter::kAvgIterations);
  state.counters["ns_per_tet"] = benchmark::Counter(static_cast<double>(mesh.tet_count()),
                                                    benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

const TetMesh& box10k() {
  static const TetMesh mesh = make_box_mesh(Vec3(0.3, 0.3, 0.3), 12, 12, 12);  // 10,368 tets
  return mesh;
}

// dog.mesh, or nullptr (the benchmark then skips with an error).
const TetMesh* dog34k(benchmark::State& state) {
  const std::filesystem::path path = std::filesystem::path(TCBENCH_SHARED_MESHES) / "dog.mesh";
  if (!std::filesystem::exists(path)) {
    state.SkipWithError("dog.mesh not found next to the project (../shared/data/meshes)");
    return nullptr;
  }
  static const TetMesh dog = [&] {
    TetMesh m = read_medit(path);
    for (Vec3& p : m.positions_m) p *= 0.01;  // the file is in centimetres-ish units: ~1.3 m long
    return m;
  }();
  return &dog;
}

void BM_FemStepBox10k(benchmark::State& state) { run_fem(state, box10k()); }
BENCHMARK(BM_FemStepBox10k)->Unit(benchmark::kMillisecond);

void BM_FemStepDog34k(benchmark::State& state) {
  if (const TetMesh* dog = dog34k(state)) run_fem(state, *dog);
}
BENCHMARK(BM_FemStepDog34k)->Unit(benchmark::kMillisecond);

// Arg 0: the box, 1: the dog. The system is assembled after ten pulled steps
// (deformed and rotated blocks); the vector is a fixed pseudo-random one.
void BM_SystemProductPaired(benchmark::State& state) {
  const TetMesh* mesh = state.range(0) == 0 ? &box10k() : dog34k(state);
  if (mesh == nullptr) return;
  CorotationalFem fem(*mesh, mesh->positions_m, fem_material());
  std::vector<Vec3> x = mesh->positions_m, v(mesh->vertex_count(), Vec3::Zero());
  const std::vector<Vec3> force = pull_on_upper_half(*mesh, fem);
  for (int s = 0; s < 10; ++s) fem.step(x, v, force, 1e-3);
  fem.begin_linear_step(x, v, force, 1e-3);
  const auto n = fem.system().rows();
  Eigen::VectorXd p(n), by_rows(n), by_blocks(n);
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (Eigen::Index i = 0; i < n; ++i) p[i] = u(rng);
  using Clock = std::chrono::steady_clock;
  double rows_s = 0.0, blocks_s = 0.0;
  std::int64_t pairs = 0;
  bool same = true;
  for (auto _ : state) {
    // Alternate which goes first, so neither always meets the other's caches.
    for (int k = 0; k < 2; ++k) {
      const auto t0 = Clock::now();
      if ((k + pairs) % 2 == 0)
        by_rows.noalias() = fem.system() * p;
      else
        fem.multiply(p, by_blocks);
      const double elapsed = std::chrono::duration<double>(Clock::now() - t0).count();
      ((k + pairs) % 2 == 0 ? rows_s : blocks_s) += elapsed;
    }
    benchmark::DoNotOptimize(by_rows.data());
    benchmark::DoNotOptimize(by_blocks.data());
    same = same && std::memcmp(by_rows.data(), by_blocks.data(), static_cast<std::size_t>(n) * sizeof(double)) == 0;
    ++pairs;
  }
  if (!same) {
    state.SkipWithError("the block product differs from Eigen's");
    return;
  }
  const double count = static_cast<double>(std::max<std::int64_t>(pairs, 1));
  state.counters["us_eigen_rows"] = 1e6 * rows_s / count;
  state.counters["us_blocks"] = 1e6 * blocks_s / count;
  state.counters["speedup"] = blocks_s > 0.0 ? rows_s / blocks_s : 0.0;
  state.counters["nonzeros"] = static_cast<double>(fem.system().nonZeros());
  state.counters["ns_per_nonzero_blocks"] = 1e9 * blocks_s / count / static_cast<double>(fem.system().nonZeros());
}
BENCHMARK(BM_SystemProductPaired)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
