#include "sim/parallel/core_handover.hpp"

#include <catch2/catch.hpp>
#include <pthread.h>
#include <sched.h>

#include <atomic>
#include <cmath>
#include <optional>
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

// Gives the calling thread `cpus` back when it leaves scope, a failed
// REQUIRE or a throw too: the rest of the suite must not run pinned.
struct RestoreAffinity {
  std::vector<int> cpus;
  ~RestoreAffinity() { set_affinity(cpus); }
};

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
      // One line's read may fall within one tick of a coarse clock (100 ns
      // on some hypervisors); 1024 lines' reads cannot.
      CHECK(t.own_ns_per_line >= 0.0);
      CHECK(t.other_ns_per_line >= 0.0);
      if (bytes >= 1 << 16) {
        CHECK(t.own_ns_per_line > 0.0);
        CHECK(t.other_ns_per_line > 0.0);
      }
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

TEST_CASE("handover_ratio_of gives a ratio only where every other fill ran on another CPU", "[core_handover]") {
  CHECK(handover_ratio_of({2.0, 5.0, 4, 4}) == 2.5);
  CHECK_FALSE(handover_ratio_of({2.0, 5.0, 4, 3}).has_value());  // one fill on the reader's CPU
  CHECK_FALSE(handover_ratio_of({2.0, 5.0, 4, 0}).has_value());  // a pinned pool: one core against itself
  CHECK_FALSE(handover_ratio_of({2.0, 5.0, 0, 0}).has_value());  // no fill by the other thread
  CHECK_FALSE(handover_ratio_of({0.0, 5.0, 4, 4}).has_value());  // own reads too quick to time: no ratio, not 0
}

TEST_CASE("the other fills are the second thread's, on its CPU; a pinned pool has no other CPU", "[core_handover]") {
  const std::vector<int> cpus = allowed();
  if (cpus.size() < 2) {
    WARN("needs two CPUs; " << cpus.size() << " allowed");
    return;
  }
  const RestoreAffinity restore{cpus};
  SECTION("caller and worker pinned to two CPUs: every other fill written on the worker's") {
    WorkerPool pool(2);  // its worker dies with it, pinned or not
    std::atomic<int> pinned{0};
    // Each thread pins itself: part 0 (this thread) to one CPU, part 1 to the other.
    pool.for_ranges(2, [&](int part, std::size_t, std::size_t) {
      if (set_affinity({cpus[static_cast<std::size_t>(part)]})) ++pinned;
    });
    REQUIRE(pinned == 2);
    const HandoverTimes t = measure_handover(pool, 1 << 16, 4);
    CHECK(t.other_fills == 4);
    CHECK(t.other_fills_apart == 4);
    CHECK(handover_ratio_of(t).has_value());
  }
  SECTION("a pool made on a pinned thread shares its CPU: no fill apart, and no ratio probed") {
    REQUIRE(set_affinity({cpus[0]}));
    WorkerPool pool(2);  // its worker inherits the pin
    const HandoverTimes t = measure_handover(pool, 1 << 16, 2);
    CHECK(t.other_fills == 2);
    CHECK(t.other_fills_apart == 0);
    CHECK_FALSE(handover_ratio_of(t).has_value());
    CHECK_FALSE(probe_handover_ratio().has_value());
  }
  SECTION("unpinned, the probe gives a positive ratio or, if the scheduler put both threads on one CPU, none") {
    const std::optional<double> ratio = probe_handover_ratio();
    if (ratio) CHECK(*ratio > 0.0);
  }
}
