#include "sim/parallel/core_handover.hpp"

#include <catch2/catch.hpp>
#include <pthread.h>
#include <sched.h>

#include <cmath>
#include <stdexcept>
#include <vector>

using namespace tcb;

namespace {

// The CPUs this thread may run on.
std::vector<int> allowed() {
  cpu_set_t set;
  CPU_ZERO(&set);
  std::vector<int> out;
  if (pthread_getaffinity_np(pthread_self(), sizeof set, &set) != 0) return out;
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &set)) out.push_back(c);
  return out;
}

// Sets the calling thread's affinity to `cpus`.
bool set_affinity(const std::vector<int>& cpus) {
  cpu_set_t set;
  CPU_ZERO(&set);
  for (const int c : cpus) CPU_SET(c, &set);
  return pthread_setaffinity_np(pthread_self(), sizeof set, &set) == 0;
}

}  // namespace

TEST_CASE("measure_handover refuses what it cannot measure", "[core_handover]") {
  WorkerPool one(1), two(2);
  CHECK_THROWS_AS(measure_handover(one, 1 << 16, 1), std::invalid_argument);  // no second thread to write
  CHECK_THROWS_AS(measure_handover(two, 0, 1), std::invalid_argument);
  CHECK_THROWS_AS(measure_handover(two, 63, 1), std::invalid_argument);  // not one whole line
  CHECK_THROWS_AS(measure_handover(two, 1 << 16, 0), std::invalid_argument);
  CHECK_THROWS_AS(measure_handover(two, 1 << 16, -1), std::invalid_argument);
}

TEST_CASE("measure_handover times both reads on pools of two and more", "[core_handover]") {
  // Times only, so nothing about their sizes is asserted (a shared machine):
  // both reads were timed (positive, finite), every round filled once by the
  // other thread, and the pool still runs every part afterwards.
  for (const int threads : {2, 3}) {
    WorkerPool pool(threads);
    for (const std::size_t bytes : {std::size_t(64), std::size_t(100), std::size_t(1) << 16}) {
      INFO("threads " << threads << ", bytes " << bytes);
      const HandoverTimes t = measure_handover(pool, bytes, 3);
      CHECK(std::isfinite(t.own_ns_per_line));
      CHECK(std::isfinite(t.other_ns_per_line));
      CHECK(t.own_ns_per_line > 0.0);
      CHECK(t.other_ns_per_line > 0.0);
      CHECK(t.other_fills == 3);
      CHECK(t.other_fills_apart >= 0);
      CHECK(t.other_fills_apart <= 3);
    }
    std::vector<int> ran(static_cast<std::size_t>(threads), 0);
    pool.for_ranges(static_cast<std::size_t>(threads), [&](int part, std::size_t, std::size_t) { ++ran[part]; });
    CHECK(ran == std::vector<int>(static_cast<std::size_t>(threads), 1));
  }
  CHECK(HandoverTimes{2.0, 5.0, 0, 0}.ratio() == 2.5);  // other over own
  CHECK(HandoverTimes{}.ratio() == 0.0);                 // nothing measured: no ratio, not a division by zero
}

TEST_CASE("the other fills are the second thread's, on its CPU; a pinned pool has no other CPU", "[core_handover]") {
  const std::vector<int> cpus = allowed();
  if (cpus.size() < 2) {
    WARN("needs two CPUs; " << cpus.size() << " allowed");
    return;
  }
  SECTION("caller and worker pinned to two CPUs: every other fill written on the worker's") {
    WorkerPool pool(2);
    bool pinned = true;
    // Each thread pins itself: part 0 (this thread) to one CPU, part 1 to the other.
    pool.for_ranges(2, [&](int part, std::size_t, std::size_t) {
      if (!set_affinity({cpus[static_cast<std::size_t>(part)]})) pinned = false;
    });
    REQUIRE(pinned);
    const HandoverTimes t = measure_handover(pool, 1 << 16, 4);
    pool.for_ranges(2, [&](int, std::size_t, std::size_t) { set_affinity(cpus); });  // both threads freed again
    CHECK(t.other_fills == 4);
    CHECK(t.other_fills_apart == 4);
  }
  SECTION("a pool made on a pinned thread shares its CPU: no fill apart, and no ratio probed") {
    REQUIRE(set_affinity({cpus[0]}));
    std::optional<double> probed;
    HandoverTimes t;
    {
      WorkerPool pool(2);  // its worker inherits the pin
      t = measure_handover(pool, 1 << 16, 2);
      probed = probe_handover_ratio();
    }
    set_affinity(cpus);
    CHECK(t.other_fills == 2);
    CHECK(t.other_fills_apart == 0);
    CHECK_FALSE(probed.has_value());
  }
  SECTION("unpinned, the probe gives a positive ratio or, if the scheduler put both threads on one CPU, none") {
    const std::optional<double> ratio = probe_handover_ratio();
    if (ratio) CHECK(*ratio > 0.0);
  }
}
