// The timing verdict's rule on synthetic evidence, and the machine readings it
// is built from on synthetic /proc text: no timing is measured here.
#include "experiments/metrics/timing_quality.hpp"

#include <catch2/catch.hpp>

#include "experiments/run/machine_load.hpp"

using namespace tcb;

TEST_CASE("a step is preempted when wall time exceeds CPU time by more than 1 % of the base", "[timing]") {
  CHECK(is_preempted(3.6, 3.5, 3.5));        // 0.1 ms lost > 35 us
  CHECK_FALSE(is_preempted(3.53, 3.5, 3.5));  // 30 us < 35 us
  CHECK_FALSE(is_preempted(3.5, 3.5, 3.5));
  CHECK_FALSE(is_preempted(3.49, 3.5, 3.5));  // CPU above wall (clock resolution): not preempted
  // A tiny base is floored at 10 us: two clocks read apart are no evidence.
  CHECK_FALSE(is_preempted(0.005, 0.0, 0.0));
  CHECK(is_preempted(0.02, 0.0, 0.0));
}

TEST_CASE("the verdict follows its rule: preempted steps and other processes; load is a note", "[timing]") {
  TimingEvidence quiet;
  quiet.steps = 1000;
  quiet.preempted_steps = 10;  // exactly 1 %: still quiet
  quiet.other_busy_cpus = 0.2;
  quiet.cpus = 2;
  quiet.loadavg_start = 1.2;
  quiet.governor = "performance";
  quiet.pinned_cpu = 1;
  const TimingVerdict q = timing_verdict(quiet);
  CHECK_FALSE(q.noisy);
  CHECK(q.reasons.empty());
  CHECK(q.notes.empty());

  TimingEvidence e = quiet;
  e.preempted_steps = 11;
  CHECK(timing_verdict(e).noisy);
  REQUIRE(timing_verdict(e).reasons.size() == 1);
  CHECK_THAT(timing_verdict(e).reasons[0], Catch::Matchers::Contains("1.1 % of steps (11 of 1000)"));

  e = quiet;
  e.other_busy_cpus = 0.3;  // > a quarter of the one CPU the run leaves
  CHECK(timing_verdict(e).noisy);
  e.cpus = 4;  // three spare CPUs: 0.3 busy is fine
  CHECK_FALSE(timing_verdict(e).noisy);
  e.cpus = 1;  // one CPU: any sizeable competitor counts
  CHECK(timing_verdict(e).noisy);

  e = quiet;
  e.loadavg_start = 1.6;  // above cpus - 0.5: a hint (it lags, and counts earlier runs), not evidence
  CHECK_FALSE(timing_verdict(e).noisy);
  REQUIRE(timing_verdict(e).notes.size() == 1);
  CHECK_THAT(timing_verdict(e).notes[0], Catch::Matchers::Contains("load average 1.60"));

  // What cannot be read is a note, never a verdict either way.
  e = quiet;
  e.other_busy_cpus.reset();
  e.loadavg_start.reset();
  e.governor.reset();
  e.pinned_cpu.reset();
  const TimingVerdict unknown = timing_verdict(e);
  CHECK_FALSE(unknown.noisy);
  CHECK(unknown.notes.size() == 3);
  e.governor = "powersave";
  CHECK_THAT(timing_verdict(e).notes[1], Catch::Matchers::Contains("powersave"));

  // The machine's own floor is a note from 1 % of the budget, never a reason.
  e = quiet;
  e.floor_p99_pct = 0.99;
  CHECK(timing_verdict(e).notes.empty());
  e.floor_p99_pct = 14.0;
  CHECK_FALSE(timing_verdict(e).noisy);
  REQUIRE(timing_verdict(e).notes.size() == 1);
  CHECK_THAT(timing_verdict(e).notes[0], Catch::Matchers::Contains("14.00 % at p99"));

  TimingEvidence none;  // a run of 0 steps
  CHECK_FALSE(timing_verdict(none).noisy);
}

TEST_CASE("/proc/stat's cpu line gives busy and total seconds; others' load is ours subtracted", "[timing]") {
  const auto p = parse_proc_stat_cpu_line("cpu  100 5 20 800 10 1 2 3 0 0", 100.0);
  REQUIRE(p);
  CHECK(p->first == Approx((100 + 5 + 20 + 1 + 2 + 3) / 100.0));  // idle and iowait are not busy
  CHECK(p->second == Approx(941 / 100.0));
  CHECK_FALSE(parse_proc_stat_cpu_line("cpu0 1 2 3 4 5 6 7 8", 100.0));  // one CPU's line, not the sum
  CHECK_FALSE(parse_proc_stat_cpu_line("cpu 1 2 3", 100.0));             // truncated
  CHECK_FALSE(parse_proc_stat_cpu_line("cpu 1 2 3 4 5 6 7 8", 0.0));

  MachineSample a, b;
  a.busy_s = 10.0;
  b.busy_s = 13.0;  // 3 CPU-seconds busy over 2 s of wall time
  a.own_cpu_s = 1.0;
  b.own_cpu_s = 2.0;  // 1 of them ours
  a.wall_s = 100.0;
  b.wall_s = 102.0;
  CHECK(*other_busy_cpus(a, b) == Approx(1.0));
  b.own_cpu_s = 5.0;  // tick rounding can put ours above the machine's: never negative
  CHECK(*other_busy_cpus(a, b) == 0.0);
  b.busy_s.reset();
  CHECK_FALSE(other_busy_cpus(a, b));
}
