"""The granularity claim judges wall-clock overshoot on quiet runs only: a noisy run is shown with its
CPU-time overshoot and decides nothing (issue: whose overshoot is it). Run by ctest with /usr/bin/python3."""
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

from tcbench_report.claims import FAILS, HOLDS, INCONCLUSIVE, worst_overshoot  # noqa: E402
from tcbench_report.loader import Run  # noqa: E402


def run(name, wall_p99, cpu_p99, verdict, floor_p99=None):
    summary = {"overshoot_pct": {"p99": wall_p99}, "overshoot_cpu_pct": {"p99": cpu_p99}}
    if verdict:
        summary["timing"] = {"verdict": verdict}
        if floor_p99 is not None:
            summary["timing"]["floor"] = {"windows": 300, "overshoot_pct": {"p99": floor_p99}}
    return Run("/nonexistent", {"summary": summary, "budget": {"kind": "wall_ms"}}, name)


class GranularityClaim(unittest.TestCase):
    def test_quiet_runs_decide(self):
        measured, verdict = worst_overshoot([run("a", 3.0, 2.9, "quiet"), run("b", 4.0, 3.8, "quiet")], None)
        self.assertEqual(verdict, HOLDS)
        self.assertIn("4.0 %", measured)
        _, verdict = worst_overshoot([run("a", 3.0, 2.9, "quiet"), run("b", 7.0, 6.5, "quiet")], None)
        self.assertEqual(verdict, FAILS)

    def test_a_noisy_run_is_inconclusive_not_failed(self):
        # 120 % on the wall clock, 8 % of it the method's own: the machine's overshoot.
        measured, verdict = worst_overshoot([run("a", 3.0, 2.9, "quiet"), run("loaded", 120.0, 8.0, "noisy")], None)
        self.assertTrue(verdict.startswith(HOLDS))
        self.assertIn(INCONCLUSIVE, verdict)
        self.assertIn("120.0 %", measured)  # both numbers shown
        self.assertIn("8.0 %", measured)

    def test_only_noisy_runs(self):
        measured, verdict = worst_overshoot([run("loaded", 120.0, 8.0, "noisy")], None)
        self.assertEqual(verdict, f"{INCONCLUSIVE}: measured on a noisy machine (CPU-time overshoot 8.0 %)")

    def test_the_overshoot_is_also_given_in_microseconds(self):
        r = run("a", 3.0, 2.9, "quiet")
        r.summary["overshoot_us"] = {"p99": 107.0}
        measured, _ = worst_overshoot([r], None)
        self.assertIn("3.0 % = 107 us", measured)

    def test_runs_before_the_verdict_are_judged_as_before(self):
        _, verdict = worst_overshoot([run("old", 4.0, None, None)], None)
        self.assertEqual(verdict, HOLDS)

    def test_a_run_within_its_machine_floor_is_inconclusive(self):
        # The null handler beside it overshot 14 % by itself; the run's 12 % shows neither a hold nor a miss.
        measured, verdict = worst_overshoot([run("haptic", 12.0, 9.0, "quiet", floor_p99=14.0)], None)
        self.assertTrue(verdict.startswith(INCONCLUSIVE), verdict)
        self.assertIn("14.0 %", verdict)
        self.assertIn("machine floor p99 up to 14.0 %", measured)

    def test_a_run_over_floor_plus_threshold_fails_whatever_the_floor(self):
        # 1040 % over a 6 % floor: the method's own part exceeds 5 % even crediting the whole floor.
        self.assertEqual(worst_overshoot([run("paper", 1040.0, 1000.0, "quiet", floor_p99=6.0)], None)[1], FAILS)
        # At floor + threshold it fails; just within it, it does not decide.
        self.assertEqual(worst_overshoot([run("x", 11.0, 11.0, "quiet", floor_p99=6.0)], None)[1], FAILS)
        self.assertTrue(worst_overshoot([run("x", 10.5, 10.0, "quiet", floor_p99=6.0)], None)[1]
                        .startswith(INCONCLUSIVE))

    def test_the_same_line_whatever_the_floor(self):
        # 9 % over floors of 4.9 % and 5.0 % both decide nothing (the rule has no step at the threshold) ...
        for floor in (4.9, 5.0):
            self.assertTrue(worst_overshoot([run("x", 9.0, 9.0, "quiet", floor_p99=floor)], None)[1]
                            .startswith(INCONCLUSIVE))
        # ... a run under the threshold holds whatever its floor ...
        self.assertEqual(worst_overshoot([run("a", 3.0, 2.9, "quiet", floor_p99=14.0)], None)[1], HOLDS)
        # ... and a small floor leaves a clear miss a miss.
        self.assertEqual(worst_overshoot([run("a", 7.0, 6.5, "quiet", floor_p99=0.5)], None)[1], FAILS)

    def test_the_runs_the_machine_could_judge_decide(self):
        _, verdict = worst_overshoot([run("a", 3.0, 2.9, "quiet", floor_p99=0.5),
                                      run("b", 9.0, 8.0, "quiet", floor_p99=7.0),
                                      run("loaded", 120.0, 8.0, "noisy")], None)
        self.assertTrue(verdict.startswith(HOLDS), verdict)
        self.assertIn(f"1 run {INCONCLUSIVE} (over by no more than the machine floor); 1 run {INCONCLUSIVE} "
                      "(noisy machine)", verdict)
        _, verdict = worst_overshoot([run("a", 3.0, 2.9, "quiet"), run("b", 9.0, 8.0, "quiet", floor_p99=7.0),
                                      run("c", 30.0, 29.0, "quiet", floor_p99=7.0)], None)
        self.assertTrue(verdict.startswith(FAILS), verdict)

if __name__ == "__main__":
    unittest.main()
