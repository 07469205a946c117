#pragma once
/// A fixed set of threads that run one function over contiguous index ranges
/// and wait for it: the collision cycle's parallel tet hashing, point
/// queries and border depths (collision.threads). Threads inherit the creating thread's CPU affinity, so
/// a pool started on a pinned thread shares its CPU. Plain std::thread, not TBB: the work is one
/// flat loop split into as many static ranges as threads, with nothing to
/// steal or nest, and static ranges make it plain which thread did which index
/// (results are written per index, so they never depend on the split).
///
/// Contract: threads >= 1; a pool of 1 runs everything on the caller's thread
/// and starts none. for_ranges(n, f) calls f(part, begin, end) for part
/// 0 .. threads()-1 over [0, n) split into contiguous ranges whose sizes differ
/// by at most one (part 0, the lowest indices, on the caller's thread; empty
/// ranges are skipped), and returns when every call has returned. f must be
/// safe to run concurrently on disjoint ranges. An exception thrown by f is
/// rethrown by for_ranges after all parts finished (the lowest part's, if
/// several threw). One for_ranges at a time; not reentrant from inside f.

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

  explicit WorkerPool(int threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int threads() const { return m_threads; }
  void for_ranges(std::size_t n, const RangeFunction& f);

  /// [begin, end) of `part` when n indices are split over `parts` (exposed for tests).
  static std::pair<std::size_t, std::size_t> range_of(std::size_t n, int parts, int part);

 private:
  void worker(int part);
  void run_part(int part);

  int m_threads;
  std::vector<std::thread> m_workers;
  std::mutex m_mutex;
  std::condition_variable m_start, m_done;
  std::size_t m_generation = 0;  // bumped per for_ranges: a worker runs each generation once
  int m_pending = 0;             // workers still running the current generation
  bool m_stop = false;
  std::size_t m_n = 0;
  const RangeFunction* m_function = nullptr;
  std::vector<std::exception_ptr> m_errors;  // per part
};

}  // namespace tcb
