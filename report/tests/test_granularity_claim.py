"""The granularity claim judges wall-clock overshoot on quiet runs only: a noisy run is shown with its
CPU-time overshoot and decides nothing (issue: whose overshoot is it). Run by ctest with /usr/bin/python3."""
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

from tcbench_report.claims import FAILS, HOLDS, INCONCLUSIVE, worst_overshoot  # noqa: E402
from tcbench_report.loader import Run  # noqa: E402


def run(name, wall_p99, cpu_p99, verdict):
    summary = {"overshoot_pct": {"p99": wall_p99}, "overshoot_cpu_pct": {"p99": cpu_p99}}
    if verdict:
        summary["timing"] = {"verdict": verdict}
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


if __name__ == "__main__":
    unittest.main()
