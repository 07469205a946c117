"""every_2nd_inferior (issue 20 item 6): handling every second step is judged inferior to the paper's method at
the same work from force error and divergence, not only jitter, per response mode. every_nth n = 2 (its
defaults) against interruptible with the paper's settings at full-work/2 (else full/2), same setup: holds when
every_nth errs more (force error p50) and diverges at least FLOOR_FACTOR noise floors more; does not hold when
interruptible is worse on both; undecided within the noise floor; mixed otherwise; not measured without a run,
a key or the floor. Run by ctest with /usr/bin/python3."""
import os
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from test_force_error_divergence import JITTER, PERTURB, diverged, force, judged, run  # noqa: E402
from tcbench_report import claims  # noqa: E402
from tcbench_report.claims import FAILS, HOLDS, MIXED, PAPER_TASKS, UNDECIDED, UNMEASURED  # noqa: E402
from tcbench_report.paper import FLOOR_FACTOR  # noqa: E402

ID = "every_2nd_inferior"
EXPLICIT = ["collision.response=explicit"]


def setup_runs(nth=(0.12, 2e-4), inter=(0.03, 5e-5), response="implicit", overrides=(), seed=0, floor=True,
               budget="full-work/2", nth_settings=None):
    """full, its noise floor (1e-6 m), every_nth n=2 (a jitter sweep's) and interruptible at `budget`;
    nth and inter are (force error p50, divergence rms final) or None for a run recorded without the keys."""
    kw = {"response": response, "overrides": list(overrides), "seed": seed}
    tag = f"{response} s{seed}"

    def keys(values):
        if values is None:
            return {}
        fe, div = values
        return {"fe": force(fe) if fe is not None else None, "div": diverged(div) if div is not None else None}

    out = [run(f"full {tag}", "full", jitter=0.01, figures=JITTER, **kw),
           run(f"nth {tag}", "every_nth", settings=nth_settings if nth_settings is not None else {"n": 2},
               jitter=0.5, figures=JITTER, **kw, **keys(nth)),
           run(f"i2 {tag}", budget=budget, settings=PAPER_TASKS, jitter=0.02, **kw, **keys(inter))]
    if floor:
        out.append(run(f"floor {tag}", "full", div=diverged(1e-6), response=response, seed=seed,
                       overrides=list(overrides) + [PERTURB]))
    return out


def rows(runs):
    return [o for o in judged(runs) if o.claim.id == ID]


def row(runs, part="implicit response"):
    return next(o for o in rows(runs) if o.part == part)


class Rule(unittest.TestCase):
    def test_the_rule(self):
        f = FLOOR_FACTOR
        self.assertEqual(claims.inferior_at_same_work(0.2, 0.1, 50 + f, 50), HOLDS)
        self.assertEqual(claims.inferior_at_same_work(0.1, 0.2, 50, 50 + f), FAILS)
        self.assertEqual(claims.inferior_at_same_work(0.2, 0.1, 50, 50 + f), MIXED)
        self.assertEqual(claims.inferior_at_same_work(0.1, 0.2, 50 + f, 50), MIXED)
        self.assertEqual(claims.inferior_at_same_work(0.2, 0.2, 50 + f, 50), MIXED)  # equal force errors
        self.assertEqual(claims.inferior_at_same_work(0.2, 0.1, 50 + f * 0.99, 50), UNDECIDED)
        self.assertEqual(claims.inferior_at_same_work(0.1, 0.2, 50, 50 + f * 0.99), UNDECIDED)


class EveryNthInferior(unittest.TestCase):
    def test_holds(self):
        o = row(setup_runs())
        self.assertEqual(o.verdict, HOLDS)
        self.assertIn("every_nth n=2 vs interruptible at full-work/2: force error p50 0.12 vs 0.03, divergence "
                      "200x floor vs 50x floor (150 floors apart), jitter (RMS, shown, not judged) 0.5 m/s = 50x "
                      "full's vs 0.02 m/s = 2x full's: inferior", o.measured)
        self.assertEqual(sorted(r.name for r in o.runs), ["nth implicit s0"])
        self.assertTrue(any("FLOOR_FACTOR = 10" in t for t in o.claim.ours))

    def test_fails_when_interruptible_is_worse_on_both(self):
        o = row(setup_runs(nth=(0.03, 5e-5), inter=(0.12, 2e-4)))
        self.assertEqual(o.verdict, FAILS)
        self.assertIn("not inferior: interruptible is worse on both", o.measured)

    def test_mixed(self):
        o = row(setup_runs(nth=(0.12, 5e-5), inter=(0.03, 2e-4)))
        self.assertEqual(o.verdict, MIXED)
        self.assertIn("force error p50 0.12 vs 0.03, divergence 50x floor vs 200x floor", o.measured)
        self.assertIn("mixed: force error and divergence disagree", o.measured)

    def test_undecided_within_the_noise_floor(self):
        o = row(setup_runs(nth=(0.12, 5.5e-5), inter=(0.03, 5e-5)))  # 55 against 50 floors: 5 < FLOOR_FACTOR
        self.assertEqual(o.verdict, UNDECIDED)
        self.assertIn("divergence 55x floor vs 50x floor (5 floors apart)", o.measured)

    def test_not_measured_without_the_interruptible_run(self):
        runs = [r for r in setup_runs() if not r.name.startswith("i2")]
        o = row(runs)
        self.assertEqual(o.verdict, UNMEASURED)
        self.assertIn("every_nth n=2: not measured: no interruptible run (paper's settings) at full-work/2 or "
                      "full/2 in the same setup; jitter (RMS, shown, not judged) 0.5 m/s = 50x full's", o.measured)
        # another budget's interruptible run is not the same work
        o = row(setup_runs(budget="full-work/3"))
        self.assertEqual(o.verdict, UNMEASURED)
        self.assertIn("no interruptible run (paper's settings) at full-work/2", o.measured)

    def test_not_measured_without_a_key_says_which(self):
        o = row(setup_runs(nth=(None, 2e-4)))
        self.assertEqual(o.verdict, UNMEASURED)
        self.assertIn("not measured (every_nth: no force_error.relative_l2.p50)", o.measured)
        o = row(setup_runs(inter=(0.03, None)))
        self.assertEqual(o.verdict, UNMEASURED)
        self.assertIn("not measured (interruptible: no divergence.rms_m.final)", o.measured)
        o = row(setup_runs(nth=None, inter=None))
        self.assertIn("not measured (every_nth and interruptible: no force_error.relative_l2.p50; every_nth and "
                      "interruptible: no divergence.rms_m.final)", o.measured)

    def test_not_measured_without_a_noise_floor(self):
        o = row(setup_runs(floor=False))
        self.assertEqual(o.verdict, UNMEASURED)
        self.assertIn("force error p50 0.12 vs 0.03, divergence n/a vs n/a", o.measured)
        self.assertIn("not measured (every_nth and interruptible: no noise floor: a noise-floor run (full, no "
                      "budget, a perturb.* override, same setup))", o.measured)

    def test_not_measured_without_a_jitter_sweep(self):
        runs = setup_runs()
        for r in runs:
            r.figures.clear()
        [o] = rows(runs)
        self.assertEqual(o.verdict, UNMEASURED)
        self.assertIn("no every_nth n=2 run (its default settings) in the sweeps declaring the jitter figure",
                      o.measured)

    def test_only_the_papers_interruptible_counts(self):
        # fine_tasks=true is ours: never the comparison, even when it sorts first and would turn the verdict
        fine = run("a fine i2", budget="full-work/2", settings={**PAPER_TASKS, "fine_tasks": True},
                   fe=force(0.5), div=diverged(1e-3))
        o = row(setup_runs() + [fine])
        self.assertEqual(o.verdict, HOLDS)
        self.assertIn("force error p50 0.12 vs 0.03", o.measured)
        self.assertNotIn("vs 0.5", o.measured)
        o = row([r for r in setup_runs() if not r.name.startswith("i2")] + [fine])
        self.assertEqual(o.verdict, UNMEASURED)
        self.assertIn("no interruptible run (paper's settings)", o.measured)
        for settings in ({"reserve_apply": True}, {"apply_first": True}, {"widen_stale": True}):
            other = run("ours", budget="full-work/2", settings=settings, fe=force(0.5), div=diverged(1e-3))
            o = row([r for r in setup_runs() if not r.name.startswith("i2")] + [other])
            self.assertEqual(o.verdict, UNMEASURED, settings)

    def test_only_every_nth_with_its_defaults_is_judged(self):
        for settings in ({"n": 3}, {"n": 2, "hold": False}):
            [o] = rows(setup_runs(nth_settings=settings))
            self.assertEqual(o.verdict, UNMEASURED, settings)
        self.assertEqual(row(setup_runs(nth_settings={})).verdict, HOLDS)  # a run recorded before settings

    def test_wall_budget_at_the_same_share_when_no_work_budget(self):
        o = row(setup_runs(budget="full/2"))
        self.assertEqual(o.verdict, HOLDS)
        self.assertIn("vs interruptible at full/2:", o.measured)
        # a work budget is preferred to a wall one
        wall = run("i2 wall", budget="full/2", settings=PAPER_TASKS, fe=force(0.5), div=diverged(1e-3))
        o = row(setup_runs() + [wall])
        self.assertIn("vs interruptible at full-work/2:", o.measured)
        self.assertEqual(o.verdict, HOLDS)

    def test_both_response_modes_judged_separately(self):
        runs = setup_runs() + setup_runs(nth=(0.03, 5e-5), inter=(0.12, 2e-4), response="explicit",
                                         overrides=EXPLICIT)
        outcomes = rows(runs)
        self.assertEqual([o.part for o in outcomes], ["implicit response", "explicit response"])
        implicit, explicit = outcomes
        self.assertEqual(implicit.verdict, HOLDS)
        self.assertEqual(explicit.verdict, FAILS)  # compared with the explicit interruptible run, its own floor
        self.assertIn("force error p50 0.03 vs 0.12, divergence 50x floor vs 200x floor", explicit.measured)
        self.assertEqual([r.name for r in explicit.runs], ["nth explicit s0"])
        # a mode without its interruptible run is not measured, whatever the other mode has
        runs = setup_runs() + [r for r in setup_runs(response="explicit", overrides=EXPLICIT)
                               if not r.name.startswith("i2")]
        self.assertEqual(row(runs, "explicit response").verdict, UNMEASURED)
        self.assertEqual(row(runs, "implicit response").verdict, HOLDS)

    def test_several_runs_give_the_share_of_each_verdict(self):
        runs = (setup_runs() + setup_runs(nth=(0.12, 5e-5), inter=(0.03, 2e-4), seed=1)
                + setup_runs(seed=2, floor=False))
        o = row(runs)
        self.assertEqual(o.verdict, "partly: holds in 1, mixed in 1 of 2 runs (1 run not measured)")
        self.assertIn("every_nth n=2 (plates20, seed 0) vs interruptible at full-work/2", o.measured)
        self.assertIn("every_nth n=2 (plates20, seed 2) vs interruptible at full-work/2", o.measured)
        o = row(setup_runs() + setup_runs(seed=1))
        self.assertEqual(o.verdict, HOLDS)
        o = row(setup_runs() + setup_runs(seed=1, floor=False))
        self.assertEqual(o.verdict, f"{HOLDS} (1 run not measured)")


if __name__ == "__main__":
    unittest.main()
