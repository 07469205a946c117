#include "sim/parallel/worker_pool.hpp"

#include <sched.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <stdexcept>

namespace tcb {
namespace {

// CPUs the calling thread may run on (threads it starts inherit them); 1 if
// they cannot be read.
int allowed_cpu_count() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) != 0) return 1;
  return CPU_COUNT(&set);
}

// Polls done() until it holds or poll_us() has passed; whether it held. The
// clock is read only when the first look fails (a section that is already
// over, or work that has already arrived, costs one load).
template <typename Done>
bool poll_until(const Done& done) {
  if (done()) return true;
  const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(WorkerPool::poll_us());
  for (;;) {
    for (int i = 0; i < 64; ++i) {
      if (done()) return true;
#if defined(__x86_64__) || defined(__i386__)
      __builtin_ia32_pause();  // lets a sibling hyperthread run, and saves power
#endif
    }
    if (std::chrono::steady_clock::now() >= until) return done();
  }
}

}  // namespace

WorkerPool::WorkerPool(int threads) : m_threads(threads), m_errors(threads > 0 ? threads : 1) {
  if (threads < 1) throw std::invalid_argument("a worker pool needs at least one thread");
  m_polls = threads > 1 && allowed_cpu_count() >= threads;
  for (int part = 1; part < threads; ++part) m_workers.emplace_back([this, part] { worker(part); });
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_stop.store(true);
  }
  m_start.notify_all();
  for (std::thread& t : m_workers) t.join();
}

std::pair<std::size_t, std::size_t> WorkerPool::range_of(std::size_t n, int parts, int part) {
  const auto p = static_cast<std::size_t>(parts), k = static_cast<std::size_t>(part);
  const std::size_t base = n / p, extra = n % p;  // the first `extra` parts take one more
  const std::size_t begin = k * base + (k < extra ? k : extra);
  return {begin, begin + base + (k < extra ? 1 : 0)};
}

void WorkerPool::run_part(int part) {
  const auto [begin, end] = range_of(m_n, m_threads, part);
  if (begin == end) return;
  try {
    (*m_function)(part, begin, end);
  } catch (...) {
    m_errors[static_cast<std::size_t>(part)] = std::current_exception();
  }
}

void WorkerPool::worker(int part) {
  std::size_t seen = 0;
  const auto started = [&] { return m_stop.load() || m_generation.load() != seen; };
  for (;;) {
    if (!(m_polls && poll_until(started))) {
      std::unique_lock<std::mutex> lock(m_mutex);
      m_start.wait(lock, started);
    }
    if (m_stop.load()) return;
    seen = m_generation.load();  // m_n and m_function were written before it was bumped
    run_part(part);
    if (m_pending.fetch_sub(1) == 1) {
      // The caller may have checked m_pending under the lock and be about to
      // block: taking the lock before notifying means it is blocked by now.
      { std::lock_guard<std::mutex> lock(m_mutex); }
      m_done.notify_one();
    }
  }
}

void WorkerPool::for_ranges(std::size_t n, const RangeFunction& f) {
  for (std::exception_ptr& e : m_errors) e = nullptr;
  m_n = n;
  m_function = &f;
  if (m_threads > 1) {
    m_pending.store(m_threads - 1);
    {
      std::lock_guard<std::mutex> lock(m_mutex);
      m_generation.fetch_add(1);
    }
    m_start.notify_all();
  }
  run_part(0);
  if (m_threads > 1) {
    const auto finished = [&] { return m_pending.load() == 0; };
    if (!(m_polls && poll_until(finished))) {
      std::unique_lock<std::mutex> lock(m_mutex);
      m_done.wait(lock, finished);
    }
  }
  m_function = nullptr;
  for (const std::exception_ptr& e : m_errors)
    if (e) std::rethrow_exception(e);
}

void WorkerPool::for_chunks(std::size_t n, std::size_t chunk, const RangeFunction& f) {
  if (chunk == 0) throw std::invalid_argument("for_chunks needs chunks of at least one index");
  const std::size_t chunks = (n + chunk - 1) / chunk;
  std::atomic<std::size_t> next{0};
  std::vector<std::size_t> failed_chunk(static_cast<std::size_t>(m_threads), chunks);
  std::vector<std::exception_ptr> failed(static_cast<std::size_t>(m_threads));
  for_ranges(static_cast<std::size_t>(m_threads), [&](int part, std::size_t, std::size_t) {
    const auto p = static_cast<std::size_t>(part);
    for (std::size_t c = next.fetch_add(1); c < chunks; c = next.fetch_add(1)) {
      try {
        f(part, c * chunk, std::min(n, (c + 1) * chunk));
      } catch (...) {
        failed_chunk[p] = c;
        failed[p] = std::current_exception();
        next = chunks;  // start no new chunk: every chunk below c is already taken
        return;
      }
    }
  });
  std::size_t first = 0;
  for (std::size_t p = 1; p < failed.size(); ++p)
    if (failed_chunk[p] < failed_chunk[first]) first = p;
  if (failed[first]) std::rethrow_exception(failed[first]);
}

}  // namespace tcb
