#pragma once
/// A fixed set of threads that run one function over index ranges and wait
/// for it: the collision cycle's parallel tet and surface hashing, point
/// queries, border depths and forces (collision.threads). Threads inherit the
/// creating thread's CPU affinity, so a pool started on a pinned thread
/// shares its CPU. Plain std::thread, not TBB: the work is one flat loop,
/// with nothing to nest. for_ranges() splits it into static ranges, one a
/// thread (the hash builds need each thread's range contiguous and in
/// order); for_chunks() hands out small chunks as threads come free, for
/// loops whose items differ in cost. Results are written per index, so they
/// never depend on the split.
///
/// Contract: threads >= 1; a pool of 1 runs everything on the caller's thread
/// and starts none. for_ranges(n, f) calls f(part, begin, end) for part
/// 0 .. threads()-1 over [0, n) split into contiguous ranges whose sizes differ
/// by at most one (part 0, the lowest indices, on the caller's thread; empty
/// ranges are skipped), and returns when every call has returned. f must be
/// safe to run concurrently on disjoint ranges. An exception thrown by f is
/// rethrown by for_ranges after all parts finished (the lowest part's, if
/// several threw). One for_ranges at a time; not reentrant from inside f.
///
/// Hand-off: a worker that finished a part, and the caller waiting for the
/// workers, poll for up to poll_us() before they block on a condition
/// variable. An empty for_ranges took 100-150 us on this 2-vCPU host while
/// both the worker and the caller slept in between (measured before they
/// polled); micro_worker_pool gives 81 us a call once the worker has
/// blocked, 0.8 us while it polls. A 2-thread dog-pair cycle starts 8-10
/// parallel sections. The poll burns at most poll_us() of a core after each
/// section, on a pool a user asked for with --threads. A pool of 1 has no
/// workers; a pool whose threads may run on fewer CPUs than it has threads
/// (--pin gives all of them one CPU) never polls, since the poller would
/// hold the CPU the thread it waits for needs.
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace tcb {

class WorkerPool {
 public:
  using RangeFunction = std::function<void(int part, std::size_t begin, std::size_t end)>;

  /// How long a thread polls before it blocks (microseconds).
  static constexpr int poll_us() { return 1000; }

  explicit WorkerPool(int threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int threads() const { return m_threads; }
  /// Whether its threads poll before blocking (see the file comment).
  bool polls() const { return m_polls; }
  void for_ranges(std::size_t n, const RangeFunction& f);
  /// f(part, begin, end) over [0, n) in chunks of `chunk` indices (the last
  /// may be shorter), each thread taking the next chunk when it finishes one:
  /// for loops whose items differ in cost (a colliding point costs far more
  /// than a free one), where static ranges leave one thread idle. `part`
  /// names the calling thread (for its scratch), not a fixed range, so f must
  /// write its results per index. chunk >= 1 (else std::invalid_argument).
  /// An exception is rethrown after all threads stopped: the one of the
  /// lowest chunk, i.e. the one a serial loop over [0, n) would have met
  /// first. After a failure no new chunk is started; chunks already taken
  /// run to their end (or their own exception).
  void for_chunks(std::size_t n, std::size_t chunk, const RangeFunction& f);

  /// [begin, end) of `part` when n indices are split over `parts` (exposed for tests).
  static std::pair<std::size_t, std::size_t> range_of(std::size_t n, int parts, int part);

 private:
  void worker(int part);
  void run_part(int part);

  int m_threads;
  bool m_polls = false;
  std::vector<std::thread> m_workers;
  std::mutex m_mutex;
  std::condition_variable m_start, m_done;
  // Bumped per for_ranges (under m_mutex, for blocked workers): a worker
  // runs each generation once. Atomic so that polling threads may read it.
  std::atomic<std::size_t> m_generation{0};
  std::atomic<int> m_pending{0};  // workers still running the current generation
  std::atomic<bool> m_stop{false};
  std::size_t m_n = 0;
  const RangeFunction* m_function = nullptr;
  std::vector<std::exception_ptr> m_errors;  // per part
};

}  // namespace tcb
