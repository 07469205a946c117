// What handing work to the pool's threads costs: one for_ranges whose parts
// do nothing, on a pool of two, after a stretch of serial work on the
// caller (the collision cycle's shape: serial code, then a parallel
// section). The worker polls for WorkerPool::poll_us() after a section
// before it blocks, so the gap decides which hand-off is measured:
//   BM_HandOff/0      back to back: the worker still polls
//   BM_HandOff/300    a shorter serial stretch than the poll: still polling
//   BM_HandOff/3000   a longer one: the worker blocked and must be woken
// Only the for_ranges call is timed (manual time, microseconds a call).
// Pools whose threads share one CPU never poll (worker_pool.hpp); this
// benchmark runs unpinned, so on a 2-CPU host its pool polls.
//   build/release/experiments/micro/micro_worker_pool
#include <benchmark/benchmark.h>

#include <atomic>
#include <chrono>

#include "sim/parallel/worker_pool.hpp"

namespace {

void BM_HandOff(benchmark::State& state) {
  tcb::WorkerPool pool(2);
  const auto gap = std::chrono::microseconds(state.range(0));
  std::atomic<int> parts{0};
  for (auto _ : state) {
    const auto serial_until = std::chrono::steady_clock::now() + gap;
    while (std::chrono::steady_clock::now() < serial_until) {
    }
    const auto start = std::chrono::steady_clock::now();
    pool.for_ranges(2, [&](int, std::size_t, std::size_t) { parts.fetch_add(1, std::memory_order_relaxed); });
    state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  if (parts != 2 * state.iterations()) state.SkipWithError("a part did not run");
  state.counters["polls"] = pool.polls() ? 1 : 0;
}
BENCHMARK(BM_HandOff)->Arg(0)->Arg(300)->Arg(3000)->UseManualTime()->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
