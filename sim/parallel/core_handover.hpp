#pragma once
/// What it costs a thread to read memory another core has just written,
/// against memory it wrote itself: the price a job split over two threads
/// pays wherever one thread reads what the other produced (the collision
/// cycle's threads build one table together, then both read all of it).
/// A hypervisor may place two vCPUs on cores that share their last-level
/// cache or on cores that do not, and may move them while a guest runs. On
/// the development VM, one evening, with this probe's first form (lines read
/// in a hashed order computed in the loop) at 4 MiB: 1.00-1.04 in the
/// minutes the dog pair's 2-thread collision cycle ran 1.74-1.86x faster
/// than one thread (plates20 1.82x, settled 1.74x), 2.5-3.3 when it ran
/// 1.35-1.46x; with this form (a shuffled order read from an array, so the
/// own reads overlap better) 2.9-4.5 in minutes of 1.24-1.46x
/// (micro_collision_cycle BM_ThreadsPaired beside micro_machine_scaling
/// BM_Handover/4096, then BM_ThreadsPaired's handover_before and
/// handover_after). With this form, a later evening: 1.09-1.29 in a minute
/// of 1.77-2.07x (dog pair 1.77, plates20 2.07, settled 2.01, dog moving
/// 1.87), 1.21-1.61 at 1.60-1.87x the minute before; but also 1.5-2.9 at
/// 1.58-1.79x in a minute when the host slowed the one-thread cycle to 1.6
/// times its usual time. So the ratio places a time taken on two threads;
/// it does not predict it, and such a time is read with it beside it.
///
/// Contract: measure_handover(pool, bytes, rounds) fills `bytes` (rounded down
/// to whole 64-byte lines, at least one) with a new value in every line,
/// written by the pool's second thread ("other") or by the calling thread
/// ("own"), `rounds` times each, alternating which goes first, and after every
/// fill times the calling thread reading every line once in a fixed shuffled
/// order (independent loads; the order is read from a sequential array).
/// Before the timed rounds the calling thread fills and reads the lines once,
/// untimed (their pages faulted in). The lines and the order are mapped for
/// the call and unmapped after it, so the allocator's state is left as it
/// was (their pages do count in the process's peak resident memory). Returns
/// the mean nanoseconds a line read after the other thread's fills and after
/// its own, and how many of the other thread's fills ran on another CPU than
/// the read after it (sched_getcpu() at the end of the fill and at the start
/// of the read): where the pool's threads share one CPU (a pinned pool) none
/// do, and the ratio is one core's against itself. Needs pool.threads() >= 2,
/// bytes >= 64, at most 2^32 - 1 lines and rounds >= 1 (else
/// std::invalid_argument; std::bad_alloc if the buffers cannot be mapped);
/// uses the pool, so not from inside one of its parts. Wall-clock times: the
/// host's noise is in them.
///
/// handover_ratio_of(t): t.ratio() where it says something about two cores:
/// nullopt unless the other thread filled at least once, every such fill ran
/// on another CPU than the read after it, and the own reads took time.
///
/// probe_handover_ratio(): the ratio as runs and benchmarks record it: after
/// a pause of twice WorkerPool::poll_us() (a pool that has just worked stops
/// polling), from a pool of two made for the call (the calling thread's
/// affinity), kProbeBytes and kProbeRounds, through handover_ratio_of();
/// nullopt also where fewer than two CPUs are allowed. So no ratio says
/// "shares a cache" when the threads merely shared a core. About 12 ms; maps
/// 4.25 MiB (the lines and their order) for the call.
#include <cstddef>
#include <optional>

#include "sim/parallel/worker_pool.hpp"

namespace tcb {

struct HandoverTimes {
  double own_ns_per_line = 0.0;    ///< read after the calling thread's fills
  double other_ns_per_line = 0.0;  ///< read after the pool's second thread's fills
  int other_fills = 0;             ///< the second thread's fills (= rounds)
  int other_fills_apart = 0;       ///< of those, the ones written on another CPU than the read after them
  /// other over own (0 if own is 0).
  double ratio() const { return own_ns_per_line > 0.0 ? other_ns_per_line / own_ns_per_line : 0.0; }
};

HandoverTimes measure_handover(WorkerPool& pool, std::size_t bytes, int rounds);

/// 4 MiB: beyond a core's L2 (1 MiB here), within the shared cache, where
/// the dog pair's cycle works (its boxes, tets, table and positions: ~8 MiB).
inline constexpr std::size_t kProbeBytes = std::size_t{4} << 20;
inline constexpr int kProbeRounds = 4;

std::optional<double> handover_ratio_of(const HandoverTimes& t);

std::optional<double> probe_handover_ratio();

}  // namespace tcb
