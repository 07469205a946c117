#include "sim/parallel/worker_pool.hpp"

#include <catch2/catch.hpp>
#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

using namespace tcb;

namespace {

// Ends the test binary with a failure if the test case it guards has not
// finished after `seconds`: a lost wake-up or a missed stop in the pool
// hangs rather than failing, and ctest sets no time limit on these tests.
class Watchdog {
 public:
  explicit Watchdog(int seconds)
      : m_thread([this, seconds] {
          std::unique_lock<std::mutex> lock(m_mutex);
          if (!m_finished.wait_for(lock, std::chrono::seconds(seconds), [this] { return m_done; })) {
            std::fprintf(stderr, "worker pool test still running after %d s: a lost wake-up or a missed stop\n",
                         seconds);
            std::_Exit(1);
          }
        }) {}
  ~Watchdog() {
    {
      std::lock_guard<std::mutex> lock(m_mutex);
      m_done = true;
    }
    m_finished.notify_one();
    m_thread.join();
  }
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;

 private:
  std::mutex m_mutex;
  std::condition_variable m_finished;
  bool m_done = false;
  std::thread m_thread;  // last: starts once the members it reads exist
};

}  // namespace

TEST_CASE("worker pool ranges cover every index once, contiguous and balanced", "[worker_pool]") {
  for (int parts : {1, 2, 3, 7})
    for (std::size_t n : {0, 1, 2, 6, 7, 1000, 1001}) {
      std::size_t next = 0;
      for (int part = 0; part < parts; ++part) {
        const auto [begin, end] = WorkerPool::range_of(n, parts, part);
        REQUIRE(begin == next);
        REQUIRE(end - begin <= n / parts + 1);
        REQUIRE(end - begin >= n / parts);
        next = end;
      }
      REQUIRE(next == n);
    }
}

TEST_CASE("worker pool runs every index once, on several threads, and can be reused", "[worker_pool]") {
  const Watchdog watchdog(60);
  for (int threads : {1, 2, 4}) {
    WorkerPool pool(threads);
    for (int round = 0; round < 50; ++round) {
      const std::size_t n = 37 + static_cast<std::size_t>(round) * 13;
      std::vector<int> hits(n, 0);
      std::vector<std::thread::id> who(static_cast<std::size_t>(threads));
      pool.for_ranges(n, [&](int part, std::size_t begin, std::size_t end) {
        who[static_cast<std::size_t>(part)] = std::this_thread::get_id();
        for (std::size_t i = begin; i < end; ++i) ++hits[i];
      });
      for (int h : hits) REQUIRE(h == 1);
      // Part 0 is the caller's; the others are the pool's own threads.
      REQUIRE(who[0] == std::this_thread::get_id());
      for (int part = 1; part < threads; ++part) REQUIRE(who[static_cast<std::size_t>(part)] != who[0]);
    }
  }
}

TEST_CASE("worker pool rethrows the lowest failing part's exception after all parts ran", "[worker_pool]") {
  const Watchdog watchdog(60);
  WorkerPool pool(3);
  std::atomic<int> ran{0};
  try {
    pool.for_ranges(30, [&](int part, std::size_t, std::size_t) {
      ++ran;
      if (part >= 1) throw std::runtime_error("part " + std::to_string(part));
    });
    FAIL("no exception");
  } catch (const std::runtime_error& e) {
    CHECK(std::string(e.what()) == "part 1");
  }
  CHECK(ran == 3);
  // Still usable afterwards.
  std::atomic<std::size_t> sum{0};
  pool.for_ranges(10, [&](int, std::size_t b, std::size_t e) { sum += e - b; });
  CHECK(sum == 10);
  CHECK_THROWS_AS(WorkerPool(0), std::invalid_argument);
}

TEST_CASE("worker pool chunks cover every index once, each chunk whole, and rethrow the lowest chunk's exception",
          "[worker_pool]") {
  const Watchdog watchdog(60);
  for (int threads : {1, 2, 3}) {
    WorkerPool pool(threads);
    for (std::size_t chunk : {1, 5, 16})
      for (std::size_t n : {0, 1, 15, 16, 17, 1000}) {
        // Recorded on the threads (one slot an index), checked afterwards:
        // Catch's assertions are not thread-safe.
        std::vector<int> hits(n, 0), part_of(n, -1);
        std::vector<std::size_t> begin_of(n, 0), end_of(n, 0);
        std::atomic<int> calls{0};
        pool.for_chunks(n, chunk, [&](int part, std::size_t begin, std::size_t end) {
          ++calls;
          for (std::size_t i = begin; i < end; ++i) {
            ++hits[i];
            part_of[i] = part;
            begin_of[i] = begin;
            end_of[i] = end;
          }
        });
        for (std::size_t i = 0; i < n; ++i) {
          REQUIRE(hits[i] == 1);
          REQUIRE(part_of[i] >= 0);
          REQUIRE(part_of[i] < threads);
          // Index i's chunk is [c * chunk, min(n, (c + 1) * chunk)), c = i / chunk.
          REQUIRE(begin_of[i] == i / chunk * chunk);
          REQUIRE(end_of[i] == std::min(n, begin_of[i] + chunk));
        }
        REQUIRE(static_cast<std::size_t>(calls) == (n + chunk - 1) / chunk);
      }
    // Indices 40 and 95 fail; a serial loop meets 40 first, whichever thread
    // ran its chunk and in whatever order the chunks were taken.
    for (int round = 0; round < 20; ++round) {
      try {
        pool.for_chunks(200, 10, [&](int, std::size_t begin, std::size_t end) {
          for (std::size_t i = begin; i < end; ++i)
            if (i == 40 || i == 95) {
              // The lower failure comes last in time, on whichever thread.
              if (i == 40 && threads > 1) std::this_thread::sleep_for(std::chrono::milliseconds(5));
              throw std::runtime_error("index " + std::to_string(i));
            }
        });
        FAIL("no exception");
      } catch (const std::runtime_error& e) {
        REQUIRE(std::string(e.what()) == "index 40");
      }
    }
    CHECK_THROWS_AS(pool.for_chunks(10, 0, [](int, std::size_t, std::size_t) {}), std::invalid_argument);
  }
}

TEST_CASE("worker pool hands work over whether its threads poll or block", "[worker_pool]") {
  const Watchdog watchdog(60);
  // Each call writes plain (non-atomic) values on every thread and reads
  // them after the call: the hand-off must publish them both ways. Gaps of
  // 0, a fifth of and twice poll_us() between calls reach a worker while it
  // polls and after it blocked; a part that outlasts poll_us() makes the
  // caller block and be woken (a lost wake-up hangs here).
  const auto poll = std::chrono::microseconds(WorkerPool::poll_us());
  const auto wait = [](std::chrono::microseconds d) {
    const auto until = std::chrono::steady_clock::now() + d;
    while (std::chrono::steady_clock::now() < until) {
    }
  };
  for (int threads : {2, 3}) {
    WorkerPool pool(threads);
    const std::chrono::microseconds gaps[] = {std::chrono::microseconds(0), poll / 5, 2 * poll};
    for (int round = 0; round < 30; ++round) {
      const auto gap = gaps[round % 3];
      const bool slow_worker = round % 5 == 4, slow_caller = round % 7 == 6;
      wait(gap);
      std::vector<std::size_t> value(64, 0);
      std::vector<std::thread::id> who(static_cast<std::size_t>(threads));
      pool.for_ranges(value.size(), [&](int part, std::size_t begin, std::size_t end) {
        who[static_cast<std::size_t>(part)] = std::this_thread::get_id();
        if ((part == threads - 1 && slow_worker) || (part == 0 && slow_caller)) wait(2 * poll);
        for (std::size_t i = begin; i < end; ++i) value[i] = i * 3 + static_cast<std::size_t>(round);
      });
      for (std::size_t i = 0; i < value.size(); ++i) REQUIRE(value[i] == i * 3 + static_cast<std::size_t>(round));
      for (int part = 1; part < threads; ++part) REQUIRE(who[static_cast<std::size_t>(part)] != who[0]);
    }
  }
}

TEST_CASE("worker pool stops whether its workers poll or block", "[worker_pool]") {
  const Watchdog watchdog(60);
  // Destroyed right after a call (the workers still poll) and after they
  // blocked; a worker that misses the stop hangs the join here.
  for (const int gap_us : {0, 3 * WorkerPool::poll_us()}) {
    WorkerPool pool(2);
    std::atomic<int> ran{0};
    pool.for_ranges(2, [&](int, std::size_t, std::size_t) { ++ran; });
    std::this_thread::sleep_for(std::chrono::microseconds(gap_us));
    CHECK(ran == 2);
  }
}

TEST_CASE("worker pool polls only with a CPU a thread", "[worker_pool]") {
  // A pool of one has no worker to poll for. A pool started on a thread
  // pinned to one CPU shares that CPU, where a poller would hold the CPU the
  // thread it waits for needs: it must block instead.
  CHECK_FALSE(WorkerPool(1).polls());
  cpu_set_t saved;
  CPU_ZERO(&saved);
  REQUIRE(pthread_getaffinity_np(pthread_self(), sizeof saved, &saved) == 0);
  int first = 0;
  while (!CPU_ISSET(first, &saved)) ++first;
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(first, &one);
  REQUIRE(pthread_setaffinity_np(pthread_self(), sizeof one, &one) == 0);
  const bool pinned_polls = WorkerPool(2).polls();
  pthread_setaffinity_np(pthread_self(), sizeof saved, &saved);
  CHECK_FALSE(pinned_polls);
  if (CPU_COUNT(&saved) >= 2) CHECK(WorkerPool(2).polls());
}
