"""Figures and claims say which statistic they use, and the trade-off figure judges the tail (issue 12, point 3):
accuracy against the p99 of per-step handling time with a whisker to the max, the median beside it; recall as
its mean beside its minimum; the speed-up claim judged on the median with the p99 shown. Run by ctest with
/usr/bin/python3."""
import os
import sys
import unittest
from types import SimpleNamespace

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

from tcbench_report import pairing, render  # noqa: E402
from tcbench_report.claims import FAILS, HOLDS, best_speedup  # noqa: E402
from tcbench_report.figures import tradeoff  # noqa: E402
from tcbench_report.loader import Run  # noqa: E402


def run(name, method="interruptible", budget="none", p50=None, p99=None, worst=None, scene="fast_sphere_torus",
        **summary):
    handling = {k: v for k, v in (("p50", p50), ("p99", p99), ("max", worst)) if v is not None}
    kind = "none" if budget == "none" else "wall_ms" if budget.startswith("ms:") else "work"
    record = {"scene": scene, "method": method, "seed": 0, "response": "implicit", "steps": 100,
              "budget": {"kind": kind, "label": budget}, "summary": {"handling_ms": handling, **summary}}
    return Run("/nonexistent", record, name)


# every_nth's shape: its median step does nothing, every n-th step costs a full cycle.
FULL = run("full", "full", p50=0.30, p99=0.43, worst=0.48, recall_min=1.0, recall_mean=1.0)
EVERY_NTH = run("every_nth", "every_nth", p50=0.0, p99=0.60, worst=0.64, recall_min=0.5, recall_mean=0.98)


class TradeoffPoints(unittest.TestCase):
    def test_x_is_the_named_statistic_and_the_whisker_reaches_the_max(self):
        [(x, y, whisker, r)] = tradeoff.points([EVERY_NTH], "p99", "recall_mean", "max")
        self.assertEqual((x, y, whisker, r.name), (0.60, 0.98, 0.64, "every_nth"))
        [(x, y, whisker, _)] = tradeoff.points([EVERY_NTH], "p50", "recall_min")
        self.assertEqual((x, y, whisker), (0.0, 0.5, None))  # a 0 ms median is drawn, not dropped

    def test_budget_order_and_missing_values(self):
        runs = [run("k8", budget="full-work/8", p50=0.15, p99=0.30, recall_mean=0.45),
                run("k2", budget="full-work/2", p50=0.17, p99=0.32, recall_mean=0.88),
                run("k32", budget="full-work/32", p50=0.10, p99=0.33, recall_mean=0.07),
                run("no p99", budget="full-work/4", p50=0.17, recall_mean=0.67),
                run("no recall", budget="full-work/16", p50=0.14, p99=0.32)]
        # From the largest budget to the smallest, whatever the x: a curve follows the budget.
        self.assertEqual([p[3].name for p in tradeoff.points(runs, "p99", "recall_mean")], ["k2", "k8", "k32"])
        self.assertEqual([p[3].name for p in tradeoff.points(runs, "p50", "recall_mean")],
                         ["k2", "no p99", "k8", "k32"])

    def test_axes_name_their_statistic(self):
        labels = {stat: label for stat, label, *_ in tradeoff.TIMES}
        self.assertIn("p99 handling time per step (ms)", labels["p99"])
        self.assertIn("median (p50)", labels["p50"])
        self.assertEqual([whisker for *_, whisker in tradeoff.TIMES], ["max", None])
        recall = [key for key, *_ in tradeoff.PANELS[0][2]]
        self.assertEqual(recall, ["recall_mean", "recall_min"])

    def test_scenes_drawn_need_a_recall(self):
        other = run("no oracle", "full", p50=1.0, p99=2.0, scene="scaling")
        only_mean = run("mean only", p50=0.1, p99=0.2, recall_mean=0.5, scene="plates20")
        self.assertEqual(list(tradeoff.scenes_drawn([FULL, EVERY_NTH, other, only_mean])),
                         ["fast_sphere_torus", "plates20"])


class SpeedupStatistics(unittest.TestCase):
    def test_speedup_by_statistic(self):
        fast = run("fast", budget="ms:0.1", p50=0.03, p99=0.27)
        self.assertAlmostEqual(pairing.speedup(fast, FULL), 10.0)
        self.assertAlmostEqual(pairing.speedup(fast, FULL, "p99"), 0.43 / 0.27)
        self.assertIsNone(pairing.speedup(run("no p99", budget="ms:0.1", p50=0.03), FULL, "p99"))
        self.assertIsNone(pairing.speedup(fast, None))

    def test_claim_judges_the_median_and_shows_the_p99(self):
        fast = run("fast", budget="ms:0.1", p50=0.03, p99=0.27)
        slow = run("slow", budget="ms:0.2", p50=0.2, p99=0.40)
        ctx = SimpleNamespace(runs=[FULL, fast, slow])
        measured, verdict = best_speedup([fast, slow], ctx)
        self.assertTrue(verdict.startswith(HOLDS))  # 10x median, though only 1.6x at the p99
        self.assertIn("median (p50) handling time: up to 10.00x (fast), down to 1.50x (slow)", measured)
        self.assertIn("p99 handling time (shown, not judged): up to 1.59x (fast), down to 1.07x (slow)", measured)
        measured, verdict = best_speedup([slow], ctx)
        self.assertTrue(verdict.startswith(FAILS))
        self.assertNotIn("down to", measured)

    def test_runs_without_p99_still_judged(self):
        old = run("old", budget="ms:0.1", p50=0.1)
        measured, verdict = best_speedup([old], SimpleNamespace(runs=[FULL, old]))
        self.assertTrue(verdict.startswith(HOLDS))
        self.assertNotIn("p99", measured)


class RunsTable(unittest.TestCase):
    def test_tail_and_mean_recall_beside_median_and_minimum(self):
        keys = [key for _, key in render.RUN_COLUMNS]
        for key in ("handling_ms.p50", "handling_ms.p99", "recall_mean", "recall_min"):
            self.assertIn(key, keys)
        self.assertEqual(keys.index("handling_ms.p99"), keys.index("handling_ms.p50") + 1)


if __name__ == "__main__":
    unittest.main()
