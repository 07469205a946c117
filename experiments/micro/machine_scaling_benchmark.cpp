// The machine's own ceiling on a second thread: how much faster two threads
// finish a fixed amount of work than one, for kinds of work that stress
// different parts of the machine. The collision cycle's stages scale 1.4x to
// 1.8x on the development VM (issue 14); this says which of them the machine
// itself caps, and where, so a report does not blame the method for a
// ceiling of the hardware (or the hypervisor's placement of its vCPUs, which
// a guest cannot see: lscpu reports what the hypervisor tells it).
//   build/release/experiments/micro/micro_machine_scaling
// Every iteration runs the same work on the project's WorkerPool with one
// thread and then with two (for_ranges: halves on the two threads), so the
// two times are paired and alternate; counter `speedup_2t` is the sum of the
// one-thread times over the sum of the two-thread times, `ns_per_item_1t`
// the one-thread cost of an item. Kinds (the argument is a working set in
// KiB where it has one):
//   BM_FmaThroughput  32 independent multiply-add chains a thread: enough to
//                     keep the core's floating-point ports busy (an item
//                     takes longer than BM_FmaLatency's despite 32x the
//                     chains). Two vCPUs on two cores give ~2x; on the two
//                     hyperthreads of one core they share the ports and give
//                     little more than 1x.
//   BM_FmaLatency     one dependent chain: the ports mostly idle, ~2x on
//                     either placement (a control for the one above).
//   BM_Chase/S        a dependent chain of loads through a random cycle of
//                     64-byte nodes spanning S KiB, each thread from its own
//                     start: the shape of a point query (bucket, entries,
//                     box, tet, positions, each address read from the last).
//                     Two threads share the caches beyond L2 and the memory.
//   BM_Gather/S       independent random loads from the same nodes: what
//                     overlapping misses (prefetching, several queries in
//                     flight) could reach.
//   BM_Handover/S     not a ratio of thread counts: reading lines the other
//                     core has just written against lines this core wrote
//                     (see its comment).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "sim/parallel/core_handover.hpp"
#include "sim/parallel/worker_pool.hpp"

namespace {

using tcb::WorkerPool;

// Runs `items` items split over each pool, the one-thread pool first, and
// accumulates both wall times (seconds).
template <typename Kernel>
void paired_iteration(WorkerPool& one, WorkerPool& two, std::size_t items, const Kernel& kernel, double& one_s,
                      double& two_s) {
  for (WorkerPool* pool : {&one, &two}) {
    const auto start = std::chrono::steady_clock::now();
    pool->for_ranges(items, [&](int part, std::size_t begin, std::size_t end) { kernel(part, begin, end); });
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    (pool == &one ? one_s : two_s) += s;
  }
}

template <typename Kernel>
void run_paired(benchmark::State& state, std::size_t items, const Kernel& kernel) {
  WorkerPool one(1), two(2);
  double one_s = 0.0, two_s = 0.0;
  std::int64_t iterations = 0;
  for (auto _ : state) {
    paired_iteration(one, two, items, kernel, one_s, two_s);
    ++iterations;
  }
  state.counters["speedup_2t"] = two_s > 0.0 ? one_s / two_s : 0.0;
  state.counters["ns_per_item_1t"] = 1e9 * one_s / (static_cast<double>(iterations) * static_cast<double>(items));
}

// Sinks a value per thread so no kernel is optimized away. Padded to a line
// each: two threads writing one line would be a cost of this benchmark.
struct alignas(64) Sink {
  double value = 0.0;
  std::uint64_t bits = 0;
};

// N independent multiply-add chains (the argument), 64 steps each an item.
template <int N>
void fma_chains(benchmark::State& state) {
  Sink sinks[2];
  run_paired(state, std::size_t{1} << 14, [&](int part, std::size_t begin, std::size_t end) {
    double acc[N];
    for (int c = 0; c < N; ++c) acc[c] = 1.0 + c;
    for (std::size_t i = begin; i < end; ++i)
      for (int k = 0; k < 64; ++k)
        for (double& a : acc) a = a * 0.999999 + 1e-7;
    double sum = 0.0;
    for (const double a : acc) sum += a;
    sinks[part].value += sum;
    benchmark::DoNotOptimize(sinks[part].value);
  });
}
void BM_FmaLatency(benchmark::State& state) { fma_chains<1>(state); }
void BM_FmaThroughput(benchmark::State& state) { fma_chains<32>(state); }

struct alignas(64) Node {
  std::uint32_t next = 0;
};

// One random cycle through all nodes (Sattolo's algorithm), fixed seed.
std::vector<Node> random_cycle(std::size_t kib) {
  const std::size_t n = kib * 1024 / sizeof(Node);
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::mt19937_64 rng(14);
  for (std::size_t i = n - 1; i > 0; --i) std::swap(order[i], order[std::uniform_int_distribution<std::size_t>(0, i - 1)(rng)]);
  std::vector<Node> nodes(n);
  for (std::size_t i = 0; i < n; ++i) nodes[order[i]].next = order[(i + 1) % n];
  return nodes;
}

void BM_Chase(benchmark::State& state) {
  const std::vector<Node> nodes = random_cycle(static_cast<std::size_t>(state.range(0)));
  Sink sinks[2];
  run_paired(state, std::size_t{1} << 18, [&](int part, std::size_t begin, std::size_t end) {
    // Each range starts at its own place in the cycle (hashed from begin:
    // begin itself is a multiple of the node count on the smaller sets), so
    // two threads do not walk behind each other through lines the other loaded.
    std::uint32_t at = static_cast<std::uint32_t>((begin * 0x9E3779B97F4A7C15ULL >> 20) % nodes.size());
    for (std::size_t i = begin; i < end; ++i) at = nodes[at].next;
    sinks[part].bits += at;
    benchmark::DoNotOptimize(sinks[part].bits);
  });
}

void BM_Gather(benchmark::State& state) {
  const std::vector<Node> nodes = random_cycle(static_cast<std::size_t>(state.range(0)));
  Sink sinks[2];
  run_paired(state, std::size_t{1} << 18, [&](int part, std::size_t begin, std::size_t end) {
    // Addresses from the index alone (a multiplicative hash), not from a
    // load: the loads are independent and may overlap.
    std::uint64_t sum = 0;
    for (std::size_t i = begin; i < end; ++i) sum += nodes[(i * 0x9E3779B97F4A7C15ULL >> 20) % nodes.size()].next;
    sinks[part].bits += sum;
    benchmark::DoNotOptimize(sinks[part].bits);
  });
}

// Reading what the other core has just written, against what this core
// has (sim/parallel/core_handover.hpp): a split cycle's threads build one
// table together and then both read all of it (the point queries), so
// about half of what each reads was last written by the other core, which
// two independent cycles side by side (micro_collision_cycle
// BM_TwinCycles) never meet. BM_Handover/S: S KiB, two rounds an
// iteration; read_ratio is the read after the other core's fills over the
// read after this one's (sums over the iterations), ns_per_line_own and
// ns_per_line_other the means an iteration, apart_share the share of the
// other core's fills that ran on another CPU than the read (1 unless the
// scheduler put both threads on one).
void BM_Handover(benchmark::State& state) {
  WorkerPool two(2);
  double own_ns = 0.0, other_ns = 0.0;
  int fills = 0, apart = 0;
  for (auto _ : state) {
    const tcb::HandoverTimes t = tcb::measure_handover(two, static_cast<std::size_t>(state.range(0)) * 1024, 2);
    own_ns += t.own_ns_per_line;
    other_ns += t.other_ns_per_line;
    fills += t.other_fills;
    apart += t.other_fills_apart;
  }
  const double n = static_cast<double>(std::max<benchmark::IterationCount>(state.iterations(), 1));
  state.counters["read_ratio"] = own_ns > 0.0 ? other_ns / own_ns : 0.0;
  state.counters["ns_per_line_own"] = own_ns / n;
  state.counters["ns_per_line_other"] = other_ns / n;
  state.counters["apart_share"] = fills > 0 ? static_cast<double>(apart) / fills : 0.0;
}

// Working sets: within L2 (1 MiB), the collision cycle's on the dog pair
// (boxes, tets, table and positions: about 8 MiB, 16 with the overflow),
// and beyond the last-level cache (512 MiB). The chase also at 2, 4 and 8
// MiB, where one thread's share of the last-level cache runs out: on the
// development VM that share moved from run to run (8 MiB: 30 to 114 ns an
// item on one thread), and two threads gained least at 4 MiB (1.09x to
// 1.69x in four runs, against 1.57-1.78x at 1 MiB and 1.73-2.16x from memory),
// the regime the dog pair's cycle works in.
BENCHMARK(BM_FmaThroughput)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FmaLatency)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Chase)
    ->Arg(1024)
    ->Arg(2 * 1024)
    ->Arg(4 * 1024)
    ->Arg(8 * 1024)
    ->Arg(16 * 1024)
    ->Arg(512 * 1024)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Gather)->Arg(1024)->Arg(16 * 1024)->Arg(512 * 1024)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Handover)->Arg(256)->Arg(1024)->Arg(4 * 1024)->Arg(16 * 1024)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
