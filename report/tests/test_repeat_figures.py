"""Repeats in every figure and claim (issue 21): a configuration with several seeds is one point or bar at
its median with the bootstrap 95 % interval (per-step curves: one thin curve per seed), a single run is drawn
as before, every caption says how many runs a configuration rests on and the jitter the seeds drew; outcome
claims give rates with Wilson intervals and hold only when every repeat has the outcome; the
hash-sensitivity figure's factors, measures and layout. Synthetic runs only. Run by ctest with
/usr/bin/python3."""
import os
import sys
import tempfile
import unittest
from types import SimpleNamespace

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

from tcbench_report import claims, figures, pairing, statistics  # noqa: E402
from tcbench_report.context import Context  # noqa: E402
from tcbench_report.figures import (divergence, force_error, handling_time, hash_sensitivity, haptic,  # noqa: E402
                                    scaling, speedup, stage_costs)
from tcbench_report.loader import Results, Run  # noqa: E402

JITTER_SETS = ["perturb.velocity=0.001", "perturb.material=0.05"]
DRAWN = {"jitter": {"position_m": 0.0, "velocity_m_per_s": 0.001, "rotation_rad": 0.0, "material_rel": 0.05},
         "bodies": []}
SEEDS = range(5)


def run(name, method="interruptible", budget="full-work/3", seed=0, overrides=JITTER_SETS, scene="plates20",
        collision=None, steps=None, figures_=(), status="ok", perturbation=DRAWN, **summary):
    kind = "none" if budget == "none" else "work" if budget.startswith("full-work/") else "wall_ms"
    record = {"scene": scene, "method": method, "seed": seed, "response": "implicit", "steps": 40,
              "overrides": list(overrides), "settings": {}, "budget": {"kind": kind, "label": budget},
              "summary": summary, "status": status,
              "world": {"objects": [{"name": "a", "tets": summary.pop("tets", 100), "passive": False}]}}
    if perturbation is not None:
        record["perturbation"] = perturbation
    if collision:
        record["collision"] = collision
    r = Run("/nonexistent", record, name)
    r.figures.update(figures_)
    if steps is not None:
        r._steps = steps
    return r


def series(scale):
    return {"step": [1.0, 2.0, 3.0], "time_s": [0.01, 0.02, 0.03], "handling_ms": [scale, 2 * scale, scale],
            "probe_force_x": [scale, 0.0, scale], "probe_force_y": [0.0, 0.0, 0.0], "probe_force_z": [0.0, 0.0, 0.0]}


def handling(p50, p99=None):
    return {"p50": p50, "p99": p99 if p99 is not None else 2 * p50, "max": 3 * p50}


def context(out, runs):
    return Context(Results(out, runs=runs), out)


class Speedup(unittest.TestCase):
    def rows(self):
        fulls = [run(f"full s{s}", "full", "none", seed=s, handling_ms=handling(0.3)) for s in SEEDS]
        budgeted = [run(f"i s{s}", seed=s, handling_ms=handling(0.1 + 0.01 * s)) for s in SEEDS]
        single = run("i6", budget="full-work/6", overrides=(), perturbation=None, handling_ms=handling(0.05))
        plain = run("full", "full", "none", overrides=(), perturbation=None, handling_ms=handling(0.3))
        runs = fulls + budgeted + [single, plain]
        return runs, pairing.budgeted_with_reference(runs, runs)

    def test_each_run_against_its_own_seed_and_one_median_per_configuration(self):
        runs, rows = self.rows()
        self.assertEqual([(r.name, ref.name) for r, ref, _ in rows][:2], [("i s0", "full s0"), ("i s1", "full s1")])
        groups = speedup.configurations(rows)
        self.assertEqual([len(g) for g in groups], [5, 1])
        median, lo, hi, n = speedup.estimates(groups[0])[0]
        self.assertAlmostEqual(median, 0.3 / 0.12)  # the median of 3.0, 2.73, 2.5, 2.31, 2.14
        self.assertTrue(lo <= median <= hi and n == 5)
        self.assertEqual(speedup.estimates(groups[1])[0][1:], (None, None, 1))
        self.assertTrue(speedup.label_note(groups[0]).startswith("median of 5 runs:\np50 2.50x ["))
        self.assertEqual(speedup.label_note(groups[1]).split("\n")[0], "p50 6.00x")  # one run: as before

    def test_drawn_with_the_count_in_the_caption(self):
        runs, _ = self.rows()
        with tempfile.TemporaryDirectory() as out:
            section = speedup.draw(context(out, runs), runs)
            self.assertIsNone(section.missing)
            self.assertIn("1 to 5 runs (seeds) per configuration", section.caption)
            self.assertIn("bootstrap 95 % interval", section.caption)
            self.assertIn("velocity +-0.001 m/s", section.caption)


class StageCosts(unittest.TestCase):
    def test_the_totals_median_beside_the_means(self):
        def stages(ms):
            return {s: {"ms_mean": ms if s == "hash_tets" else 0.0, "interrupted_steps": 0} for s in stage_costs.STAGES}
        runs = [run(f"i s{s}", seed=s, stages=stages(0.1 * (s + 1))) for s in SEEDS]
        runs.append(run("one", budget="full-work/6", overrides=(), perturbation=None, stages=stages(0.2)))
        bars = stage_costs.bars(runs)["plates20"]
        self.assertAlmostEqual(bars[0]["ms"][1], 0.3)  # the mean of 0.1 .. 0.5
        median, lo, hi, n = bars[0]["total"]
        self.assertAlmostEqual(median, 0.3)
        self.assertEqual(n, 5)
        self.assertTrue(lo <= median <= hi)
        self.assertEqual(bars[1]["total"][1:], (None, None, 1))
        with tempfile.TemporaryDirectory() as out:
            section = stage_costs.draw(context(out, runs), runs)
            self.assertIn("median of the seeds' totals", section.caption)


class ForceError(unittest.TestCase):
    def runs(self):
        def fe(p50, mean):
            return {"samples": 4, "relative_l2": {"mean": mean, "p50": p50, "p95": 2 * p50, "p99": 2 * p50,
                                                  "max": 2 * p50},
                    "undefined_samples": 0, "missed_share": {"mean": 0.1, "max": 0.1},
                    "ghost_share": {"mean": 0.0, "max": 0.0},
                    "by_source": {"computed": {"points": 10, "relative_l2_part_mean": 0.05},
                                  "held": {"points": 5, "relative_l2_part_mean": p50}}}
        return ([run(f"i s{s}", seed=s, handling_ms=handling(0.1, 0.2 + 0.01 * s), force_error=fe(0.1 * (s + 1), 0.2))
                 for s in SEEDS] + [run("one", budget="full-work/6", overrides=(), perturbation=None,
                                        handling_ms=handling(0.1), force_error=fe(0.4, 0.5))])

    def test_one_point_and_one_group_of_bars_per_configuration(self):
        runs = self.runs()
        [(_, members)] = force_error.rows(runs)
        groups = statistics.repeats(members)
        p = force_error.group_point(groups[0])
        self.assertAlmostEqual(p["p50"], 0.3)
        self.assertAlmostEqual(p["p95"], 0.6)
        self.assertAlmostEqual(p["x"], 0.22)
        self.assertTrue(p["lo"] <= p["p50"] <= p["hi"] and p["n"] == 5)
        self.assertEqual(force_error.group_point(groups[1]), dict(force_error.point(groups[1][0]), lo=None, hi=None,
                                                                  n=1))
        b = force_error.group_breakdown(groups[0])
        self.assertEqual((b["mean"], b["mean_interval"], b["n"]), (0.2, (0.2, 0.2), 5))
        self.assertAlmostEqual(b["parts"]["held"], 0.3)
        self.assertEqual(b["points"], {"computed": 50, "held": 25})
        self.assertTrue(force_error.breakdown_note(b).startswith("median of 5 runs:\n"))
        self.assertFalse(force_error.breakdown_note(force_error.group_breakdown(groups[1])).startswith("median"))
        with tempfile.TemporaryDirectory() as out:
            section = force_error.draw(context(out, runs), runs)
            self.assertIsNone(section.missing)
            self.assertIn("1 to 5 runs (seeds) per configuration", section.caption)


class Divergence(unittest.TestCase):
    def test_median_of_the_runs_and_of_their_multiples(self):
        def div(rms):
            return {"compared_steps": 8, "last_step": 40, "rms_m": {"final": rms, "max": rms}}
        floors = [run(f"floor s{s}", "full", "none", seed=s, overrides=JITTER_SETS + ["perturb.position=1e-09"],
                      divergence=div(1e-6 * (s + 1))) for s in SEEDS]
        runs = floors + [run(f"i s{s}", seed=s, divergence=div(1e-4)) for s in SEEDS]
        [(_, row)] = divergence.bars(runs, runs)
        [group] = divergence.bar_groups(row)
        value, lo, hi, floor_value, multiple, m_lo, m_hi, n = divergence.group_values(group, pairing.DIVERGENCE)
        self.assertEqual((value, lo, hi, n), (1e-4, 1e-4, 1e-4, 5))
        self.assertAlmostEqual(floor_value, 3e-6)
        self.assertAlmostEqual(multiple, 100 / 3)  # the median of 100, 50, 33.3, 25, 20
        self.assertTrue(m_lo <= multiple <= m_hi)
        self.assertTrue(divergence.group_note(group, pairing.DIVERGENCE).startswith("median of 5: 0.0001"))
        self.assertIn("(n=5 seeds)", divergence.tick(group[0], row, group))
        with tempfile.TemporaryDirectory() as out:
            section = divergence.draw(context(out, runs), runs)
            self.assertIsNone(section.missing)
            self.assertIn("n = 5 runs (seeds) per configuration", section.caption)


class Curves(unittest.TestCase):
    def test_handling_time_draws_every_seed_thin(self):
        runs = [run(f"i s{s}", seed=s, steps=series(0.1)) for s in SEEDS]
        runs.append(run("full", "full", "none", overrides=(), perturbation=None, steps=series(0.3)))
        self.assertEqual([[r.name for r in g] for g in handling_time.curves(runs)],
                         [["full"], [f"i s{s}" for s in SEEDS]])
        with tempfile.TemporaryDirectory() as out:
            section = handling_time.draw(context(out, runs), runs)
            self.assertIn("own thin curve", section.caption)
            self.assertEqual(len(section.runs), 6)

    def test_haptic_curves_and_the_median_change(self):
        runs = [run(f"h s{s}", seed=s, steps=series(1.0), probe_force_change_rms=0.1 * (s + 1)) for s in SEEDS]
        with tempfile.TemporaryDirectory() as out:
            section = haptic.draw(context(out, runs), runs)
            self.assertIn("median 0.3 [", section.caption)
            self.assertIn("over 5 seeds", section.caption)
            self.assertIn("drawn thin", section.caption)

    def test_scaling_exponent_fits_a_power_law(self):
        # p50 = 2e-4 * tets^1.5 exactly: the fit finds 1.5 over the sizes run; two sizes fit nothing.
        pts = [(n, 2e-4 * n ** 1.5, None, None, None, 1) for n in (10_000, 40_000, 1_000_000)]
        slope, lo, hi = scaling.exponent(pts)
        self.assertAlmostEqual(slope, 1.5, places=9)
        self.assertEqual((lo, hi), (10_000, 1_000_000))
        self.assertIsNone(scaling.exponent(pts[:2]))
        # A size without a p50 is left out of the fit rather than taken as 0.
        self.assertIsNone(scaling.exponent(pts[:2] + [(5_000, None, None, None, None, 1)]))
        noisy = [(n, n * (1.1 if k % 2 else 0.9), None, None, None, 1) for k, n in enumerate((1e4, 1e5, 1e6, 1e7))]
        self.assertLess(abs(scaling.exponent(noisy)[0] - 1.0), 0.05)

    def test_scaling_work_exponent_is_per_step_and_apart_from_the_time(self):
        # Work grows as tets^1.0 and time as tets^1.2: the caption gives both, each over its own fit. Work is
        # divided by the run's steps, so a size run for twice the steps does not bend the fit.
        runs = [run(f"n{n}", "full", "none", overrides=[f"n={n}"], tets=n, handling_ms=handling(1e-3 * n ** 1.2),
                    work_units_total=7.0 * n * 40 * (2 if n == 4_000 else 1)) for n in (1_000, 4_000, 16_000)]
        runs[1].record["steps"] = 80
        [(legend, rs)] = scaling.curves(runs).items()
        self.assertEqual(scaling.work_points(rs), [(1_000, 7_000.0), (4_000, 28_000.0), (16_000, 112_000.0)])
        self.assertAlmostEqual(scaling.exponent(scaling.work_points(rs))[0], 1.0, places=9)
        # A size without the count is left out of the work fit, not taken as 0: each fit over its own sizes.
        runs.append(run("n64k", "full", "none", overrides=["n=64000"], tets=64_000,
                        handling_ms=handling(1e-3 * 64_000 ** 1.2)))
        [(legend, rs)] = scaling.curves(runs).items()
        self.assertEqual(len(scaling.work_points(rs)), 3)
        with tempfile.TemporaryDirectory() as out:
            section = scaling.draw(context(out, runs), runs)
            self.assertIn("full: 1.20 over 1000..64000 tets (work units a step: 1.00 over 1000..16000 tets).",
                          section.caption)
            self.assertIn("Work units count", section.caption)
        # Without work counts the time's exponent stands alone, with nothing said about work.
        bare = [run(f"b{n}", "full", "none", overrides=[f"n={n}"], tets=n, handling_ms=handling(1e-3 * n))
                for n in (1_000, 4_000, 16_000)]
        with tempfile.TemporaryDirectory() as out:
            caption = scaling.draw(context(out, bare), bare).caption
            self.assertIn("full: 1.00 over 1000..16000 tets.", caption)
            self.assertNotIn("work units", caption.lower())

    def test_scaling_points_are_medians(self):
        runs = [run(f"4 s{s}", seed=s, overrides=JITTER_SETS + ["n=4"], tets=400,
                    handling_ms=handling(1.0 + 0.1 * s)) for s in SEEDS]
        runs += [run("8", overrides=["n=8"], tets=800, handling_ms=handling(2.0))]
        [(legend, rs)] = scaling.curves(runs).items()
        pts = scaling.points(rs)
        self.assertEqual([p[0] for p in pts], [400, 800])
        self.assertAlmostEqual(pts[0][1], 1.2)
        self.assertEqual(pts[0][5], 5)
        self.assertEqual(pts[1][1:], (2.0, None, None, 4.0, 1))


class RestingStack(unittest.TestCase):
    def runs(self, fallen=(), loud=()):
        out = [run(f"full s{s}", "full", "none", seed=s, jitter=0.01, tunneling=0, figures_=("jitter",),
                   top_centre_height_m={"initial": 1.0, "final": 0.95}) for s in SEEDS]
        out += [run(f"i s{s}", seed=s, jitter=0.5 if s in loud else 0.012, tunneling=0, figures_=("jitter",),
                    top_centre_height_m={"initial": 1.0, "final": 0.2 if s in fallen else 0.95}) for s in SEEDS]
        return out

    def judge(self, runs):
        ctx = SimpleNamespace(runs=runs, reference=lambda r: pairing.reference(r, runs))
        return claims.rests_plausibly([r for r in runs if r.method == "interruptible"], ctx)

    def test_every_repeat_rests(self):
        measured, verdict = self.judge(self.runs())
        self.assertIn("standing in 5/5 runs (100 %, 95 % CI 57-100 %)", measured)
        self.assertIn("velocity +-0.001 m/s", measured)
        self.assertEqual(verdict, f"{claims.HOLDS} at its budget (full-work/3 (5/5 (100 %, 95 % CI 57-100 %) runs))")

    def test_a_rate_below_all_does_not_hold(self):
        measured, verdict = self.judge(self.runs(fallen=(2,), loud=(4,)))
        self.assertIn("standing in 4/5 runs (80 %, 95 % CI 38-96 %)", measured)
        self.assertIn("with plausible jitter in 4/5 runs", measured)
        self.assertIn("resting plausibly (all four) in 3/5 runs (60 %, 95 % CI 23-88 %)", measured)
        self.assertIn("seed 2: fallen", measured)
        self.assertIn("seed 4: implausible jitter", measured)
        self.assertTrue(verdict.startswith("partly"), verdict)
        self.assertIn("3/5 (60 %, 95 % CI 23-88 %)", verdict)

    def test_an_unjittered_run_is_not_pooled_with_the_jittered_seeds(self):
        runs = self.runs() + [run("full", "full", "none", overrides=(), perturbation=None, jitter=0.01, tunneling=0,
                                  top_centre_height_m={"initial": 1.0, "final": 0.95}),
                              run("i", overrides=(), perturbation=None, jitter=0.01, tunneling=0,
                                  top_centre_height_m={"initial": 1.0, "final": 0.3})]
        measured, verdict = self.judge(runs)
        self.assertIn("full-work/3 (not jittered): ok, top centre 1.000 -> 0.300 m: fallen", measured)
        self.assertIn("full-work/3 (jittered: velocity +-0.001 m/s, Young's modulus +-0.05 relative), 5 seeds",
                      measured)
        self.assertIn("not at full-work/3 (not jittered)", verdict)

    def test_one_run_as_before(self):
        runs = [run("full", "full", "none", jitter=0.01, tunneling=0, top_centre_height_m={"initial": 1.0, "final": 1.0}),
                run("i", jitter=0.01, tunneling=0, top_centre_height_m={"initial": 1.0, "final": 1.0})]
        measured, verdict = self.judge(runs)
        self.assertTrue(measured.startswith("full-work/3: ok, top centre 1.000 -> 1.000 m: standing"), measured)
        self.assertEqual(verdict, f"{claims.HOLDS} at its budget (full-work/3)")


class Tunnelling(unittest.TestCase):
    def test_pass_through_per_configuration_as_a_rate(self):
        runs = [run(f"k64 s{s}", budget="full-work/64", seed=s, scene="fst", latency_steps={"mean": 1.0, "max": 1 + s},
                    tunneling=int(s >= 2)) for s in SEEDS]
        runs += [run(f"k2 s{s}", budget="full-work/2", seed=s, scene="fst", latency_steps={"mean": 0.5, "max": 1},
                     tunneling=0) for s in SEEDS]
        measured, verdict = claims.latency_bound(runs, None)
        self.assertIn("pass-through per configuration (2 with 5 seeds each): interruptible @ full-work/64 in 3/5 runs "
                      "(60 %, 95 % CI 23-88 %)", measured)
        self.assertIn("none in the other 1 (0/5 runs each: 95 % CI 0-43 %)", measured)
        self.assertEqual(verdict, claims.HOLDS)  # nothing at or below 2 steps passed through, some above did
        single = [run("one", scene="fst", latency_steps={"mean": 1.0, "max": 1}, tunneling=0)]
        self.assertNotIn("per configuration", claims.latency_bound(single, None)[0])

    def test_every_nth_jitter_rate(self):
        runs = [run(f"full s{s}", "full", "none", seed=s, jitter=0.01) for s in SEEDS]
        runs += [run(f"n s{s}", "every_nth", "none", seed=s, jitter=0.5 if s else 0.05) for s in SEEDS]
        ctx = SimpleNamespace(runs=runs, reference=lambda r: pairing.reference(r, runs))
        measured, verdict = claims.jitters([r for r in runs if r.method == "every_nth"], ctx)
        self.assertIn("jitter above 10x full's in 4/5 runs (80 %, 95 % CI 38-96 %)", measured)
        self.assertTrue(verdict.startswith("partly: 4/5"), verdict)


class HashSensitivity(unittest.TestCase):
    C = {"cell_size_m": 0.01, "mean_edge_m": 0.01, "table_size": 211, "tets": 100, "hash": "mixed",
         "response": "implicit"}

    def runs(self):
        c = self.C
        return [run("default", "full", "none", overrides=(), collision=c, recall_mean=1.0,
                    handling_ms=handling(1.0), max_task_work=5000),
                run("cell2", "full", "none", overrides=("collision.cell_size=auto*2",), collision=dict(c, cell_size_m=0.02),
                    recall_mean=0.9, handling_ms=handling(0.8), max_task_work=4000),
                run("cellhalf", "full", "none", overrides=("collision.cell_size=0.005",),
                    collision=dict(c, cell_size_m=0.005), recall_mean=0.8, handling_ms=handling(1.5),
                    max_task_work=6000),
                run("table4", "full", "none", overrides=("collision.table_size=auto*4",),
                    collision=dict(c, table_size=809), recall_mean=1.0, handling_ms=handling(0.9), max_task_work=5000)] + [
                run(f"i cell2 s{s}", budget="full/3", seed=s, overrides=("collision.cell_size=auto*2",),
                    collision=dict(c, cell_size_m=0.02), recall_mean=0.5 + 0.1 * s, handling_ms=handling(0.3),
                    max_task_us={"p50": 10.0, "p99": 20.0 + s, "max": 40.0}) for s in SEEDS]

    def test_the_detectors_automatic_table_size(self):
        self.assertEqual([hash_sensitivity.next_prime(n) for n in (0, 2, 3, 4, 201, 4183)], [2, 2, 3, 5, 211, 4201])
        self.assertEqual(hash_sensitivity.automatic_table_size(2091), 4201)  # the fixture's fast_sphere_torus

    def test_factors_from_what_the_run_resolved(self):
        default, cell2, cellhalf, table4, *_ = self.runs()
        self.assertEqual([hash_sensitivity.varied(r) for r in (default, cell2, cellhalf, table4)],
                         [None, "cell_size", "cell_size", "table_size"])
        self.assertEqual(hash_sensitivity.factor(default, "cell_size"), 1.0)
        self.assertEqual(hash_sensitivity.factor(default, "table_size"), 1.0)  # 211 = next_prime(2 * 100 + 1)
        self.assertEqual(hash_sensitivity.factor(cellhalf, "cell_size"), 0.5)  # a size in metres, placed
        self.assertAlmostEqual(hash_sensitivity.factor(table4, "table_size"), 809 / 211)

    def test_without_the_collision_block_the_override_places_the_run(self):
        old = run("old", overrides=("collision.table_size=auto*0.25",), perturbation=None)
        self.assertEqual(hash_sensitivity.factor(old, "table_size"), 0.25)
        self.assertEqual(hash_sensitivity.factor(run("old default", overrides=()), "cell_size"), 1.0)
        self.assertIsNone(hash_sensitivity.factor(run("old metres", overrides=("collision.cell_size=0.01",)),
                                                  "cell_size"))

    def test_points_medians_and_the_largest_tasks_fallback(self):
        runs = self.runs()
        pts = hash_sensitivity.points(runs, "plates20", "cell_size", "recall_mean")
        self.assertEqual(list(pts), ["full", "interruptible @ full/3"])
        self.assertEqual([(x, y, n) for x, y, _, _, n in pts["full"]], [(0.5, 0.8, 1), (1.0, 1.0, 1), (2.0, 0.9, 1)])
        [(x, y, lo, hi, n)] = pts["interruptible @ full/3"]
        self.assertEqual((x, n), (2.0, 5))
        self.assertAlmostEqual(y, 0.7)
        self.assertTrue(lo <= y <= hi)
        table = hash_sensitivity.points(runs, "plates20", "table_size", "recall_mean")
        self.assertEqual([(x, y) for x, y, *_ in table["full"]], [(1.0, 1.0), (809 / 211, 1.0)])
        task = hash_sensitivity.points(runs, "plates20", "cell_size", hash_sensitivity.TASK)
        self.assertEqual([y for _, y, *_ in task["full"]], [6000, 5000, 4000])  # work units: no wall budget
        self.assertEqual(task["interruptible @ full/3"][0][1], 22.0)  # the median p99 in µs
        self.assertEqual(hash_sensitivity.task_key(runs[:1]), hash_sensitivity.TASK_WORK)
        self.assertEqual(hash_sensitivity.task_key(runs[-1:]), hash_sensitivity.TASK_US)

    def test_drawn_or_missing(self):
        runs = self.runs()
        with tempfile.TemporaryDirectory() as out:
            ctx = context(out, runs)
            section = hash_sensitivity.draw(ctx, runs)
            self.assertIsNone(section.missing)
            self.assertTrue(os.path.exists(os.path.join(out, section.image)))
            self.assertIn("1 to 5 runs (seeds) per configuration", section.caption)
            self.assertIn("max_task_work", section.caption)
            missing = hash_sensitivity.draw(ctx, runs[:1])
            self.assertIn("collision.cell_size", missing.missing)

    def test_registered_like_the_others(self):
        self.assertIn("hash_sensitivity", dict(figures.discover()))
        self.assertEqual(dict(figures.discover())["hash_sensitivity"].SCOPE, "declared")


class EveryFigureWithRepeats(unittest.TestCase):
    def test_every_caption_counts_its_runs(self):
        """Every figure drawn from repeated runs says how many runs a configuration rests on."""
        runs = []
        for s in SEEDS:
            common = dict(seed=s, steps=series(0.1), figures_=("jitter", "settling", "latency", "haptic", "scaling",
                                                               "hash_sensitivity"),
                          collision=HashSensitivity.C)
            runs.append(run(f"full s{s}", "full", "none", handling_ms=handling(0.3), jitter=0.01, recall_mean=1.0,
                            recall_min=1.0, settled_max_speed_median=0.01, tunneling=0,
                            top_centre_height_m={"initial": 1.0, "final": 1.0}, latency_steps={"mean": 0, "max": 0},
                            probe_force_change_rms=0.1, **common))
            runs.append(run(f"i s{s}", budget="ms:0.1", handling_ms=handling(0.1 + 0.01 * s), jitter=0.02,
                            recall_mean=0.9, recall_min=0.5, settled_max_speed_median=0.02, tunneling=0,
                            overshoot_pct={"p50": 1.0, "p99": 3.0 + s, "max": 9.0},
                            overshoot_cpu_pct={"p50": 1.0, "p99": 2.0, "max": 4.0},
                            timing={"verdict": "quiet", "floor": {"windows": 40, "overshoot_pct": {"p99": 1.5 + s}}},
                            top_centre_height_m={"initial": 1.0, "final": 1.0}, latency_steps={"mean": 1, "max": 2},
                            probe_force_change_rms=0.2, **dict(common, overrides=JITTER_SETS + [
                                "collision.cell_size=auto*2"])))
        with tempfile.TemporaryDirectory() as out:
            ctx = context(out, runs)
            for name, module in figures.discover():
                if name == "animation":
                    continue  # needs recorded frames
                sections = module.draw(ctx, figures.runs_in_scope(name, module, runs))
                for section in sections if isinstance(sections, list) else [sections]:
                    if section.missing:
                        continue
                    self.assertRegex(section.caption, r"runs \(seeds\) per configuration|One run per configuration",
                                     name)
                    self.assertIn("velocity +-0.001 m/s", section.caption, name)


if __name__ == "__main__":
    unittest.main()
