// One implicit corotational FEM step (rotation extraction, assembly, CG
// solve) of a deforming object, for the FEM cost per step the issues report.
//   build/release/experiments/micro/micro_fem_step --benchmark_repetitions=5
// Objects: a structured box of 10,368 tets and the real dog.mesh (34,072).
#include <benchmark/benchmark.h>

#include <filesystem>

#include "sim/dynamics/corotational_fem.hpp"
#include "sim/mesh/box_mesh.hpp"
#include "sim/mesh/medit_io.hpp"

namespace {

using namespace tcb;

void run_fem(benchmark::State& state, const TetMesh& mesh) {
  Material material;
  material.youngs_modulus_pa = 1e5;
  material.damping_mass_per_s = 0.5;
  CorotationalFem fem(mesh, mesh.positions_m, material);
  std::vector<Vec3> x = mesh.positions_m, v(mesh.vertex_count(), Vec3::Zero());
  // A steady pull along x on the upper half keeps the object deforming and
  // rotating, so the warm starts do not make later steps trivially cheap.
  double top = -1e30;
  for (const Vec3& p : x) top = std::max(top, p.y());
  std::vector<Vec3> force(mesh.vertex_count(), Vec3::Zero());
  for (std::size_t i = 0; i < x.size(); ++i)
    if (x[i].y() > 0.5 * top) force[i] = Vec3(fem.vertex_masses_kg()[i] * 20.0, 0, 0);
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

void BM_FemStepBox10k(benchmark::State& state) {
  static const TetMesh mesh = make_box_mesh(Vec3(0.3, 0.3, 0.3), 12, 12, 12);  // 10,368 tets
  run_fem(state, mesh);
}
BENCHMARK(BM_FemStepBox10k)->Unit(benchmark::kMillisecond);

void BM_FemStepDog34k(benchmark::State& state) {
  const std::filesystem::path path = std::filesystem::path(TCBENCH_SHARED_MESHES) / "dog.mesh";
  if (!std::filesystem::exists(path)) {
    state.SkipWithError("dog.mesh not found next to the project (../shared/data/meshes)");
    return;
  }
  static const TetMesh dog = [&] {
    TetMesh m = read_medit(path);
    for (Vec3& p : m.positions_m) p *= 0.01;  // the file is in centimetres-ish units: ~1.3 m long
    return m;
  }();
  run_fem(state, dog);
}
BENCHMARK(BM_FemStepDog34k)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
