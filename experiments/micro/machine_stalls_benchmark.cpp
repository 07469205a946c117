// The machine's own floor under microsecond budgets: how often a thread that
// does nothing but read the clock loses the CPU for a while without being
// switched out (timer and other interrupts, hypervisor exits). Such a stall in
// the work a handler does after its last budget check is overshoot no method
// can avoid, so the issue-12 target "overshoot p99 <= 1 % of the budget" is
// only reachable where stalls longer than 1 % of the budget are rarer than
// 1 % of steps in that post-check interval.
//   build/release/experiments/micro/micro_machine_stalls
// Each iteration spins for one window of W µs (the argument: budgets of the
// committed scenes at full/10 and full/3, and 1 ms) and records the longest
// gap between two consecutive clock reads. Counters, over all windows:
//   stalled_1pct   share of windows holding a gap longer than 1 % of W
//   stalled_10us   share of windows holding a gap longer than 10 µs
//   stalls_10us_per_s  gaps longer than 10 µs per second of spinning
//   longest_gap_us the longest gap seen
// The second family reads the thread's CPU clock instead of the wall clock:
// if it shows the same stalls, they are billed to the thread and CPU-time
// overshoot cannot tell them from the method's own (issue 19's verdict).
//
// The third family is a handler that does nothing the machine could slow down
// by itself: tasks of a fixed arithmetic chain on one register (no memory, so
// no cold cache), a steady-clock poll between tasks, and a stop at the first
// poll past the window, as the interruptible handler stops. Its overshoot (end
// of the last task minus the window) is the floor any method meets here with
// tasks of that length. The deadline falls in a stall with a probability the
// stall's length weights, so this floor is what a p99 feels, not the
// stall rate alone. Counters:
//   overshoot_p50_us, overshoot_p99_us  over all windows
//   overshoot_p99_pct                   the p99 as a share of the window
//   task_p50_us, task_p99_us            the interval between polls (a sample)
#include <benchmark/benchmark.h>

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <utility>
#include <vector>

#include "experiments/metrics/distribution.hpp"

namespace {

double read_us(clockid_t clock) {
  timespec t{};
  clock_gettime(clock, &t);
  return static_cast<double>(t.tv_sec) * 1e6 + static_cast<double>(t.tv_nsec) * 1e-3;
}

void run_windows(benchmark::State& state, clockid_t clock) {
  const double window_us = static_cast<double>(state.range(0));
  std::int64_t windows = 0, stalled_1pct = 0, stalled_10us = 0, stalls_10us = 0;
  double spun_us = 0.0, longest_us = 0.0;
  for (auto _ : state) {
    const double start = read_us(clock);
    double previous = start, now = start, longest = 0.0;
    while (now - start < window_us) {
      now = read_us(clock);
      const double gap = now - previous;
      longest = std::max(longest, gap);
      stalls_10us += gap > 10.0;
      previous = now;
    }
    ++windows;
    spun_us += now - start;
    stalled_1pct += longest > 0.01 * window_us;
    stalled_10us += longest > 10.0;
    longest_us = std::max(longest_us, longest);
  }
  const double n = static_cast<double>(std::max<std::int64_t>(windows, 1));
  state.counters["stalled_1pct"] = static_cast<double>(stalled_1pct) / n;
  state.counters["stalled_10us"] = static_cast<double>(stalled_10us) / n;
  state.counters["stalls_10us_per_s"] = spun_us > 0 ? static_cast<double>(stalls_10us) / (spun_us * 1e-6) : 0.0;
  state.counters["longest_gap_us"] = longest_us;
}

void BM_WallClockWindow(benchmark::State& state) { run_windows(state, CLOCK_MONOTONIC); }
void BM_ThreadCpuClockWindow(benchmark::State& state) { run_windows(state, CLOCK_THREAD_CPUTIME_ID); }

// One task: `steps` dependent multiply-adds on a value the compiler cannot
// fold (it is returned and kept). About 4 cycles a step: 256 steps are
// roughly 0.4 µs on a 2.5 GHz core.
double fixed_task(double x, std::int64_t steps) {
  for (std::int64_t i = 0; i < steps; ++i) x = x * 0.999999 + 1e-9;
  return x;
}

void BM_NullHandlerOvershoot(benchmark::State& state) {
  using clock = std::chrono::steady_clock;
  const auto window = std::chrono::microseconds(state.range(0));
  const std::int64_t task_steps = state.range(1);
  std::vector<double> overshoot_us, task_us;
  double x = 1.0;
  std::int64_t polls = 0;
  for (auto _ : state) {
    const auto start = clock::now();
    auto previous = start, now = start;
    while (now - start < window) {
      x = fixed_task(x, task_steps);
      now = clock::now();
      if ((++polls & 15) == 0) task_us.push_back(std::chrono::duration<double, std::micro>(now - previous).count());
      previous = now;
    }
    overshoot_us.push_back(std::chrono::duration<double, std::micro>(now - start - window).count());
  }
  benchmark::DoNotOptimize(x);
  // The run summaries' percentiles (distribution.hpp), so these read as summary.timing.floor does.
  const tcb::Distribution overshoot = tcb::summarize(std::move(overshoot_us)), task = tcb::summarize(std::move(task_us));
  state.counters["overshoot_p50_us"] = overshoot.p50;
  state.counters["overshoot_p99_us"] = overshoot.p99;
  state.counters["overshoot_p99_pct"] = 100.0 * overshoot.p99 / static_cast<double>(state.range(0));
  state.counters["task_p50_us"] = task.p50;
  state.counters["task_p99_us"] = task.p99;
}

// 47, 110, 160, 370 µs: haptic_probe and sneaker_grass at full/10 and full/3
// when this family was written (their full cost has moved since: the null
// handler below uses today's windows); 1000 µs: the haptic probe's 1 ms budget. MinTime so every window count is
// in the thousands.
BENCHMARK(BM_WallClockWindow)->Arg(47)->Arg(110)->Arg(160)->Arg(370)->Arg(1000)->MinTime(2.0)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ThreadCpuClockWindow)->Arg(47)->Arg(160)->Arg(1000)->MinTime(2.0)->Unit(benchmark::kMicrosecond);

// Windows of issue 12's cells on the current main (budget_overshoot.toml):
// haptic_probe full/10 and full/3 (72, 240 µs), sneaker_grass (160, 550 µs),
// 1 ms, plates20 full/10 (1570 µs). Tasks of no steps (a poll only), 256 and
// 512 steps (about the fine tasks' median, 0.8-1.4 µs, on this VM).
BENCHMARK(BM_NullHandlerOvershoot)
    ->ArgsProduct({{72, 160, 240, 550, 1000, 1570}, {0, 256, 512}})
    ->ArgNames({"window_us", "task_steps"})
    ->MinTime(2.0)
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
