"""The whole step's speed-up (summary.step_ms: handling + dynamics) is shown beside the handling one, the claim
still judged on handling, and runs recorded before step_ms show "n/a"; the stage-cost figure stacks
summary.stages in the cycle's order and leaves out runs without stages. Run by ctest with /usr/bin/python3."""
import os
import sys
import tempfile
import unittest
from types import SimpleNamespace

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

from tcbench_report import pairing  # noqa: E402
from tcbench_report.claims import FAILS, HOLDS, best_speedup  # noqa: E402
from tcbench_report.context import Context  # noqa: E402
from tcbench_report.figures import speedup, stage_costs  # noqa: E402
from tcbench_report.loader import Results, Run  # noqa: E402


def run(name, method="interruptible", budget="none", p50=None, p99=None, step=None, stages=None, seed=0,
        scene="plates20", label=None, steps=100, **summary):
    """step: (p50, p99) of summary.step_ms, or None for a run recorded before it."""
    kind = "none" if budget == "none" else "wall_ms" if budget.startswith("ms:") or budget.startswith("full/") \
        else "work"
    body = {"handling_ms": {k: v for k, v in (("p50", p50), ("p99", p99)) if v is not None}, **summary}
    if step is not None:
        body["step_ms"] = {"mean": step[0], "p50": step[0], "p95": step[1], "p99": step[1], "max": step[1]}
    if stages is not None:
        body["stages"] = stages
    record = {"scene": scene, "method": method, "seed": seed, "response": "implicit", "steps": steps,
              "budget": {"kind": kind, "label": budget}, "summary": body}
    if label:
        record["method_label"] = label
    return Run("/nonexistent", record, name)


# The reference: 0.30 ms handling, 2.30 ms the whole step (2 ms of dynamics).
FULL = run("full", "full", p50=0.30, p99=0.43, step=(2.30, 2.60))
OLD_FULL = run("old full", "full", p50=0.30, p99=0.43, scene="old")


class StepSpeedup(unittest.TestCase):
    def test_ratio_of_the_reference_step_over_the_runs(self):
        fast = run("fast", budget="ms:0.1", p50=0.10, p99=0.20, step=(2.10, 2.50))
        self.assertAlmostEqual(pairing.step_speedup(fast, FULL), 2.30 / 2.10)
        self.assertAlmostEqual(pairing.step_speedup(fast, FULL, "p99"), 2.60 / 2.50)
        self.assertAlmostEqual(pairing.speedup(fast, FULL), 3.0)  # the handling ratio is unchanged
        self.assertAlmostEqual(pairing.speedup(fast, FULL, "p50", pairing.STEP), 2.30 / 2.10)

    def test_runs_or_references_without_step_ms_give_none(self):
        old = run("old", budget="ms:0.1", p50=0.10, scene="old")
        self.assertIsNone(pairing.step_speedup(old, OLD_FULL))
        self.assertIsNone(pairing.step_speedup(run("new", budget="ms:0.1", p50=0.1, step=(2.0, 2.2)), OLD_FULL))
        self.assertIsNone(pairing.step_speedup(old, None))

    def test_figure_series_beside_the_handling_ones(self):
        fast = run("fast", budget="ms:0.1", p50=0.10, p99=0.20, step=(2.10, 2.50))
        old = run("old", budget="ms:0.1", p50=0.10, p99=0.20, scene="old")
        series = speedup.ratios([(fast, FULL, 3.0), (old, OLD_FULL, 3.0)])
        self.assertEqual([(what, stat) for what, stat, *_ in speedup.SERIES],
                         [("handling time", "p50"), ("handling time", "p99"),
                          ("whole step (handling + dynamics)", "p50"), ("whole step (handling + dynamics)", "p99")])
        self.assertAlmostEqual(series[0][0], 3.0)
        self.assertAlmostEqual(series[2][0], 2.30 / 2.10)
        self.assertAlmostEqual(series[3][0], 2.60 / 2.50)
        self.assertEqual([series[2][1], series[3][1]], [None, None])  # an old run: no step bars
        self.assertAlmostEqual(series[1][1], 0.43 / 0.20)


class StepSpeedupInTheClaim(unittest.TestCase):
    def test_shown_beside_and_never_judged(self):
        # 3x on handling, but the whole step slowed down (the dynamics took longer): the claim still holds.
        slower_step = run("slower step", budget="ms:0.1", p50=0.10, p99=0.20, step=(2.80, 3.40))
        measured, verdict = best_speedup([slower_step], SimpleNamespace(runs=[FULL, slower_step]))
        self.assertTrue(verdict.startswith(HOLDS))
        self.assertIn("median (p50) handling time: up to 3.00x (slower step)", measured)
        self.assertIn("median (p50) whole step (step_ms: handling + dynamics) (shown, not judged): up to 0.82x "
                      "(slower step)", measured)
        self.assertIn("p99 whole step (shown, not judged): up to 0.76x (slower step)", measured)
        self.assertNotIn("n/a", measured)

    def test_a_large_step_speedup_does_not_make_it_hold(self):
        slow = run("slow", budget="ms:0.2", p50=0.20, p99=0.40, step=(0.50, 0.60))
        measured, verdict = best_speedup([slow], SimpleNamespace(runs=[FULL, slow]))
        self.assertTrue(verdict.startswith(FAILS))  # 1.5x handling decides, not the 4.6x step
        self.assertIn("up to 4.60x (slow)", measured)

    def test_old_runs_show_n_a(self):
        old = run("old", budget="ms:0.1", p50=0.1, scene="old")
        measured, verdict = best_speedup([old], SimpleNamespace(runs=[OLD_FULL, old]))
        self.assertTrue(verdict.startswith(HOLDS))
        self.assertIn("whole step (step_ms: handling + dynamics): n/a", measured)
        self.assertNotIn("p99", measured)

    def test_mixed_old_and_new_runs_name_the_missing(self):
        new = run("new", budget="ms:0.1", p50=0.1, step=(2.0, 2.3))
        old = run("old", budget="ms:0.1", p50=0.1, scene="old")
        measured, _ = best_speedup([new, old], SimpleNamespace(runs=[FULL, OLD_FULL, new, old]))
        self.assertIn("up to 1.15x (new)", measured)
        self.assertIn("whole step n/a for 1 run without step_ms", measured)


def stages(ms, interrupted=None, reverse=False):
    """summary.stages from per-stage ms (STAGES order); reverse: the JSON object's keys in the other order."""
    interrupted = interrupted or [0] * len(stage_costs.STAGES)
    pairs = [(name, {"ms_mean": m, "ms_max": 2 * m, "work_mean": 10 * m, "interrupted_steps": i})
             for name, m, i in zip(stage_costs.STAGES, ms, interrupted)]
    return dict(reversed(pairs) if reverse else pairs)


MS = [0.01, 0.10, 0.08, 0.06, 0.04, 0.05, 0.03, 0.02]


class StageCostBars(unittest.TestCase):
    def test_stage_order(self):
        self.assertEqual(stage_costs.STAGES, ("prioritize", "hash_tets", "query_points", "hash_surface",
                                              "border_depth", "propagate", "forces", "apply"))
        [bar] = stage_costs.bars([run("r", "full", stages=stages(MS, reverse=True),
                                      stages_ms_unaccounted_mean=0.005)])["plates20"]
        self.assertEqual(bar["ms"], MS)  # in the cycle's order, whatever the JSON's
        self.assertEqual(bar["unaccounted"], 0.005)
        self.assertEqual(bar["label"], "full\nno budget")

    def test_runs_without_stages_are_left_out(self):
        runs = [run("old", "full", p50=0.3), run("null", "full", stages=None, seed=1),
                run("new", "interruptible", budget="full/3", stages=stages(MS), seed=2)]
        runs[1].summary["stages"] = None  # a run that took no step
        out = stage_costs.bars(runs)
        self.assertEqual([[r.name for r in b["runs"]] for b in out["plates20"]], [["new"]])
        self.assertEqual(stage_costs.bars([run("old", "full", p50=0.3, scene="old")]), {})
        missing = stage_costs.draw(SimpleNamespace(missing=lambda title, why: ("missing", why)),
                                   [run("old", "full", p50=0.3)])
        self.assertEqual(missing[0], "missing")

    def test_seeds_averaged_other_setups_kept_apart_in_order(self):
        a = [0.0, 0.2, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]
        b = [0.0, 0.4, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]
        cut = [0, 30, 0, 0, 0, 10, 0, 0]
        runs = [run("i s1", budget="full/3", stages=stages(b, cut), seed=1),
                run("i s0", budget="full/3", stages=stages(a, [0, 10, 0, 0, 0, 30, 0, 0]), seed=0),
                run("f", "full", stages=stages(MS)),
                run("i k10", budget="full/10", stages=stages(a)),
                run("t", "interruptible", budget="full/3", stages=stages(a), label="interruptible(fine_tasks=true)"),
                run("other scene", "full", stages=stages(MS), scene="another")]
        out = stage_costs.bars(runs)
        self.assertEqual(list(out), ["another", "plates20"])
        labels = [b["label"] for b in out["plates20"]]
        self.assertEqual(labels, ["full\nno budget", "interruptible\nfull/3\nmean of 2 seeds",
                                  "interruptible\nfull/10", "interruptible(\nfine_tasks=true)\nfull/3"])
        both = out["plates20"][1]
        self.assertEqual([r.name for r in both["runs"]], ["i s0", "i s1"])
        self.assertAlmostEqual(both["ms"][1], 0.3)
        self.assertEqual(both["interrupted"], [0, 20, 0, 0, 0, 20, 0, 0])
        self.assertIsNone(both["unaccounted"])
        self.assertEqual(stage_costs.interruption_note(both), "interrupted 40 of 100 steps\nmostly hash_tets (20)")
        self.assertEqual(stage_costs.interruption_note(out["plates20"][0]), "never interrupted")
        [none] = stage_costs.bars([run("none", "none", stages=stages([0.0] * 8))])["plates20"]
        self.assertEqual(stage_costs.interruption_note(none), "no time in any stage\n(no collision cycle)")

    def test_the_figure_is_drawn(self):
        runs = [run("f", "full", p50=0.3, stages=stages(MS), stages_ms_unaccounted_mean=0.004),
                run("i", budget="full/3", p50=0.1, stages=stages([m / 3 for m in MS], [0, 50, 0, 0, 0, 20, 5, 0])),
                run("old", "full", p50=0.3, scene="old")]
        with tempfile.TemporaryDirectory() as out:
            ctx = Context(Results(out, runs=runs), out)
            section = stage_costs.draw(ctx, runs)
            self.assertIsNone(section.missing)
            self.assertTrue(os.path.exists(os.path.join(out, section.image)))
            self.assertEqual([r.name for r in section.runs], ["f", "i"])
            self.assertIn("mean ms per step", section.caption)


if __name__ == "__main__":
    unittest.main()
