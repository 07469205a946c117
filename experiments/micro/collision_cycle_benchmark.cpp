// One whole collision cycle (hash tets, query points, hash surface, border
// depth, propagation, forces), for the figures the collision-pipeline issue
// reports:
//   build/release/experiments/micro/micro_collision_cycle --benchmark_repetitions=3
// BM_DogPair/<hash>/<cell x 100>/<threads>: dog.mesh (34,072 tets, scaled to 1.34 m
// long) against a copy translated by half its height along y, which puts 10 %
// of the vertices inside the other dog (1,541 of 15,460).
// bucket_share: distinct buckets / distinct cells the tets occupy (1 = no two
// occupied cells share a bucket; lower = more hash collisions), in the hash
// the `hash` argument names: what keep > 0 (keep_table) reads; keep 0's
// table is a dense grid, one cell a bucket (TetHashDetector::enable_widening).
// cells_per_tet: cells a tet's box covers, so hash entries a tet a cycle (fewer
// are entered where a budgetless cycle leaves out tets, and cells of tets,
// no query point reaches).
// BM_Plates20/<hash>/<threads>: the plates20 scene (15,360 tets, as built: step 0).
// BM_Plates20Settled/<threads>: the same after 300 steps of `full` (the
// stack sunk into itself, as a running scene meets it).
// BM_DogPairMoving/<keep>/<threads>, BM_Plates20Moving/<keep>: the same
// scenes moving between cycles as a step would move them (dog_b, and every
// other plate, translated along x by 1 mm a cycle, back and forth every 32
// cycles: 1 m/s at dt 1 ms, a few % of a cell), untimed; keep 0 is the
// paper's schedule (every cycle hashes afresh), keep > 0 our keep_table (the
// last table refreshed; hashed afresh when the overflow grows past keep/1000
// of the tets; 125 is the default, kKeepTableRehashShare).
// fresh_hash_share: the cycles that hashed afresh.
// hash: 0 = mixed (default), 1 = the paper's xor of primes. threads: the
// cycle's collision.threads (its tet and surface hashing, point queries,
// border depths and forces in parallel; the same contacts on every count,
// which the counter `colliding` shows; above one thread, handover_before and
// handover_after give the vCPUs' handover ratio around the timed loop, as in
// BM_ThreadsPaired).
// ms_<stage>: the cycle's wall time per stage, per cycle.
// BM_ThreadsPaired and BM_OrderPaired measure two cycles side by side (2
// threads against 1; the detector's tets, or the dog pair itself, ordered
// along a Morton curve against the file's order), BM_HashFloorPaired the
// cycle's tet hashing beside a bare dense-grid build, BM_PointGridPaired its
// hashing and queries beside a bare grid of the points, BM_SurfaceWholePaired
// the surface hashed one triangle a task against as a whole, BM_TwinCycles
// two independent one-thread cycles at once against one after the other
// (what the machine's second core gives this work): see their comments.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "baselines/registry.hpp"
#include "experiments/run/thread_clock.hpp"
#include "experiments/scene/scene_file.hpp"
#include "method/detection/morton_order.hpp"
#include "method/geometry/perturbed_predicates.hpp"
#include "method/handler/collision_cycle.hpp"
#include "sim/mesh/curve_numbering.hpp"
#include "sim/mesh/medit_io.hpp"
#include "sim/parallel/core_handover.hpp"
#include "sim/parallel/worker_pool.hpp"

namespace {

using namespace tcb;

struct Fixture {
  SceneDesc scene;
  World world;
};

// Orders of a mesh's numbering, for BM_OrderPaired: the file's, or its tets
// (by centroid), its vertices, or both sorted along a Morton curve.
enum class Numbering { File = 0, MortonTets = 1, MortonVertices = 2, MortonBoth = 3 };

// The same mesh renumbered: vertices and/or tets sorted by Morton key (a
// tet by its centroid's), each tet's vertices renamed, the whole rebuilt.
TetMesh renumbered(const TetMesh& mesh, Numbering numbering) {
  // Vertices: what a scene's mesh_order = "curve" loads.
  TetMesh out = numbering == Numbering::MortonVertices || numbering == Numbering::MortonBoth
                    ? vertices_along_curve(mesh)
                    : mesh;
  if (numbering != Numbering::MortonTets && numbering != Numbering::MortonBoth) return out;
  std::vector<Tet> sorted;
  sorted.reserve(out.tet_count());
  for (const std::uint32_t t : morton_tet_order(out.positions_m, out.tets))
    sorted.push_back(out.tets[t]);  // the detector's slot order
  return build_tet_mesh(std::move(out.positions_m), std::move(sorted));
}

Fixture dog_pair(Numbering numbering = Numbering::File) {
  TetMesh dog = read_medit(std::filesystem::path(TCBENCH_SHARED_MESHES) / "dog.mesh");
  if (numbering != Numbering::File) dog = renumbered(dog, numbering);
  for (Vec3& p : dog.positions_m) p *= 0.01;
  const auto [lo, hi] = bounding_box(dog.positions_m);
  const auto mesh = std::make_shared<const TetMesh>(std::move(dog));
  Fixture f;
  f.scene.world.dt_s = 1e-3;
  for (int copy = 0; copy < 2; ++copy) {
    Body b;
    b.name = copy ? "dog_b" : "dog_a";
    b.group = b.name;
    b.mesh = mesh;
    b.x_m = mesh->positions_m;
    if (copy)
      for (Vec3& p : b.x_m) p.y() += 0.5 * (hi.y() - lo.y());
    b.v_m_per_s.assign(b.x_m.size(), Vec3::Zero());
    b.contact_force_n.assign(b.x_m.size(), Vec3::Zero());
    b.mass_kg = lumped_masses_kg(*mesh, b.x_m, 1000.0);
    f.world.bodies.push_back(std::move(b));
  }
  return f;
}

Fixture plates20() {
  Fixture f;
  f.scene = load_scene_file(resolve_scene("plates20", default_scene_dirs()));
  f.world = build_world(f.scene.world);
  return f;
}

// plates20 after 300 steps of the scene under `full` (untimed): the
// plates have sunk into one another under the stack's weight (not yet at
// rest, which the scene reaches in its second second), and touching faces
// are no longer the same doubles. As built (step 0) every interface point
// lies exactly on its neighbour's face, where orient3d's exact stages answer
// often; a running scene meets that in its first step only, so BM_Plates20
// alone would misstate where a running stack's cycle goes.
// Stepped once per process (a few seconds); callers that change the world
// take a clone_world() of it.
const Fixture& plates20_settled() {
  static const Fixture settled = [] {
    Fixture f = plates20();
    auto handler = make_handler("full");
    handler->init(f.world, resolve_collision_settings(f.world, f.scene.collision, f.scene.world.dt_s));
    for (int s = 0; s < 300; ++s) {
      Budget unlimited = Budget::unlimited();
      handler->step(f.world, unlimited);
      f.world.step(f.scene.world.dt_s);
    }
    return f;
  }();
  return settled;
}

// A copy of plates20_settled() a benchmark may change.
Fixture settled_copy() { return {plates20_settled().scene, clone_world(plates20_settled().world)}; }

// The paired benchmarks' scene argument: 0 the dog pair, 1 plates20 as
// built, 2 plates20 after 300 steps (a copy).
Fixture paired_scene(std::int64_t scene) {
  return scene == 0 ? dog_pair() : (scene == 2 ? settled_copy() : plates20());
}

// The bodies the moving benchmarks move: every other one (dog_b; every
// other plate of the stack).
std::vector<char> every_other_body(const World& world) {
  std::vector<char> moving(world.bodies.size(), 0);
  for (std::size_t b = 1; b < moving.size(); b += 2) moving[b] = 1;
  return moving;
}

// Whether dog.mesh is there; if not, the benchmark is skipped with an error.
bool have_dog_mesh(benchmark::State& state) {
  if (std::filesystem::exists(std::filesystem::path(TCBENCH_SHARED_MESHES) / "dog.mesh")) return true;
  state.SkipWithError("dog.mesh not found (../shared/data/meshes)");
  return false;
}

// Every body's tets, degenerate ones included.
std::size_t total_tets(const World& world) {
  std::size_t tets = 0;
  for (const Body& b : world.bodies) tets += b.mesh->tet_count();
  return tets;
}

// The box of a tet's four corners at positions x. Always inline: GCC had
// left it a call, which cost the bare references of BM_HashFloorPaired
// about a quarter of their time.
[[gnu::always_inline]] inline void tet_box_of(const std::vector<Vec3>& x, const Tet& t, Vec3& lo, Vec3& hi) {
  lo = x[t[0]];
  hi = lo;
  for (int k = 1; k < 4; ++k) {
    lo = lo.cwiseMin(x[t[k]]);
    hi = hi.cwiseMax(x[t[k]]);
  }
}

// Of the cells the tets' boxes cover: the share in distinct buckets
// (distinct buckets / distinct cells), and the cells a tet (the hash's
// entries a tet: each costs a hash, a remainder and a push every cycle).
struct CellFigures {
  double bucket_share = 0.0;
  double cells_per_tet = 0.0;
};
CellFigures cell_figures(const World& world, const DetectionSettings& d) {
  std::set<std::array<std::int64_t, 3>> cells;
  std::size_t entries = 0, tets = 0;
  // Cells cut as the detector cuts them (SpatialHash::cell_of), degenerate
  // tets left out as it leaves them out; every body here has a partner.
  const SpatialHash grid(d.cell_size_m, 1, d.hash);
  for (const Body& b : world.bodies)
    for (std::size_t ti = 0; ti < b.mesh->tet_count(); ++ti) {
      if (b.mesh->is_degenerate[ti]) continue;
      Vec3 lo, hi;
      tet_box_of(b.x_m, b.mesh->tets[ti], lo, hi);
      ++tets;
      const auto cell = [&](double x) { return grid.cell_of(x); };
      for (auto i = cell(lo.x()); i <= cell(hi.x()); ++i)
        for (auto j = cell(lo.y()); j <= cell(hi.y()); ++j)
          for (auto k = cell(lo.z()); k <= cell(hi.z()); ++k) {
            cells.insert({i, j, k});
            ++entries;
          }
    }
  const std::size_t all_tets = total_tets(world);  // the table is sized by every tet, as the detector sizes it
  const std::uint64_t n = d.table_size ? d.table_size : next_prime(2 * all_tets + 1);
  std::set<std::uint64_t> buckets;
  for (const auto& c : cells) buckets.insert(hash_cell(d.hash, c[0], c[1], c[2]) % n);
  return {static_cast<double>(buckets.size()) / static_cast<double>(cells.size()),
          static_cast<double>(entries) / static_cast<double>(std::max<std::size_t>(tets, 1))};
}

// One whole cycle without a budget at the world's positions, its stage
// costs counted afresh (the benchmarks' unit of work).
void full_cycle(CollisionCycle& cycle, World& world) {
  cycle.begin(world);
  cycle.start_step_costs();
  Budget unlimited = Budget::unlimited();
  cycle.advance(world, unlimited);
}

// Adds a cycle's stage times to `sum`.
void add_stage_ms(StageCosts& sum, const CollisionCycle& cycle) {
  for (std::size_t st = 0; st < kCostStages; ++st) sum.ms[st] += cycle.step_costs().ms[st];
}

// Moves the bodies marked in `moving` along x by 1 mm, forwards in the
// first 16 of every 32 calls and back in the others (a step of 1 m/s at
// dt 1 ms), and advances the step index.
void move_between_cycles(World& world, const std::vector<char>& moving, std::int64_t call) {
  const double dx_m = (call / 16) % 2 == 0 ? 1e-3 : -1e-3;
  for (std::size_t b = 0; b < world.bodies.size(); ++b)
    if (moving[b])
      for (Vec3& x : world.bodies[b].x_m) x.x() += dx_m;
  ++world.step_index;
}

// Cycles on f's world; with `moving` (one flag a body) the world moves
// between cycles (untimed) and `schedule` decides whether tables are kept.
void run_cycles(benchmark::State& state, Fixture& f, CollisionSettings settings, CycleSchedule schedule = {},
                const std::vector<char>& moving = {}) {
  const CellFigures cells = cell_figures(f.world, settings.detection);
  state.counters["bucket_share"] = cells.bucket_share;
  state.counters["cells_per_tet"] = cells.cells_per_tet;
  // Above one thread the times depend on the vCPUs' placement: the handover
  // ratio before and after the loop says which regime the run was in (see
  // BM_ThreadsPaired; 0: not measured).
  const bool threaded = settings.threads > 1;
  CollisionCycle cycle(f.world, std::move(settings), DetectionMode::SpatialHash, schedule);
  std::size_t colliding = 0;
  const std::size_t tets = total_tets(f.world);
  StageCosts stages;  // summed over the iterations
  std::int64_t calls = 0;
  if (threaded) state.counters["handover_before"] = probe_handover_ratio().value_or(0.0);
  for (auto _ : state) {
    if (!moving.empty()) {
      state.PauseTiming();
      move_between_cycles(f.world, moving, calls++);
      state.ResumeTiming();
    }
    full_cycle(cycle, f.world);
    colliding = cycle.contacts().size();
    benchmark::DoNotOptimize(cycle.contacts().data());
    add_stage_ms(stages, cycle);
  }
  if (threaded) state.counters["handover_after"] = probe_handover_ratio().value_or(0.0);
  // ms_<stage>: the cycle's wall time per stage (its steady clock, read at
  // stage changes), per cycle: where a thread count's speed-up is limited.
  for (std::size_t s = 0; s < kCostStages; ++s) {
    if (static_cast<CostStage>(s) == CostStage::Apply) continue;  // the handler's, not the cycle's
    state.counters["ms_" + std::string(cost_stage_name(static_cast<CostStage>(s)))] =
        stages.ms[s] / static_cast<double>(std::max<benchmark::IterationCount>(state.iterations(), 1));
  }
  state.counters["fresh_hash_share"] =
      static_cast<double>(cycle.fresh_tet_hashes()) /
      static_cast<double>(std::max<benchmark::IterationCount>(state.iterations(), 1));
  state.counters["tets"] = static_cast<double>(tets);
  state.counters["colliding"] = static_cast<double>(colliding);
  state.counters["ns_per_tet"] =
      benchmark::Counter(static_cast<double>(tets), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["ns_per_colliding"] = benchmark::Counter(
      static_cast<double>(colliding), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_DogPair(benchmark::State& state) {
  if (!have_dog_mesh(state)) return;
  static Fixture f = dog_pair();
  CollisionSettings settings = resolve_collision_settings(f.world, f.scene.collision, f.scene.world.dt_s);
  settings.detection.hash = state.range(0) == 0 ? HashFunction::Mixed : HashFunction::Paper;
  settings.detection.cell_size_m = average_edge_length(f.world) * static_cast<double>(state.range(1)) / 100.0;
  settings.threads = static_cast<int>(state.range(2));
  run_cycles(state, f, settings);
}
BENCHMARK(BM_DogPair)->ArgsProduct({{0, 1}, {50, 100, 200}, {1}})->Args({0, 100, 2})->Unit(benchmark::kMillisecond);

// The moving benchmarks' first argument: 0 the paper's schedule, else
// keep_table with a fresh hash past keep_per_mille/1000 of the tets.
CycleSchedule keep_schedule(std::int64_t keep_per_mille) {
  return {.keep_table = keep_per_mille > 0, .keep_table_rehash_share = static_cast<double>(keep_per_mille) / 1000.0};
}

void BM_DogPairMoving(benchmark::State& state) {
  if (!have_dog_mesh(state)) return;
  Fixture f = dog_pair();  // its own: the motion must not reach the other benchmarks
  CollisionSettings settings = resolve_collision_settings(f.world, f.scene.collision, f.scene.world.dt_s);
  settings.threads = static_cast<int>(state.range(1));
  run_cycles(state, f, settings, keep_schedule(state.range(0)), {0, 1});
}
BENCHMARK(BM_DogPairMoving)
    ->ArgsProduct({{0, 125}, {1, 2}})
    ->Args({31, 1})
    ->Args({62, 1})
    ->Args({250, 1})
    ->Args({500, 1})
    ->Unit(benchmark::kMillisecond);

void BM_Plates20(benchmark::State& state) {
  static Fixture f = plates20();
  CollisionSettings settings = resolve_collision_settings(f.world, f.scene.collision, f.scene.world.dt_s);
  settings.detection.hash = state.range(0) == 0 ? HashFunction::Mixed : HashFunction::Paper;
  settings.threads = static_cast<int>(state.range(1));
  run_cycles(state, f, settings);
}
BENCHMARK(BM_Plates20)->Args({0, 1})->Args({1, 1})->Args({0, 2})->Unit(benchmark::kMillisecond);

void BM_Plates20Settled(benchmark::State& state) {
  Fixture f = settled_copy();
  CollisionSettings settings = resolve_collision_settings(f.world, f.scene.collision, f.scene.world.dt_s);
  settings.threads = static_cast<int>(state.range(0));
  run_cycles(state, f, settings);
}
BENCHMARK(BM_Plates20Settled)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

void BM_Plates20Moving(benchmark::State& state) {
  Fixture f = plates20();
  CollisionSettings settings = resolve_collision_settings(f.world, f.scene.collision, f.scene.world.dt_s);
  run_cycles(state, f, settings, keep_schedule(state.range(0)), every_other_body(f.world));
}
BENCHMARK(BM_Plates20Moving)->Arg(0)->Arg(125)->Unit(benchmark::kMillisecond);

// Two cycles timed side by side, for the paired benchmarks: each
// iteration runs both, which goes first alternating with the call, so the
// host's load weighs on both alike. Seconds and stage times summed a cycle.
struct SideBySide {
  double seconds[2] = {0.0, 0.0};
  StageCosts stages[2];
  std::int64_t calls = 0;  ///< iterations run by loop()
  /// When set (two CPUs), cycle 0 runs pinned to first_on[(call / 2) % 2],
  /// so its time is taken on both CPUs alike, each CPU's turns first and
  /// second as often, and is kept apart per CPU (first_seconds_on,
  /// first_calls_on): the one-thread reference is then not whichever CPU
  /// the scheduler chose, which matters where one vCPU runs slower than the
  /// other. Where a pin is refused, pinning stops (pin_refused) and the
  /// rest runs as the scheduler places it.
  std::vector<int> first_on;
  double first_seconds_on[2] = {0.0, 0.0};
  std::int64_t first_calls_on[2] = {0, 0};
  bool pin_refused = false;

  void run(CollisionCycle* cycles[2], World* worlds[2], std::int64_t call) {
    for (int k = 0; k < 2; ++k) {
      const int which = static_cast<int>((call + k) % 2);
      const std::size_t cpu = static_cast<std::size_t>((call / 2) % 2);
      std::optional<ScopedPin> pin;
      if (which == 0 && first_on.size() == 2 && !pin_refused) {
        pin.emplace(first_on[cpu]);
        if (!pin->error().empty()) {
          pin_refused = true;
          pin.reset();
        } else if (k == 1) {
          // After a pooled cycle its worker polls for up to poll_us() before
          // it blocks: let it, untimed, so the pinned cycle does not share a
          // core with it only on the turns that follow.
          std::this_thread::sleep_for(std::chrono::microseconds(2 * WorkerPool::poll_us()));
        }
      }
      const auto start = std::chrono::steady_clock::now();
      full_cycle(*cycles[which], *worlds[which]);
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      seconds[which] += s;
      if (pin) {
        first_seconds_on[cpu] += s;
        ++first_calls_on[cpu];
      }
      add_stage_ms(stages[which], *cycles[which]);
    }
  }
  /// Cycle 0's pinned time a call on each CPU, ms, where every call of it
  /// was pinned and both CPUs had turns; else nothing.
  std::optional<std::array<double, 2>> first_ms_on() const {
    if (first_on.size() != 2 || pin_refused || first_calls_on[0] == 0 || first_calls_on[1] == 0) return std::nullopt;
    return std::array<double, 2>{1e3 * first_seconds_on[0] / static_cast<double>(first_calls_on[0]),
                                 1e3 * first_seconds_on[1] / static_cast<double>(first_calls_on[1])};
  }
  /// The benchmark's loop: each iteration, if `moves`, first calls
  /// move(calls) untimed, then runs both cycles; stops with `mismatch` as
  /// the error (returning false) once their contact counts differ.
  template <typename Move>
  bool loop(benchmark::State& state, CollisionCycle* cycles[2], World* worlds[2], bool moves, Move&& move,
            const char* mismatch) {
    for (auto _ : state) {
      if (moves) {
        state.PauseTiming();
        move(calls);
        state.ResumeTiming();
      }
      run(cycles, worlds, calls);
      ++calls;
      if (cycles[0]->contacts().size() != cycles[1]->contacts().size()) {
        state.SkipWithError(mismatch);
        return false;
      }
    }
    return true;
  }
  /// Cycle k's mean time per call, ms.
  double ms_per_call(int k) const { return 1e3 * seconds[k] / static_cast<double>(std::max<std::int64_t>(calls, 1)); }
  /// Counters <prefix><stage>: cycle num's stage time over cycle den's, for
  /// each stage den spent time in.
  void stage_ratios(benchmark::State& state, const std::string& prefix, int num, int den) const {
    for (std::size_t st = 0; st < kCostStages; ++st)
      if (stages[den].ms[st] > 0.0 && static_cast<CostStage>(st) != CostStage::Apply)
        state.counters[prefix + std::string(cost_stage_name(static_cast<CostStage>(st)))] =
            stages[num].ms[st] / stages[den].ms[st];
  }
};

// The 2-thread speed-up measured side by side: BM_ThreadsPaired/<scene>/<keep>
// (scene 0 the dog pair, 1 plates20, 2 plates20 after 300 steps as in
// BM_Plates20Settled; keep as in the moving benchmarks, with the same motion
// when > 0) runs two cycles on one world,
// one on 1 thread and one on 2, both in every iteration (which goes first
// alternates), so the host's load, which moves this VM's single figures
// 1.3-2x between minutes, weighs on both alike. speedup_2t: the one-thread
// cycles' time over the two-thread cycles' (sums over the iterations), and
// speedup_<stage> the same for each stage (the cycle's stage clock); ms_1t,
// ms_2t per cycle. handover_before and handover_after: the vCPUs' handover
// ratio (probe_handover_ratio) before and after the timed loop; the
// speed-up depends on it (core_handover.hpp). The one-thread cycle runs
// pinned to the first two allowed CPUs by turns (SideBySide::first_on; the
// two-thread one, which uses both CPUs anyway, unpinned): ms_1t_cpu0 and
// ms_1t_cpu1 are its times a cycle on each, cpu_ratio the second over the
// first, speedup_2t the mean of the two over ms_2t, and
// speedup_2t_vs_faster the faster CPU's over ms_2t. Where one vCPU runs
// slower than the other (a neighbour on the host; cpu_ratio far from 1), an
// unpinned one-thread side would take whichever CPU it was given, and the
// ratio would say more about the host than about the split
// (docs/performance.md, "Two threads"). pinned: 1 where every one-thread
// cycle ran pinned, 0 where a pin was refused (then speedup_2t is the sums'
// ratio, as scheduled, and the per-CPU counters are left out).
// micro_machine_scaling gives the machine's own ratio for kinds of work
// beside it. Stops with an error if the two cycles' contacts differ.
void BM_ThreadsPaired(benchmark::State& state) {
  const bool dogs = state.range(0) == 0;
  if (dogs && !have_dog_mesh(state)) return;
  Fixture f = paired_scene(state.range(0));
  const std::vector<char> moving = every_other_body(f.world);
  const bool move = state.range(1) > 0;
  CollisionSettings one = resolve_collision_settings(f.world, f.scene.collision, f.scene.world.dt_s);
  CollisionSettings two = one;
  one.threads = 1;
  two.threads = 2;
  CollisionCycle cycles[2] = {CollisionCycle(f.world, one, DetectionMode::SpatialHash, keep_schedule(state.range(1))),
                              CollisionCycle(f.world, two, DetectionMode::SpatialHash, keep_schedule(state.range(1)))};
  CollisionCycle* both[2] = {&cycles[0], &cycles[1]};
  World* worlds[2] = {&f.world, &f.world};
  SideBySide pair;  // 0: one thread, 1: two
  const std::vector<int> cpus = allowed_cpus();
  if (cpus.size() >= 2) pair.first_on = {cpus[0], cpus[1]};
  // The vCPUs' placement before and after (sim/parallel/core_handover.hpp):
  // near 1, the cores hand each other lines as cheaply as they keep their
  // own; 2 and more, they do not, and the split cycle loses to it. 0: not
  // measured (fewer than two CPUs, or both threads ran on one).
  const auto handover_ratio = [] { return probe_handover_ratio().value_or(0.0); };
  state.counters["handover_before"] = handover_ratio();
  if (!pair.loop(state, both, worlds, move, [&](std::int64_t call) { move_between_cycles(f.world, moving, call); },
                 "the 1- and 2-thread cycles found different contacts"))
    return;
  state.counters["handover_after"] = handover_ratio();
  const auto on = pair.first_ms_on();
  state.counters["pinned"] = on ? 1.0 : 0.0;
  // Pinned: over the mean of the two CPUs' times, as if one thread ran on
  // each half the time, whatever the turns' counts; else the sums' ratio.
  state.counters["speedup_2t"] = on ? 0.5 * ((*on)[0] + (*on)[1]) / pair.ms_per_call(1)
                                    : (pair.seconds[1] > 0.0 ? pair.seconds[0] / pair.seconds[1] : 0.0);
  state.counters["ms_1t"] = pair.ms_per_call(0);
  state.counters["ms_2t"] = pair.ms_per_call(1);
  if (on) {
    state.counters["ms_1t_cpu0"] = (*on)[0];
    state.counters["ms_1t_cpu1"] = (*on)[1];
    state.counters["cpu_ratio"] = (*on)[1] / (*on)[0];
    state.counters["speedup_2t_vs_faster"] = std::min((*on)[0], (*on)[1]) / pair.ms_per_call(1);
  }
  state.counters["colliding"] = static_cast<double>(cycles[0].contacts().size());
  // speedup_<stage>: the same ratio for each stage that took time (the
  // serial one, propagate, shows ~1).
  pair.stage_ratios(state, "speedup_", 0, 1);
  // ms1_<stage>, ms2_<stage>: the stage's time a cycle on 1 and 2 threads,
  // so a stage's loss (ms2 - ms1 / 2) can be weighed against the others'.
  const double calls = static_cast<double>(std::max<std::int64_t>(pair.calls, 1));
  for (std::size_t st = 0; st < kCostStages; ++st) {
    if (!(pair.stages[0].ms[st] > 0.0) || static_cast<CostStage>(st) == CostStage::Apply) continue;
    const std::string name(cost_stage_name(static_cast<CostStage>(st)));
    state.counters["ms1_" + name] = pair.stages[0].ms[st] / calls;
    state.counters["ms2_" + name] = pair.stages[1].ms[st] / calls;
  }
}
BENCHMARK(BM_ThreadsPaired)->Args({0, 0})->Args({1, 0})->Args({2, 0})->Args({0, 125})->Unit(benchmark::kMillisecond);

// What this machine gives a second thread on this very work, with none of
// a split's own costs: BM_TwinCycles/<scene> (scenes as in
// BM_ThreadsPaired) runs two independent one-thread cycles ("twins"), each
// on its own copy of the world, in three ways an iteration, which of them
// first rotating with the iteration: one twin after the other on this
// thread pinned to the first allowed CPU, the same pinned to the second
// ("alone"), and both at once on a pool's two threads ("beside", timed from
// the hand-off until both are done; then an untimed pause of twice the
// pool's poll, so its worker's polling does not run beside the next
// alone pair). Beside, no thread waits for the other and nothing is
// serial, so throughput_2t (each twin's cycles a second beside, added up,
// over the mean of the two CPUs' rates alone) is what the second vCPU adds
// to this work when the two only share the machine (caches beyond L2,
// memory, the hypervisor's placement): an estimate of how far a split of
// one cycle can get here, not a bound. throughput_2t_wall counts the pair
// done only when the later twin is (two cycles a section): lower where one
// vCPU runs slower, which a split's chunks taken as threads come free
// would partly even out, and by the worker's start (about 0.1 ms). The
// twins hold two sets of tables where a split cycle's threads share one
// (more cache pressure than a split meets), while a split cycle pays for
// its serial stages and waits, and its threads read what the other has
// just written (the tables both built, the contacts this thread
// listed), which the twins never do and this machine may charge for
// (sim/parallel/core_handover.hpp). cpu_ratio: the second CPU's time alone
// over the first's; far from 1, the vCPUs ran at different speeds in that
// run (a neighbour on the host), and no paired 1-against-2-thread ratio of
// the same minutes means much. slowdown_<stage>: a stage's time a cycle
// beside over alone (1 = unhurt by the other core). Stops with an error if
// the twins' contact counts differ or two CPUs cannot be had.
void BM_TwinCycles(benchmark::State& state) {
  const bool dogs = state.range(0) == 0;
  if (dogs && !have_dog_mesh(state)) return;
  const std::vector<int> cpus = allowed_cpus();
  if (cpus.size() < 2) {
    state.SkipWithError("needs two CPUs");
    return;
  }
  Fixture f = paired_scene(state.range(0));
  World twin = clone_world(f.world);
  CollisionSettings one = resolve_collision_settings(f.world, f.scene.collision, f.scene.world.dt_s);
  one.threads = 1;
  CollisionCycle cycles[2] = {CollisionCycle(f.world, one, DetectionMode::SpatialHash),
                              CollisionCycle(twin, one, DetectionMode::SpatialHash)};
  World* worlds[2] = {&f.world, &twin};
  WorkerPool pool(2);
  // A new worker polls first: let it block before the first pinned pair runs.
  std::this_thread::sleep_for(std::chrono::microseconds(2 * WorkerPool::poll_us()));
  // Stage times summed over the cycles run so (beside: a twin's own, added up after).
  StageCosts alone, beside[2];
  const auto run = [&](int k, StageCosts& sum) {
    full_cycle(cycles[k], *worlds[k]);
    add_stage_ms(sum, cycles[k]);
  };
  using Clock = std::chrono::steady_clock;
  const auto seconds_since = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };
  double alone_s[2] = {0.0, 0.0};  // both twins in turn, pinned to cpus[0] and to cpus[1]
  double beside_s = 0.0;           // both twins at once, until the later is done
  double twin_s[2] = {0.0, 0.0};   // each twin's own time beside the other
  std::int64_t calls = 0;
  for (auto _ : state) {
    for (int k = 0; k < 3; ++k) {
      const int what = static_cast<int>((calls + k) % 3);  // 0, 1: alone on that CPU; 2: beside
      if (what == 2) {
        const auto start = Clock::now();
        pool.for_ranges(2, [&](int part, std::size_t, std::size_t) {
          const auto twin_start = Clock::now();
          run(part, beside[part]);
          twin_s[part] += seconds_since(twin_start);
        });
        beside_s += seconds_since(start);
        state.PauseTiming();
        std::this_thread::sleep_for(std::chrono::microseconds(2 * WorkerPool::poll_us()));
        state.ResumeTiming();
        continue;
      }
      const ScopedPin pin(cpus[static_cast<std::size_t>(what)]);
      if (!pin.error().empty()) {
        state.SkipWithError(pin.error().c_str());
        return;
      }
      const auto start = Clock::now();
      run(0, alone);
      run(1, alone);
      alone_s[what] += seconds_since(start);
    }
    ++calls;
    if (cycles[0].contacts().size() != cycles[1].contacts().size()) {
      state.SkipWithError("the twin cycles found different contact counts");
      return;
    }
  }
  const double n = static_cast<double>(std::max<std::int64_t>(calls, 1));
  // Rates in cycles a second: alone, the mean of the two CPUs'; beside, the
  // twins' added up, or two cycles a section.
  const double alone_rate = 0.5 * (2.0 * n / alone_s[0] + 2.0 * n / alone_s[1]);
  state.counters["throughput_2t"] = (n / twin_s[0] + n / twin_s[1]) / alone_rate;
  state.counters["throughput_2t_wall"] = 2.0 * n / beside_s / alone_rate;
  state.counters["cpu_ratio"] = alone_s[1] / alone_s[0];
  state.counters["ms_alone_cpu0"] = 1e3 * alone_s[0] / (2.0 * n);  // a cycle
  state.counters["ms_alone_cpu1"] = 1e3 * alone_s[1] / (2.0 * n);
  state.counters["ms_beside"] = 1e3 * beside_s / n;  // a section: two cycles at once
  state.counters["colliding"] = static_cast<double>(cycles[0].contacts().size());
  for (std::size_t st = 0; st < kCostStages; ++st) {
    if (!(alone.ms[st] > 0.0) || static_cast<CostStage>(st) == CostStage::Apply) continue;
    // Per cycle: alone ran four cycles an iteration, beside two.
    const double beside_ms = (beside[0].ms[st] + beside[1].ms[st]) / 2.0, alone_ms = alone.ms[st] / 4.0;
    state.counters["slowdown_" + std::string(cost_stage_name(static_cast<CostStage>(st)))] = beside_ms / alone_ms;
  }
}
BENCHMARK(BM_TwinCycles)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

// What hashing the surface as a whole on one thread buys, measured side by
// side: BM_SurfaceWholePaired/<scene> (0 the dog pair, 2 plates20 after 300
// steps, as in BM_ThreadsPaired) runs two one-thread cycles on one world,
// the first one triangle a task (CycleSchedule::whole_surface_hash off: the
// serial insert_box() and build()), the second the whole stage at once
// (SurfaceHash::hash_all on a pool of the calling thread: the owners'
// build), both in every iteration (which goes first alternates).
// speedup: the first's time over the second's (sums over the iterations),
// speedup_<stage> the same a stage. The same table, work and contacts
// either way (collision_cycle_test checks it); stops with an error if the
// colliding counts differ.
void BM_SurfaceWholePaired(benchmark::State& state) {
  const bool dogs = state.range(0) == 0;
  if (dogs && !have_dog_mesh(state)) return;
  Fixture f = paired_scene(state.range(0));  // 0 or 2
  CollisionSettings settings = resolve_collision_settings(f.world, f.scene.collision, f.scene.world.dt_s);
  settings.threads = 1;
  CycleSchedule one_by_one, whole;
  one_by_one.whole_surface_hash = false;
  whole.whole_surface_hash = true;
  CollisionCycle cycles[2] = {CollisionCycle(f.world, settings, DetectionMode::SpatialHash, one_by_one),
                              CollisionCycle(f.world, settings, DetectionMode::SpatialHash, whole)};
  CollisionCycle* both[2] = {&cycles[0], &cycles[1]};
  World* worlds[2] = {&f.world, &f.world};
  SideBySide pair;  // 0: one triangle a task, 1: the whole stage
  if (!pair.loop(state, both, worlds, false, [](std::int64_t) {},
                 "the one-triangle and whole-stage surface hashes found different contacts"))
    return;
  state.counters["speedup"] = pair.seconds[1] > 0.0 ? pair.seconds[0] / pair.seconds[1] : 0.0;
  state.counters["ms_one_by_one"] = pair.ms_per_call(0);
  state.counters["ms_whole"] = pair.ms_per_call(1);
  pair.stage_ratios(state, "speedup_", 0, 1);
  double triangles = 0.0;
  for (const Body& b : f.world.bodies) triangles += static_cast<double>(b.mesh->surface.size());
  state.counters["surface_triangles"] = triangles;
}
BENCHMARK(BM_SurfaceWholePaired)->Arg(0)->Arg(2)->Unit(benchmark::kMillisecond);

// What ordering along a space-filling curve buys, measured side by side:
// BM_OrderPaired/<numbering>/<keep>/<scene> runs the dog pair (scene 0; 1:
// plates20, /0 only) as the file numbers it
// with the detector's tets in the file's order (DetectionSettings::
// curve_order off: the layout before the detector's slots), against
// 0: the same mesh with the detector's slots along a Morton curve (the
// default; the same answers and work), or the mesh itself renumbered
// (1: tets along a Morton curve by centroid, 2: vertices, 3: both), or
// 4: the default slots on both sides, the second with its vertices
// renumbered (scene mesh_order "curve" against the default "file"), one
// cycle of each in every iteration (which goes first alternates), with the
// moving benchmarks' motion and keep. time_ratio: the second over the first
// (sums over the iterations); ratio_<stage> the same a stage. Renumbering
// the vertices (/2) is the scene setting mesh_order = "curve", a named
// variant and not the paper's default: it changes the order of sums and
// which candidate a smallest-index rule picks, so its steps.csv is not the
// file's bit for bit; tets renumbered (/1, /3) are no setting at all (the
// detector's slots, /0, give their layout without renumbering). Stops with
// an error if the colliding counts differ.
void BM_OrderPaired(benchmark::State& state) {
  const bool plates = state.range(2) == 1;
  if (!plates && !have_dog_mesh(state)) return;
  const bool both_slotted = state.range(0) == 4;
  if (plates && state.range(0) != 0) {
    state.SkipWithError("plates20 is generated: only the detector's slots (/0) apply");
    return;
  }
  const Numbering second = both_slotted ? Numbering::MortonVertices : static_cast<Numbering>(state.range(0));
  Fixture f[2] = {plates ? plates20() : dog_pair(), plates ? plates20() : dog_pair(second)};
  const std::vector<char> moving = every_other_body(f[0].world);
  std::vector<CollisionCycle> cycles;
  for (Fixture& g : f) {
    CollisionSettings settings = resolve_collision_settings(g.world, g.scene.collision, g.scene.world.dt_s);
    settings.threads = 1;
    settings.detection.curve_order = both_slotted || &g != &f[0];
    cycles.emplace_back(g.world, settings, DetectionMode::SpatialHash, keep_schedule(state.range(1)));
  }
  CollisionCycle* both[2] = {&cycles[0], &cycles[1]};
  World* worlds[2] = {&f[0].world, &f[1].world};
  SideBySide pair;  // 0: the file's numbering and order, 1: slots along the curve, or renumbered
  const auto move = [&](std::int64_t call) {
    for (Fixture& g : f) move_between_cycles(g.world, moving, call);
  };
  if (!pair.loop(state, both, worlds, true, move, "the reordered pair found a different number of contacts"))
    return;
  state.counters["time_ratio"] = pair.seconds[0] > 0.0 ? pair.seconds[1] / pair.seconds[0] : 0.0;
  state.counters["ms_file"] = pair.ms_per_call(0);
  state.counters["ms_renumbered"] = pair.ms_per_call(1);
  state.counters["colliding"] = static_cast<double>(cycles[0].contacts().size());
  pair.stage_ratios(state, "ratio_", 1, 0);
}
BENCHMARK(BM_OrderPaired)
    ->ArgsProduct({{0, 1, 2, 3, 4}, {0, 125}, {0}})
    ->Args({0, 0, 1})
    ->Args({0, 125, 1})
    ->Unit(benchmark::kMillisecond);


// The grid the bare references below cut (BM_HashFloorPaired,
// BM_PointGridPaired): cells as the detector cuts them (SpatialHash::
// cell_of), a dense grid over every body's vertices (so over every tet's
// box: a tet's corners are vertices), and each body's reach, the box of
// the other bodies' vertices, where a tet whose box misses it is left out,
// as the cycle leaves it out.
struct BareFrame {
  std::int64_t first[3] = {0, 0, 0};
  std::int64_t n[3] = {1, 1, 1};
  std::vector<Vec3> reach_lo, reach_hi;

  void cut(const World& world, const SpatialHash& grid) {
    const std::size_t bodies = world.bodies.size();
    std::vector<Vec3> lo(bodies, Vec3::Constant(INFINITY)), hi(bodies, Vec3::Constant(-INFINITY));
    Vec3 all_lo = Vec3::Constant(INFINITY), all_hi = Vec3::Constant(-INFINITY);
    for (std::size_t b = 0; b < bodies; ++b) {
      for (const Vec3& p : world.bodies[b].x_m) {
        lo[b] = lo[b].cwiseMin(p);
        hi[b] = hi[b].cwiseMax(p);
      }
      all_lo = all_lo.cwiseMin(lo[b]);
      all_hi = all_hi.cwiseMax(hi[b]);
    }
    for (int a = 0; a < 3; ++a) {
      first[a] = grid.cell_of(all_lo[a]);
      n[a] = grid.cell_of(all_hi[a]) - first[a] + 1;
    }
    reach_lo.assign(bodies, Vec3::Constant(INFINITY));
    reach_hi.assign(bodies, Vec3::Constant(-INFINITY));
    for (std::size_t b = 0; b < bodies; ++b)
      for (std::size_t o = 0; o < bodies; ++o)
        if (o != b) {
          reach_lo[b] = reach_lo[b].cwiseMin(lo[o]);
          reach_hi[b] = reach_hi[b].cwiseMax(hi[o]);
        }
  }
  std::size_t cells() const { return static_cast<std::size_t>(n[0] * n[1] * n[2]); }
  std::size_t cell_of_point(const SpatialHash& grid, const Vec3& p) const {
    return index(grid.cell_of(p.x()) - first[0], grid.cell_of(p.y()) - first[1], grid.cell_of(p.z()) - first[2]);
  }
  /// Calls visit(t, lo, hi) with the index and box of every tet t of body b, in file order,
  /// that is not degenerate and reaches the other bodies' vertices.
  template <typename Visit>
  void for_each_kept_tet(const Body& body, std::size_t b, Visit&& visit) const {
    for (std::size_t t = 0; t < body.mesh->tet_count(); ++t) {
      if (body.mesh->is_degenerate[t]) continue;
      Vec3 lo, hi;
      tet_box_of(body.x_m, body.mesh->tets[t], lo, hi);
      if ((hi.array() < reach_lo[b].array()).any() || (lo.array() > reach_hi[b].array()).any()) continue;
      visit(t, lo, hi);
    }
  }
  /// Calls visit(cell) for every cell box [lo, hi] covers (inside the grid).
  template <typename Visit>
  void for_each_cell(const SpatialHash& grid, const Vec3& lo, const Vec3& hi, Visit&& visit) const {
    const std::int64_t i0 = grid.cell_of(lo.x()) - first[0], i1 = grid.cell_of(hi.x()) - first[0];
    const std::int64_t j0 = grid.cell_of(lo.y()) - first[1], j1 = grid.cell_of(hi.y()) - first[1];
    const std::int64_t k0 = grid.cell_of(lo.z()) - first[2], k1 = grid.cell_of(hi.z()) - first[2];
    for (std::int64_t i = i0; i <= i1; ++i)
      for (std::int64_t j = j0; j <= j1; ++j)
        for (std::int64_t k = k0; k <= k1; ++k) visit(index(i, j, k));
  }
  std::size_t index(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return static_cast<std::size_t>((i * n[1] + j) * n[2] + k);
  }
};

// A budgetless one-thread cycle and a bare reference, both in every
// iteration (which goes first alternates, so the host's load weighs on both
// alike): the cycle's time in `stages` (its stage clock) and the
// reference's (a steady clock around bare()), summed. After each iteration
// check() may stop the benchmark (returns false).
struct BesideCycle {
  double cycle_ms = 0.0, bare_ms = 0.0;
  std::int64_t calls = 0;
  bool ok = true;
};
template <typename Bare, typename Check>
BesideCycle time_beside_cycle(benchmark::State& state, CollisionCycle& cycle, World& world,
                              std::initializer_list<CostStage> stages, Bare&& bare, Check&& check) {
  BesideCycle t;
  for (auto _ : state) {
    for (int k = 0; k < 2; ++k) {
      if ((t.calls + k) % 2 == 0) {
        full_cycle(cycle, world);
        for (const CostStage st : stages) t.cycle_ms += cycle.step_costs().ms[static_cast<std::size_t>(st)];
      } else {
        const auto start = std::chrono::steady_clock::now();
        bare();
        t.bare_ms += 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      }
    }
    ++t.calls;
    if (!check()) {
      t.ok = false;
      break;
    }
  }
  return t;
}

// A floor for the cycle's tet hashing, measured beside it:
// BM_HashFloorPaired/<scene> (0 the dog pair, 1 plates20) runs a
// budgetless one-thread cycle and a bare dense-grid build of the same tets
// (time_beside_cycle). The bare build is the least a table the queries
// could read takes: each body's tets in file order, left out as the cycle
// leaves them out (BareFrame), a count a cell, a prefix sum over the whole
// grid, a fill. It keeps no boxes, no body unions, no work charge, no
// overflow check, no threads, nothing the budgets need; it is a reference,
// not a detector. It enters a tet into every cell of its box, where the
// cycle leaves out the cells holding no other body's vertex
// (TetHashDetector::hash_tets): the floor of a build into every cell, which
// the cycle, entering fewer, may pass (the dog pair: 0.77). floor_ratio: the cycle's hash_tets
// stage time over the bare build's (sums over the iterations);
// entries_ratio: the bare build's entries over cells_per_tet x tets (1 when
// it left out no tets; below 1 by the share of cells it left out).
struct BareGrid {
  BareFrame frame;
  std::vector<std::uint32_t> start;  // a cell's first item, then its fill cursor
  std::vector<std::uint32_t> items;
};

std::size_t bare_grid_build(const World& world, const SpatialHash& grid, BareGrid& g) {
  g.frame.cut(world, grid);
  g.start.assign(g.frame.cells() + 1, 0);
  // Twice over the tets: count, then fill; `visit(cell, item)` per cell.
  const auto walk = [&](auto&& visit) {
    std::uint32_t first_item = 0;  // the body's first tet's item
    for (std::size_t b = 0; b < world.bodies.size(); ++b) {
      const Body& body = world.bodies[b];
      g.frame.for_each_kept_tet(body, b, [&](std::size_t t, const Vec3& lo, const Vec3& hi) {
        const auto item = first_item + static_cast<std::uint32_t>(t);
        g.frame.for_each_cell(grid, lo, hi, [&](std::size_t c) { visit(c, item); });
      });
      first_item += static_cast<std::uint32_t>(body.mesh->tet_count());
    }
  };
  walk([&](std::size_t c, std::uint32_t) { ++g.start[c + 1]; });
  for (std::size_t c = 1; c < g.start.size(); ++c) g.start[c] += g.start[c - 1];
  g.items.resize(g.start.back());
  walk([&](std::size_t c, std::uint32_t item) { g.items[g.start[c]++] = item; });
  return g.items.size();
}

void BM_HashFloorPaired(benchmark::State& state) {
  const bool dogs = state.range(0) == 0;
  if (dogs && !have_dog_mesh(state)) return;
  Fixture f = dogs ? dog_pair() : plates20();
  CollisionSettings settings = resolve_collision_settings(f.world, f.scene.collision, f.scene.world.dt_s);
  settings.threads = 1;
  const CellFigures cells = cell_figures(f.world, settings.detection);
  const SpatialHash grid(settings.detection.cell_size_m, 1, settings.detection.hash);  // for cell_of() alone
  CollisionCycle cycle(f.world, settings, DetectionMode::SpatialHash);
  BareGrid bare;
  std::size_t entries = 0;
  const BesideCycle t = time_beside_cycle(
      state, cycle, f.world, {CostStage::HashTets},
      [&] {
        entries = bare_grid_build(f.world, grid, bare);
        benchmark::DoNotOptimize(bare.items.data());
      },
      [] { return true; });
  const std::size_t tets = total_tets(f.world);
  const double n = static_cast<double>(std::max<std::int64_t>(t.calls, 1));
  state.counters["ms_hash_tets"] = t.cycle_ms / n;
  state.counters["ms_bare"] = t.bare_ms / n;
  state.counters["floor_ratio"] = t.bare_ms > 0.0 ? t.cycle_ms / t.bare_ms : 0.0;
  state.counters["bare_ns_per_tet"] = 1e6 * t.bare_ms / n / static_cast<double>(tets);
  state.counters["entries_ratio"] = static_cast<double>(entries) / (cells.cells_per_tet * static_cast<double>(tets));
  state.counters["grid_cells"] = static_cast<double>(bare.frame.cells());
}
BENCHMARK(BM_HashFloorPaired)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// What hashing the points instead of the tets would cost, measured beside
// the paper's tet hash: BM_PointGridPaired/<scene> (0 the dog pair, 1
// plates20) runs a budgetless one-thread cycle and a bare point grid
// (time_beside_cycle). The point grid enters every vertex into the one
// cell it lies in (count, prefix sum, fill: one entry a point, where the
// tet hash enters each tet into cells_per_tet cells); then each tet, left
// out as the cycle leaves it out (BareFrame), visits the cells its box
// covers and tests the other bodies' points there not yet found inside:
// its box, then the method's exact point_in_tet_perturbed. It answers only
// which vertices are inside, not which tet (the cycle's smallest file id)
// nor any depth, charges no work, and would not fit the interruptible
// handler's tasks, which are per point: a variant's floor, not the paper's
// method. ratio: the cycle's hash_tets + query_points stage time over the
// point grid's (sums over the iterations). Stops with an error where the
// two find different vertices inside.
struct PointGrid {
  BareFrame frame;
  std::vector<std::uint32_t> offset;  // body b's vertices are ids offset[b] ..
  std::vector<std::uint32_t> start;   // a cell's first point, after the fill
  std::vector<std::uint32_t> points;  // vertex ids (offset of the body + vertex)
  std::vector<Vec3> positions;        // the points' positions, in the same order
  std::vector<std::uint32_t> owner;   // the points' bodies, in the same order
};

std::size_t bare_point_grid_inside(const World& world, const SpatialHash& grid, PointGrid& g,
                                   std::vector<char>& inside) {
  const std::size_t bodies = world.bodies.size();
  g.frame.cut(world, grid);
  g.offset.assign(bodies + 1, 0);
  for (std::size_t b = 0; b < bodies; ++b)
    g.offset[b + 1] = g.offset[b] + static_cast<std::uint32_t>(world.bodies[b].x_m.size());
  g.start.assign(g.frame.cells() + 1, 0);
  for (const Body& body : world.bodies)
    for (const Vec3& p : body.x_m) ++g.start[g.frame.cell_of_point(grid, p) + 1];
  for (std::size_t c = 1; c < g.start.size(); ++c) g.start[c] += g.start[c - 1];
  g.points.resize(g.offset[bodies]);
  g.positions.resize(g.offset[bodies]);
  g.owner.resize(g.offset[bodies]);
  std::vector<std::uint32_t> cursor(g.start.begin(), g.start.end() - 1);
  for (std::size_t b = 0; b < bodies; ++b)
    for (std::size_t v = 0; v < world.bodies[b].x_m.size(); ++v) {
      const Vec3& p = world.bodies[b].x_m[v];
      const std::uint32_t e = cursor[g.frame.cell_of_point(grid, p)]++;
      g.points[e] = g.offset[b] + static_cast<std::uint32_t>(v);
      g.positions[e] = p;
      g.owner[e] = static_cast<std::uint32_t>(b);
    }
  inside.assign(g.offset[bodies], 0);
  std::size_t found = 0;
  for (std::size_t b = 0; b < bodies; ++b) {
    const Body& body = world.bodies[b];
    const auto& x = body.x_m;
    g.frame.for_each_kept_tet(body, b, [&](std::size_t t, const Vec3& lo, const Vec3& hi) {
      const Tet& tet = body.mesh->tets[t];
      g.frame.for_each_cell(grid, lo, hi, [&](std::size_t c) {
        for (std::uint32_t e = g.start[c]; e < g.start[c + 1]; ++e) {
          if (g.owner[e] == b) continue;
          const Vec3& p = g.positions[e];
          if ((p.array() < lo.array()).any() || (p.array() > hi.array()).any()) continue;
          const std::uint32_t id = g.points[e];
          if (inside[id]) continue;
          if (point_in_tet_perturbed(p, x[tet[0]], x[tet[1]], x[tet[2]], x[tet[3]])) {
            inside[id] = 1;
            ++found;
          }
        }
      });
    });
  }
  return found;
}

void BM_PointGridPaired(benchmark::State& state) {
  const bool dogs = state.range(0) == 0;
  if (dogs && !have_dog_mesh(state)) return;
  Fixture f = dogs ? dog_pair() : plates20();
  CollisionSettings settings = resolve_collision_settings(f.world, f.scene.collision, f.scene.world.dt_s);
  settings.threads = 1;
  const SpatialHash grid(settings.detection.cell_size_m, 1, settings.detection.hash);  // for cell_of() alone
  CollisionCycle cycle(f.world, settings, DetectionMode::SpatialHash);
  PointGrid bare;
  std::vector<char> inside;
  std::size_t found = 0;
  // Both answers after every iteration: the same vertices inside.
  const auto same = [&] {
    if (found != cycle.contacts().size()) return false;
    for (const Contact& c : cycle.contacts())
      if (!inside[bare.offset[static_cast<std::size_t>(c.object)] + static_cast<std::size_t>(c.vertex)]) return false;
    return true;
  };
  const BesideCycle t = time_beside_cycle(
      state, cycle, f.world, {CostStage::HashTets, CostStage::QueryPoints},
      [&] {
        found = bare_point_grid_inside(f.world, grid, bare, inside);
        benchmark::DoNotOptimize(inside.data());
      },
      same);
  if (!t.ok) {
    state.SkipWithError("the point grid and the cycle found different vertices inside");
    return;
  }
  const double n = static_cast<double>(std::max<std::int64_t>(t.calls, 1));
  state.counters["ms_hash_and_query"] = t.cycle_ms / n;
  state.counters["ms_point_grid"] = t.bare_ms / n;
  state.counters["ratio"] = t.bare_ms > 0.0 ? t.cycle_ms / t.bare_ms : 0.0;
  state.counters["point_grid_ns_per_tet"] = 1e6 * t.bare_ms / n / static_cast<double>(total_tets(f.world));
  state.counters["colliding"] = static_cast<double>(cycle.contacts().size());
}
BENCHMARK(BM_PointGridPaired)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
