"""Force error and divergence: the noise-floor run a divergence is measured against (perturb.* overrides
stripped, the contact response respected), the multiple of the floor, both figures' data from synthetic
summaries (runs without the keys left out), and the force-error and divergence evidence of the every_nth and
extrapolation claims, whose verdicts stay the jitter's. Run by ctest with /usr/bin/python3."""
import os
import sys
import tempfile
import unittest
from types import SimpleNamespace

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

from tcbench_report import claims, pairing  # noqa: E402
from tcbench_report.claims import FAILS, HOLDS, PAPER_TASKS, UNMEASURED  # noqa: E402
from tcbench_report.context import Context  # noqa: E402
from tcbench_report.figures import divergence, force_error  # noqa: E402
from tcbench_report.loader import Results, Run  # noqa: E402

PERTURB = "perturb.position=1e-09"


def force(p50, p95=None, mean=None, by_source=None, missed=0.0, ghost=0.0, samples=8):
    """summary.force_error with relative_l2 p50 (None: every sample undefined)."""
    rel = None if p50 is None else {"mean": p50 if mean is None else mean, "p50": p50, "p95": p95 or p50,
                                    "p99": p95 or p50, "max": p95 or p50}
    sources = {s: {"points": 0, "ghost_share": None, "angle_deg_mean": None, "angle_deg_p95": None,
                   "relative_l2_part_mean": None} for s in force_error.SOURCES}
    for s, (points, part) in (by_source or {}).items():
        sources[s] = {"points": points, "ghost_share": 0.0, "angle_deg_mean": 1.0, "angle_deg_p95": 2.0,
                      "relative_l2_part_mean": part}
    return {"samples": samples, "relative_l2": rel, "undefined_samples": 0 if rel else samples,
            "angle_deg": None, "missed_share": {"mean": missed, "max": missed},
            "ghost_share": {"mean": ghost, "max": ghost}, "reference_ms_mean": 70.0, "by_source": sources}


def diverged(rms, momentum=None, angle=None, last_step=40):
    def final_max(value):
        return None if value is None else {"final": value, "max": value}
    return {"reference": "runs/full", "every": 5, "compared_steps": 8, "last_step": last_step,
            "rms_m": final_max(rms), "max_m": final_max(rms), "com_drift_m": final_max(rms),
            "orientation_drift_deg": final_max(angle), "linear_momentum_diff_n_s": final_max(momentum),
            "angular_momentum_diff_n_m_s": final_max(momentum)}


def run(name, method="interruptible", budget="none", response="implicit", overrides=(), seed=0, scene="plates20",
        settings=None, fe=None, div=None, jitter=None, p99=10.0, figures=(), label=None, **summary):
    kind = "none" if budget == "none" else "work" if budget.startswith("full-work/") else "wall_ms"
    body = {"handling_ms": {"p50": p99 / 2, "p99": p99}, "force_error": fe, "divergence": div, "jitter": jitter,
            **summary}
    record = {"scene": scene, "method": method, "seed": seed, "response": response, "steps": 40,
              "overrides": list(overrides), "settings": settings if settings is not None else {},
              "budget": {"kind": kind, "label": budget}, "summary": body, "status": "ok"}
    if label:
        record["method_label"] = label
    r = Run("/nonexistent", record, name)
    r.figures.update(figures)
    return r


def ctx_of(runs):
    return SimpleNamespace(runs=runs, reference=lambda r: pairing.reference(r, runs))


class NoiseFloor(unittest.TestCase):
    def test_perturbation_stripped_response_and_other_overrides_respected(self):
        explicit = ["collision.response=explicit"]
        floor_i = run("floor implicit", "full", overrides=[PERTURB], div=diverged(1e-6))
        floor_e = run("floor explicit", "full", response="explicit", overrides=explicit + [PERTURB],
                      div=diverged(2e-6))
        floor_k = run("floor stiff", "full", overrides=["contact.stiffness=1e5", PERTURB], div=diverged(3e-6))
        floor_s1 = run("floor seed 1", "full", seed=1, overrides=[PERTURB], div=diverged(4e-6))
        runs = [floor_i, floor_e, floor_k, floor_s1]
        self.assertTrue(all(pairing.is_noise_floor(f) for f in runs))
        self.assertFalse(pairing.is_noise_floor(run("full", "full")))
        self.assertFalse(pairing.is_noise_floor(run("perturbed budgeted", budget="full/3", overrides=[PERTURB])))
        self.assertIs(pairing.noise_floor(run("i", budget="full/3", div=diverged(1e-4)), runs), floor_i)
        # the scene's --set strings stay on the floor run; the response mode is the run's recorded one
        self.assertIs(pairing.noise_floor(run("e", budget="full/3", response="explicit", overrides=explicit,
                                              div=diverged(1e-4)), runs), floor_e)
        self.assertIs(pairing.noise_floor(run("e old", budget="full/3", response="explicit",
                                              div=diverged(1e-4)), runs), floor_e)
        self.assertIs(pairing.noise_floor(run("k", budget="full/3", overrides=["contact.stiffness=1e5"],
                                              div=diverged(1e-4)), runs), floor_k)
        self.assertIs(pairing.noise_floor(run("s1", budget="full/3", seed=1, div=diverged(1e-4)), runs), floor_s1)
        self.assertIsNone(pairing.noise_floor(run("s2", budget="full/3", seed=2, div=diverged(1e-4)), runs))
        self.assertIsNone(pairing.noise_floor(run("other", budget="full/3", scene="stack", div=diverged(1)), runs))
        self.assertIsNone(pairing.noise_floor(floor_i, runs))  # a floor has no floor
        # compared up to another step: not this run's floor
        self.assertIsNone(pairing.noise_floor(run("short", budget="full/3", div=diverged(1e-4, last_step=20)), runs))
        # the floor is no reference: a budgeted run's reference is the unperturbed full run
        full = run("full", "full")
        self.assertIs(pairing.reference(run("i", budget="full/3"), runs + [full]), full)

    def test_multiple_of_the_floor(self):
        floor = run("floor", "full", overrides=[PERTURB], div=diverged(5e-7, momentum=2e-4, angle=4e-5))
        r = run("i", budget="full/3", div=diverged(1.75e-4, momentum=0.035, angle=None))
        self.assertAlmostEqual(pairing.floor_multiple(r, floor), 350.0)
        self.assertAlmostEqual(pairing.floor_multiple(r, floor, "divergence.linear_momentum_diff_n_s.max"), 175.0)
        self.assertIsNone(pairing.floor_multiple(r, floor, "divergence.orientation_drift_deg.final"))  # missing
        self.assertIsNone(pairing.floor_multiple(r, None))
        self.assertIsNone(pairing.floor_multiple(r, run("zero floor", "full", overrides=[PERTURB], div=diverged(0.0))))
        self.assertIsNone(pairing.floor_multiple(run("old", budget="full/3"), floor))


class ForceErrorFigure(unittest.TestCase):
    RUNS = [run("full", "full", fe=force(0.0, by_source={"computed": (100, 0.0)}), p99=30.0),
            run("nth", "every_nth", settings={"n": 2}, fe=force(0.017, 0.093, mean=0.031, missed=0.0005,
                                                                by_source={"computed": (96, 0.0), "held": (97, 0.061)}),
                p99=27.0),
            run("i3", budget="full-work/3", fe=force(0.166, 0.303, mean=0.187, missed=0.38, ghost=0.0126,
                                                     by_source={"computed": (45, 0.054), "held": (27, 0.042),
                                                                "extrapolated": (40, 0.071)}), p99=8.6),
            run("i3 explicit", budget="full-work/3", response="explicit", fe=force(0.2)),
            run("undefined", budget="full-work/10", fe=force(None)),
            run("old", budget="full-work/3", seed=1),  # recorded without --force-reference
            run("floor", "full", overrides=[PERTURB], fe=force(0.0), div=diverged(1e-6))]

    def test_rows_by_scene_and_response_without_floor_or_missing_runs(self):
        rows = force_error.rows(self.RUNS)
        self.assertEqual([key for key, _ in rows], [("plates20", "implicit"), ("plates20", "explicit")])
        self.assertEqual([r.name for r in rows[0][1]], ["full", "nth", "i3", "undefined"])
        self.assertEqual([r.name for r in rows[1][1]], ["i3 explicit"])
        self.assertEqual(force_error.rows([run("old", budget="full/3")]), [])

    def test_points_and_breakdown(self):
        by_name = {r.name: r for r in self.RUNS}
        self.assertEqual(force_error.point(by_name["i3"]), {"x": 8.6, "p50": 0.166, "p95": 0.303})
        self.assertEqual(force_error.point(by_name["full"])["p50"], 0.0)
        self.assertEqual(force_error.point_label(by_name["full"], force_error.point(by_name["full"])), "0 (full)")
        self.assertIsNone(force_error.point(by_name["undefined"]))  # every sample undefined: no point
        b = force_error.breakdown(by_name["i3"])
        self.assertEqual(b["parts"], {"computed": 0.054, "held": 0.042, "extrapolated": 0.071})
        self.assertEqual(b["mean"], 0.187)
        self.assertEqual((b["missed"], b["ghost"]), (0.38, 0.0126))
        self.assertIn("missed 38 %", force_error.breakdown_note(b))
        self.assertIn("extrapolated 36 %", force_error.breakdown_note(b))
        held = force_error.breakdown(by_name["nth"])
        self.assertEqual(held["parts"], {"computed": 0.0, "held": 0.061})  # sources that never occurred: absent
        undefined = force_error.breakdown(by_name["undefined"])
        self.assertIsNone(undefined["mean"])
        self.assertIn("8 undefined", force_error.breakdown_note(undefined))

    def test_y_scale(self):
        self.assertEqual(force_error.y_scale([0.0, 0.017, 0.166]), ("symlog", 0.01))
        self.assertEqual(force_error.y_scale([0.017, 0.3]), ("log", None))
        self.assertEqual(force_error.y_scale([0.1, 0.3]), ("linear", None))
        self.assertEqual(force_error.y_scale([0.0]), ("linear", None))

    def test_the_figure_is_drawn_or_says_why_not(self):
        with tempfile.TemporaryDirectory() as out:
            ctx = Context(Results(out, runs=self.RUNS), out)
            section = force_error.draw(ctx, self.RUNS)
            self.assertIsNone(section.missing)
            self.assertTrue(os.path.exists(os.path.join(out, section.image)))
            self.assertNotIn("floor", [r.name for r in section.runs])
            self.assertNotIn("old", [r.name for r in section.runs])
            self.assertIn("p50", section.caption)
            self.assertIn("p95", section.caption)
            self.assertIn("parts, not a sum", section.caption)
            missing = force_error.draw(ctx, [run("old", budget="full/3")])
            self.assertIn("force_error", missing.missing)


class DivergenceFigure(unittest.TestCase):
    FLOOR = run("floor", "full", overrides=[PERTURB], div=diverged(5e-7, momentum=2e-4, angle=4e-5))
    RUNS = [run("full", "full"), FLOOR,
            run("nth", "every_nth", settings={"n": 2}, div=diverged(3.5e-5, momentum=5e-3, angle=5e-4)),
            run("i3", budget="full-work/3", div=diverged(1.75e-4, momentum=0.035, angle=None)),
            run("explicit", budget="full-work/3", response="explicit", overrides=["collision.response=explicit"],
                div=diverged(1e-4, momentum=0.01, angle=0.01)),
            run("old", budget="full-work/10")]

    def test_bars_with_their_floor_and_multiples(self):
        rows = divergence.bars(self.RUNS, self.RUNS)
        self.assertEqual([key for key, _ in rows], [("plates20", "implicit"), ("plates20", "explicit")])
        implicit = rows[0][1]
        self.assertEqual([b["run"].name for b in implicit], ["nth", "i3"])  # no full, no floor, no "old"
        self.assertIs(implicit[1]["floor"], self.FLOOR)
        value, floor_value, multiple = implicit[1]["values"][pairing.DIVERGENCE]
        self.assertEqual((value, floor_value), (1.75e-4, 5e-7))
        self.assertAlmostEqual(multiple, 350.0)
        self.assertEqual(divergence.bar_note(implicit[1], pairing.DIVERGENCE), "0.000175\n350x floor")
        self.assertEqual(divergence.bar_note(implicit[1], "divergence.orientation_drift_deg.final"), "n/a")
        [no_floor] = rows[1][1]
        self.assertIsNone(no_floor["floor"])
        self.assertEqual(divergence.bar_note(no_floor, pairing.DIVERGENCE), f"0.0001\n{divergence.NO_FLOOR}")

    def test_the_figure_is_drawn_or_says_why_not(self):
        with tempfile.TemporaryDirectory() as out:
            ctx = Context(Results(out, runs=self.RUNS), out)
            section = divergence.draw(ctx, self.RUNS)
            self.assertIsNone(section.missing)
            self.assertTrue(os.path.exists(os.path.join(out, section.image)))
            self.assertEqual([r.name for r in section.runs], ["nth", "i3", "floor", "explicit"])
            self.assertIn("rms_m.final", section.caption)
            self.assertIn(PERTURB, section.caption)
            missing = divergence.draw(ctx, [run("old", budget="full/3")])
            self.assertIn("divergence", missing.missing)


def outcome(outcomes, claim_id, part=""):
    return next(o for o in outcomes if o.claim.id == claim_id and o.part.startswith(part))


def judged(runs):
    with tempfile.TemporaryDirectory() as out:
        return claims.judge(Context(Results(out, runs=runs), out))


JITTER = ("jitter",)  # the sweep declares the jitter figure


class EveryNthEvidence(unittest.TestCase):
    def setups(self, response="implicit", overrides=()):
        kw = {"response": response, "overrides": list(overrides)}
        return [run(f"full {response}", "full", jitter=0.01, figures=JITTER, **kw),
                run(f"floor {response}", "full", div=diverged(1e-6), response=response,
                    overrides=list(overrides) + [PERTURB]),
                run(f"nth {response}", "every_nth", settings={"n": 2, "hold": True}, jitter=0.5, figures=JITTER,
                    fe=force(0.12), div=diverged(2e-4), **kw),
                run(f"i2 {response}", budget="full-work/2", settings=PAPER_TASKS, fe=force(0.03),
                    div=diverged(5e-5), **kw),
                run(f"i2 fine {response}", budget="full-work/2", settings={**PAPER_TASKS, "fine_tasks": True},
                    fe=force(0.5), div=diverged(1e-3), **kw),
                run(f"i10 {response}", budget="full-work/10", settings=PAPER_TASKS, fe=force(0.9),
                    div=diverged(1e-3), **kw)]

    def test_force_error_and_divergence_beside_the_jitter_verdict_both_responses(self):
        runs = self.setups() + self.setups("explicit", ["collision.response=explicit"])
        outcomes = judged(runs)
        for mode in ("implicit", "explicit"):
            o = outcome(outcomes, "every_2nd_jitters", f"{mode} response")
            self.assertEqual(o.verdict, HOLDS)  # jitter 50x full's: the verdict is the jitter's, as before
            self.assertIn("jitter (RMS) 0.5 m/s = 50x full's", o.measured)
            self.assertIn("every_nth n=2 0.12 vs interruptible at full-work/2 0.03 (inferior: yes)", o.measured)
            self.assertIn("every_nth n=2 200x floor vs interruptible at full-work/2 50x floor (inferior: yes)",
                          o.measured)
            self.assertNotIn("0.5 (inferior", o.measured)  # fine_tasks=true is not the paper's method
            self.assertEqual([r.name for r in o.runs], [f"nth {mode}"])

    def test_the_evidence_does_not_change_the_verdict(self):
        runs = self.setups()
        runs[2].summary["jitter"] = 0.011  # barely jitters: the claim does not hold, whatever the force error says
        o = outcome(judged(runs), "every_2nd_jitters")
        self.assertEqual(o.verdict, FAILS)
        self.assertIn("(inferior: yes)", o.measured)

    def test_only_a_cheaper_interruptible_run_leaves_it_undecided(self):
        runs = [r for r in self.setups() if not r.name.startswith("i2")]
        runs[2].summary["force_error"] = force(0.12)
        o = outcome(judged(runs), "every_2nd_jitters")
        self.assertIn("every_nth n=2 0.12 vs interruptible at full-work/10 0.9 (inferior: undecided, every_nth had "
                      "more work: every_nth 1/2 of full's, interruptible 1/10)", o.measured)

    def test_decisions(self):
        self.assertEqual(claims.inferior(0.1, 0.2, 2, 2), "inferior: no")
        self.assertTrue(claims.inferior(0.3, 0.2, 2, 3).startswith("inferior: yes, though interruptible had less"))
        self.assertTrue(claims.inferior(0.1, 0.2, 2, 1.5).startswith("inferior: no, though interruptible had more"))
        self.assertTrue(claims.inferior(0.3, 0.2, 2, 1.5).startswith("inferior: undecided, interruptible had more"))
        self.assertTrue(claims.inferior(0.3, 0.2, 2, 2, decided=False).startswith("inferior: undecided"))
        self.assertTrue(claims.above_noise(30.0, 15.0))
        self.assertFalse(claims.above_noise(12.0, 5.0))
        self.assertFalse(claims.above_noise(None, 5.0))

    def test_without_the_new_keys_n_a(self):
        runs = [run("full", "full", jitter=0.01, figures=JITTER),
                run("nth", "every_nth", settings={"n": 2}, jitter=0.5, figures=JITTER)]
        o = outcome(judged(runs), "every_2nd_jitters")
        self.assertEqual(o.verdict, HOLDS)
        self.assertIn("force error (relative L2 against full's forces from the same state, p50 over sampled "
                      "steps): n/a (no every_nth n=2 run with summary.force_error)", o.measured)
        self.assertIn("as a multiple of the noise floor): n/a (no every_nth n=2 run with summary.divergence)",
                      o.measured)

    def test_no_floor_and_no_comparison(self):
        runs = [r for r in self.setups() if not r.name.startswith(("floor", "i2", "i10"))]
        o = outcome(judged(runs), "every_2nd_jitters")
        self.assertEqual(o.verdict, HOLDS)
        self.assertIn("every_nth n=2 0.12 vs no interruptible run (paper's settings, relative budget, same setup) "
                      "with force error: n/a", o.measured)
        self.assertIn("every_nth n=2 0.0002 m (no noise-floor run) vs no interruptible run", o.measured)

    def test_no_jitter_sweep_no_evidence(self):
        runs = self.setups()
        for r in runs:
            r.figures.clear()  # no sweep declares the jitter figure: nothing judged, no scene to take evidence from
        [o] = [o for o in judged(runs) if o.claim.id == "every_2nd_jitters"]
        self.assertEqual(o.verdict, UNMEASURED)
        self.assertIn("jitter (what the verdict judges): not measured in the runs of sweeps declaring the jitter "
                      "figure", o.measured)
        self.assertIn("n/a (no every_nth n=2 run with summary.force_error)", o.measured)
        self.assertIn("evidence from the scenes judged only (none): plates20 left out", o.measured)

    def test_the_evidence_responds_per_mode_where_only_it_has_runs(self):
        runs = self.setups() + [r for r in self.setups("explicit", ["collision.response=explicit"])
                                if not r.name.startswith("full")]
        runs[-4].figures.clear()  # the explicit every_nth run is no jitter sweep's: explicit only has evidence
        outcomes = judged(runs)
        o = outcome(outcomes, "every_2nd_jitters", "explicit response")  # plates20 is judged (implicit)
        self.assertEqual(o.verdict, UNMEASURED)
        self.assertIn("every_nth n=2 0.12 vs interruptible at full-work/2 0.03 (inferior: yes)", o.measured)

    def test_evidence_from_the_scenes_judged_only(self):
        # a self-collision scene's runs (no jitter sweep) are drawn by the force-error and divergence figures,
        # but back no resting-contact claim
        fold = {"scene": "folding_bar"}
        runs = self.setups() + [
            run("i3", budget="full-work/3", settings=PAPER_TASKS, jitter=0.02, figures=JITTER, fe=force(0.166),
                div=diverged(1.7e-4)),
            run("n3", "interruptible_no_extrapolation", budget="full-work/3", settings=PAPER_TASKS, jitter=0.03,
                figures=JITTER, fe=force(0.25), div=diverged(4e-4))] + [
            run("fold floor", "full", div=diverged(1e-6), overrides=[PERTURB], **fold),
            run("fold nth", "every_nth", settings={"n": 2}, fe=force(0.7), div=diverged(9e-3), **fold),
            run("fold i2", budget="full-work/2", settings=PAPER_TASKS, fe=force(0.01), div=diverged(2e-6), **fold),
            run("fold i3", budget="full-work/3", settings=PAPER_TASKS, fe=force(0.6), div=diverged(7e-3), **fold),
            run("fold n3", "interruptible_no_extrapolation", budget="full-work/3", settings=PAPER_TASKS,
                fe=force(0.8), div=diverged(8e-3), **fold)]
        outcomes = judged(runs)
        for claim_id in ("every_2nd_jitters", "extrapolation_steadies", "every_2nd_inferior"):
            for o in (o for o in outcomes if o.claim.id == claim_id):
                self.assertNotIn("0.7", o.measured, claim_id)
                self.assertNotIn("9e+03x", o.measured, claim_id)
                self.assertNotIn("0.6 with extrapolation", o.measured, claim_id)
                self.assertFalse([r.name for r in o.runs if r.name.startswith("fold")], claim_id)
        o = outcome(outcomes, "every_2nd_jitters")
        self.assertIn("every_nth n=2 0.12 vs interruptible at full-work/2 0.03 (inferior: yes)", o.measured)
        self.assertIn("evidence from the scenes judged only (plates20): folding_bar left out", o.measured)
        o = outcome(outcomes, "extrapolation_steadies")
        self.assertIn("full-work/3: 0.166 with extrapolation, 0.25 without (lower with: yes)", o.measured)
        self.assertIn("evidence from the scenes judged only (plates20): folding_bar left out", o.measured)


class ExtrapolationEvidence(unittest.TestCase):
    def runs(self, ablation_fe=0.25, ablation_div=4e-4, floor=True):
        out = [run("full", "full", jitter=0.01, figures=JITTER),
               run("i3", budget="full-work/3", settings=PAPER_TASKS, jitter=0.02, figures=JITTER,
                   fe=force(0.166), div=diverged(1.7e-4)),
               run("n3", "interruptible_no_extrapolation", budget="full-work/3", settings=PAPER_TASKS, jitter=0.03,
                   figures=JITTER, fe=force(ablation_fe) if ablation_fe is not None else None,
                   div=diverged(ablation_div) if ablation_div is not None else None)]
        if floor:
            out.append(run("floor", "full", overrides=[PERTURB], div=diverged(1e-6)))
        return out

    def test_with_and_without_extrapolation(self):
        o = outcome(judged(self.runs()), "extrapolation_steadies")
        self.assertTrue(o.verdict.startswith(HOLDS))  # jitter 0.02 < 0.03: the jitter's verdict
        self.assertIn("full-work/3: 0.166 with extrapolation, 0.25 without (lower with: yes)", o.measured)
        self.assertIn("full-work/3: 170x floor with extrapolation, 400x floor without (lower with: yes)", o.measured)

    def test_within_the_noise_and_without_a_floor(self):
        o = outcome(judged(self.runs(ablation_fe=0.1, ablation_div=1.75e-4)), "extrapolation_steadies")
        self.assertIn("0.166 with extrapolation, 0.1 without (lower with: no)", o.measured)
        self.assertIn("170x floor with extrapolation, 175x floor without (lower with: undecided, they differ by less "
                      "than the noise)", o.measured)
        o = outcome(judged(self.runs(floor=False)), "extrapolation_steadies")
        self.assertIn("0.00017 m (no noise-floor run) with extrapolation, 0.0004 m (no noise-floor run) without "
                      "(lower with: undecided without a noise floor)", o.measured)

    def test_ablation_without_the_keys(self):
        o = outcome(judged(self.runs(ablation_fe=None, ablation_div=None)), "extrapolation_steadies")
        self.assertIn("0.166 with extrapolation, no interruptible_no_extrapolation run with force error at this "
                      "budget: n/a", o.measured)
        self.assertIn("170x floor with extrapolation, no interruptible_no_extrapolation run with divergence at this "
                      "budget: n/a", o.measured)
        o = outcome(judged([r for r in self.runs() if r.name in ("full", "n3")]), "extrapolation_steadies")
        self.assertEqual(o.verdict, UNMEASURED)
        self.assertIn("n/a (no interruptible run with summary.force_error)", o.measured)

    def test_evidence_is_about_the_papers_method_only(self):
        for claim in claims.CLAIMS:
            for e in claim.evidence:
                if "interruptible" in e.select.methods:
                    self.assertEqual(e.select.settings, PAPER_TASKS, claim.id)


if __name__ == "__main__":
    unittest.main()
