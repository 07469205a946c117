#include "sim/parallel/core_handover.hpp"

#include <sched.h>
#include <sys/mman.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <new>
#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

namespace tcb {

namespace {

struct alignas(64) Line {
  std::uint64_t value = 0;
};

// The lines, mapped for one call and unmapped after it: a 4 MiB vector
// would be mmapped by glibc too, but freeing it raises glibc's mmap
// threshold for the rest of the process (a run's later allocations would
// then come from the heap where a run without the probe maps them).
class MappedLines {
 public:
  explicit MappedLines(std::size_t count) : m_count(count) {
    void* p = mmap(nullptr, count * sizeof(Line), PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
    m_lines = static_cast<Line*>(p);
  }
  ~MappedLines() { munmap(m_lines, m_count * sizeof(Line)); }
  MappedLines(const MappedLines&) = delete;
  MappedLines& operator=(const MappedLines&) = delete;
  Line* begin() { return m_lines; }
  Line* end() { return m_lines + m_count; }
  const Line& operator[](std::size_t i) const { return m_lines[i]; }

 private:
  Line* m_lines = nullptr;
  std::size_t m_count;
};

}  // namespace

HandoverTimes measure_handover(WorkerPool& pool, std::size_t bytes, int rounds) {
  if (pool.threads() < 2) throw std::invalid_argument("measure_handover needs a pool of at least two threads");
  if (bytes < sizeof(Line)) throw std::invalid_argument("measure_handover needs at least one 64-byte line");
  if (rounds < 1) throw std::invalid_argument("measure_handover needs at least one round");
  const std::size_t count = bytes / sizeof(Line);
  MappedLines lines(count);
  // Every line once, in an order no prefetcher follows (fixed seed: the same
  // order in every call); read from a sequential array, not computed in
  // the timed loop.
  std::vector<std::uint32_t> order(count);
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin(), order.end(), std::mt19937(14));
  HandoverTimes out;
  double own_s = 0.0, other_s = 0.0;
  std::uint64_t stamp = 0, sum = 0;
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
      for (const std::uint32_t i : order) sum += lines[i].value;
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

std::optional<double> probe_handover_ratio() {
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof allowed, &allowed) != 0 || CPU_COUNT(&allowed) < 2) return std::nullopt;
  WorkerPool pool(2);
  const HandoverTimes t = measure_handover(pool, kProbeBytes, kProbeRounds);
  if (t.other_fills_apart < t.other_fills) return std::nullopt;
  return t.ratio();
}

}  // namespace tcb
