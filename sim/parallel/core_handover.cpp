#include "sim/parallel/core_handover.hpp"

#include <sched.h>
#include <sys/mman.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <limits>
#include <new>
#include <numeric>
#include <random>
#include <stdexcept>
#include <thread>

namespace tcb {

namespace {

struct alignas(64) Line {
  std::uint64_t value = 0;
};

// `count` values of T (trivial, zero-initialised by the kernel), mapped for
// one call and unmapped after it: a vector of a few hundred KiB or more
// would be mmapped by glibc too, but freeing it raises glibc's mmap
// threshold for the rest of the process (a run's later allocations would
// then come from the heap where a run without the probe maps them).
template <typename T>
class Mapped {
 public:
  explicit Mapped(std::size_t count) : m_count(count) {
    void* p = mmap(nullptr, count * sizeof(T), PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
    m_data = static_cast<T*>(p);
  }
  ~Mapped() { munmap(m_data, m_count * sizeof(T)); }
  Mapped(const Mapped&) = delete;
  Mapped& operator=(const Mapped&) = delete;
  T* begin() { return m_data; }
  T* end() { return m_data + m_count; }
  const T* begin() const { return m_data; }
  const T* end() const { return m_data + m_count; }
  const T& operator[](std::size_t i) const { return m_data[i]; }

 private:
  T* m_data = nullptr;
  std::size_t m_count;
};

}  // namespace

HandoverTimes measure_handover(WorkerPool& pool, std::size_t bytes, int rounds) {
  if (pool.threads() < 2) throw std::invalid_argument("measure_handover needs a pool of at least two threads");
  if (bytes < sizeof(Line)) throw std::invalid_argument("measure_handover needs at least one 64-byte line");
  if (bytes / sizeof(Line) > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("measure_handover takes at most 2^32 - 1 lines");
  if (rounds < 1) throw std::invalid_argument("measure_handover needs at least one round");
  const std::size_t count = bytes / sizeof(Line);
  Mapped<Line> lines(count);
  // Every line once, in an order no prefetcher follows (fixed seed: the same
  // order in every call); read from a sequential array, not computed in
  // the timed loop.
  Mapped<std::uint32_t> order(count);
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin(), order.end(), std::mt19937(14));
  std::uint64_t stamp = 0, sum = 0;
  const auto read_all = [&] {
    for (const std::uint32_t i : order) sum += lines[i].value;
  };
  // An untimed fill and read by the calling thread first: the pages are
  // faulted in and in its TLB before any timed read, so the first timed
  // read (always after the other thread's fill) pays no more than the rest.
  ++stamp;
  for (Line& line : lines) line.value = stamp;
  read_all();
  HandoverTimes out;
  double own_s = 0.0, other_s = 0.0;
  for (int round = 0; round < rounds; ++round)
    for (int k = 0; k < 2; ++k) {
      const bool other = (round + k) % 2 == 0;
      ++stamp;  // a new value every fill: each line written, not left as it was
      int writer_cpu = -1;
      pool.for_ranges(2, [&](int part, std::size_t, std::size_t) {
        if ((part == 1) != other) return;  // part 0 is the calling thread
        for (Line& line : lines) line.value = stamp;
        writer_cpu = sched_getcpu();
      });
      const int reader_cpu = sched_getcpu();
      const auto start = std::chrono::steady_clock::now();
      read_all();
      (other ? other_s : own_s) += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (other) {
        ++out.other_fills;
        out.other_fills_apart += writer_cpu != reader_cpu ? 1 : 0;
      }
    }
  // Stored, so the reads are not optimized away (the value itself means nothing).
  volatile std::uint64_t sink = sum;
  static_cast<void>(sink);
  const double reads = static_cast<double>(rounds) * static_cast<double>(count);
  out.own_ns_per_line = 1e9 * own_s / reads;
  out.other_ns_per_line = 1e9 * other_s / reads;
  return out;
}

std::optional<double> handover_ratio_of(const HandoverTimes& t) {
  if (t.other_fills < 1 || t.other_fills_apart < t.other_fills || !(t.own_ns_per_line > 0.0)) return std::nullopt;
  return t.ratio();
}

std::optional<double> probe_handover_ratio() {
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof allowed, &allowed) != 0 || CPU_COUNT(&allowed) < 2) return std::nullopt;
  // A pool that has just finished a parallel section polls for up to
  // poll_us() (a run's handler's, a benchmark's 2-thread cycle's): let it
  // block first, so it takes no CPU from the probe.
  std::this_thread::sleep_for(std::chrono::microseconds(2 * WorkerPool::poll_us()));
  WorkerPool pool(2);
  return handover_ratio_of(measure_handover(pool, kProbeBytes, kProbeRounds));
}

}  // namespace tcb
