"""The statistics of repeats (issue 21): the counter-based generator, the Wilson interval of a rate and the
bootstrap interval of a median, against values worked out by hand (in the comments) and the reference values
the C++ side (tests/experiments/statistics/statistics_test.cpp) checks too; how runs are grouped into
configurations; the jitter a run's seed drew, in the new and the older run.json forms. Run by ctest with
/usr/bin/python3."""
import math
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

from tcbench_report import pairing, statistics  # noqa: E402
from tcbench_report.loader import Run  # noqa: E402

# z for 95 %, and z^2 = 3.841458820694124 (the chi-square 95 % quantile with one degree of freedom).
Z = 1.959963984540054


def run(name, method="interruptible", budget="full-work/3", seed=0, overrides=(), perturbation=None, scene="plates20",
        steps=100, settings=None, response="implicit", mesh_order=None, **summary):
    kind = "none" if budget == "none" else "work"
    record = {"scene": scene, "method": method, "seed": seed, "response": response, "steps": steps,
              "overrides": list(overrides), "settings": settings or {}, "budget": {"kind": kind, "label": budget},
              "summary": summary, "status": "ok"}
    if perturbation is not None:
        record["perturbation"] = perturbation
    if mesh_order is not None:
        record["world"] = {"mesh_order": mesh_order}
    return Run("/nonexistent", record, name)


def jitter(position=0.0, velocity=0.0, rotation=0.0, material=0.0):
    return {"position_m": position, "velocity_m_per_s": velocity, "rotation_rad": rotation, "material_rel": material}


class Generator(unittest.TestCase):
    def test_splitmix_finaliser(self):
        # SplitMix64's output for the state 0 after one increment: the published first value of
        # splitmix64 seeded with 0.
        self.assertEqual(statistics.mix64(0), 0xE220A8397B1DCDAF)

    def test_counter_bits_chain_the_three_counters(self):
        m = statistics.mix64
        self.assertEqual(statistics.counter_bits(7, 3, 11), m(m(m(7) ^ 3) ^ 11))
        self.assertNotEqual(statistics.counter_bits(7, 3, 11), statistics.counter_bits(7, 11, 3))

    def test_uniform01_is_the_top_53_bits(self):
        self.assertEqual(statistics.uniform01(0, 0, 0), 0.13870941014555427)  # the C++ side's value
        for r in range(50):
            for j in range(5):
                u = statistics.uniform01(statistics.BOOTSTRAP_SEED, r, j)
                self.assertTrue(0.0 <= u < 1.0)
                self.assertEqual(u * 2 ** 53, statistics.counter_bits(statistics.BOOTSTRAP_SEED, r, j) >> 11)

    def test_the_seed_spells_tcbench(self):
        self.assertEqual(statistics.BOOTSTRAP_SEED.to_bytes(7, "big"), b"tcbench")


class Wilson(unittest.TestCase):
    def test_none_of_ten(self):
        # p = 0: centre = (z^2/2n) / (1 + z^2/n) and half the same, so hi = 2 centre = z^2 / (n + z^2)
        # = 3.841458820694124 / 13.841458820694124 = 0.27753279986...; lo exactly 0.
        lo, hi = statistics.wilson_interval(0, 10)
        self.assertEqual(lo, 0.0)
        self.assertAlmostEqual(hi, Z * Z / (10 + Z * Z), places=14)
        self.assertAlmostEqual(hi, 0.2775327998628892, places=12)

    def test_half_of_ten(self):
        # p = 1/2: centre = 1/2 exactly; half = z sqrt(1/40 + z^2/400) / (1 + z^2/10)
        # = 1.959964 * sqrt(0.0346036) / 1.3841459 = 0.2634069...: (0.2365931, 0.7634069).
        lo, hi = statistics.wilson_interval(5, 10)
        half = Z * math.sqrt(1 / 40 + Z * Z / 400) / (1 + Z * Z / 10)
        self.assertAlmostEqual(lo, 0.5 - half, places=14)
        self.assertAlmostEqual(hi, 0.5 + half, places=14)
        self.assertAlmostEqual(lo, 0.236593090512564, places=12)
        self.assertAlmostEqual(hi, 0.7634069094874361, places=12)

    def test_all_of_ten(self):
        # p = 1: the mirror of 0/10: lo = n / (n + z^2) = 10 / 13.8414588 = 0.72246720...; hi exactly 1.
        lo, hi = statistics.wilson_interval(10, 10)
        self.assertAlmostEqual(lo, 10 / (10 + Z * Z), places=14)
        self.assertAlmostEqual(lo, 0.7224672001371107, places=12)
        self.assertEqual(hi, 1.0)

    def test_four_of_five_and_no_runs(self):
        lo, hi = statistics.wilson_interval(4, 5)  # the C++ side's values: 38-96 %
        self.assertAlmostEqual(lo, 0.37553462976252533, places=12)
        self.assertAlmostEqual(hi, 0.9637758913675698, places=12)
        self.assertIsNone(statistics.wilson_interval(0, 0))
        for n in range(1, 12):
            for k in range(n + 1):
                lo, hi = statistics.wilson_interval(k, n)
                self.assertTrue(0.0 <= lo <= k / n <= hi <= 1.0, (k, n))

    def test_words(self):
        self.assertEqual(statistics.outcome_text("standing", 4, 5), "standing in 4/5 runs (80 %, 95 % CI 38-96 %)")
        self.assertEqual(statistics.outcome_text("standing", 1, 1), "standing in 1/1 runs")
        self.assertEqual(statistics.rate_text(0, 10), "0/10 (0 %, 95 % CI 0-28 %)")


class Bootstrap(unittest.TestCase):
    VALUES = [3.0, 1.0, 4.0, 1.0, 5.0, 9.0, 2.0, 6.0]

    def test_median(self):
        self.assertIsNone(statistics.median([]))
        self.assertEqual(statistics.median([3.0]), 3.0)
        self.assertEqual(statistics.median([4.0, 1.0]), 2.5)
        self.assertEqual(statistics.median([5.0, 1.0, 3.0]), 3.0)
        self.assertEqual(statistics.median(self.VALUES), 3.5)  # sorted 1 1 2 3 | 4 5 6 9: (3 + 4) / 2

    def test_reference_values(self):
        # The C++ side (bootstrap_median in experiments/statistics/) checks the same three numbers; an
        # independent transcription of the definition gives them too.
        self.assertEqual(statistics.bootstrap_median_interval(self.VALUES), (3.5, 1.0, 6.0))
        self.assertIs(statistics.bootstrap_median, statistics.bootstrap_median_interval)

    def test_indices_50_and_1949(self):
        n, seed = len(self.VALUES), statistics.BOOTSTRAP_SEED
        medians = sorted(statistics.median([self.VALUES[math.floor(statistics.uniform01(seed, r, j) * n)]
                                            for j in range(n)]) for r in range(2000))
        self.assertEqual(statistics.bootstrap_median_interval(self.VALUES)[1:], (medians[50], medians[1949]))

    def test_equal_values_give_a_zero_width_interval(self):
        self.assertEqual(statistics.bootstrap_median_interval([1.5] * 4), (1.5, 1.5, 1.5))
        self.assertEqual(statistics.bootstrap_median_interval([0.25] * 7), (0.25, 0.25, 0.25))

    def test_the_interval_holds_the_median(self):
        for n in range(2, 12):
            values = [statistics.uniform01(99, n, j) * 10 for j in range(n)]
            median, lo, hi = statistics.bootstrap_median_interval(values)
            self.assertTrue(min(values) <= lo <= median <= hi <= max(values), values)

    def test_below_two_values(self):
        self.assertEqual(statistics.bootstrap_median_interval([2.0]), (2.0, None, None))
        self.assertEqual(statistics.bootstrap_median_interval([]), (None, None, None))
        self.assertEqual(statistics.summarise([None, 2.0]), (2.0, None, None, 1))
        self.assertEqual(statistics.summarise([None]), (None, None, None, 0))

    def test_fewer_resamples_and_another_seed(self):
        # R = 40: entries floor(1) = 1 and ceil(39) - 1 = 38 of the sorted resample medians.
        n = len(self.VALUES)
        medians = sorted(statistics.median([self.VALUES[math.floor(statistics.uniform01(5, r, j) * n)]
                                            for j in range(n)]) for r in range(40))
        self.assertEqual(statistics.bootstrap_median_interval(self.VALUES, 40, 5), (3.5, medians[1], medians[38]))

    def test_text(self):
        self.assertEqual(statistics.estimate_text(0.5, None, None, 1), "0.5")
        self.assertEqual(statistics.estimate_text(0.5, 0.25, 0.75, 5), "median 0.5 [0.25, 0.75] (n=5)")
        self.assertEqual(statistics.estimate_text(None, None, None, 0), "n/a")


class Configurations(unittest.TestCase):
    JITTERED = ["perturb.velocity=0.001", "perturb.material=0.05"]

    def test_everything_but_the_seed(self):
        a = run("a", seed=0, overrides=self.JITTERED)
        b = run("b", seed=3, overrides=list(reversed(self.JITTERED)))  # the order of the --set strings
        self.assertEqual(statistics.configuration(a), statistics.configuration(b))
        # A run that says "file" is one of a run recorded before the field.
        self.assertEqual(statistics.configuration(a),
                         statistics.configuration(run("b2", mesh_order="file", overrides=self.JITTERED)))
        for other in (run("m", mesh_order="curve", overrides=self.JITTERED),
                      run("c", budget="full-work/6", overrides=self.JITTERED),
                      run("d", method="full", budget="none", overrides=self.JITTERED),
                      run("e", response="explicit", overrides=self.JITTERED),
                      run("f", steps=300, overrides=self.JITTERED),
                      run("g", settings={"fine_tasks": True}, overrides=self.JITTERED),
                      run("h", scene="stack", overrides=self.JITTERED),
                      run("i")):
            self.assertNotEqual(statistics.configuration(a), statistics.configuration(other), other.name)

    def test_pairing_folds_the_mesh_order_override_into_the_recorded_order(self):
        curve = run("c1", mesh_order="curve")
        self.assertEqual(pairing.setup(curve),
                         pairing.setup(run("c2", mesh_order="curve", overrides=["scene.mesh_order=curve"])))
        self.assertEqual(pairing.setup(run("f1")),
                         pairing.setup(run("f2", mesh_order="file", overrides=["scene.mesh_order=file"])))
        self.assertNotEqual(pairing.setup(curve), pairing.setup(run("f3", mesh_order="file")))

    def test_groups_sorted_by_seed_in_order_of_appearance(self):
        runs = [run("s3", seed=3), run("x", budget="full-work/6"), run("s1", seed=1), run("s0", seed=0)]
        self.assertEqual([[r.name for r in g] for g in statistics.repeats(runs)], [["s0", "s1", "s3"], ["x"]])

    def test_noise_floor_runs_are_not_repeats_of_the_full_run(self):
        full = [run(f"full s{s}", "full", "none", seed=s) for s in range(3)]
        floor = [run(f"floor s{s}", "full", "none", seed=s, overrides=["perturb.position=1e-09"],
                     divergence={"compared_steps": 8}) for s in range(3)]
        groups = statistics.repeats(full + floor)
        self.assertEqual([[r.name for r in g] for g in groups],
                         [["full s0", "full s1", "full s2"], ["floor s0", "floor s1", "floor s2"]])
        self.assertTrue(all(pairing.is_noise_floor(r) for r in groups[1]))


class Jitter(unittest.TestCase):
    def test_the_global_jitter_in_words(self):
        r = run("r", perturbation={"jitter": jitter(velocity=0.1, material=0.05), "bodies": [
            {"name": "sphere", "jitter": jitter(velocity=0.1, material=0.05), "offset_m": [0, 0, 0],
             "velocity_m_per_s": [0.01, -0.02, 0.03], "rotation_rad": [0, 0, 0], "youngs_modulus_factor": 1.02}]})
        self.assertEqual(statistics.jitter_text(r), "velocity +-0.1 m/s, Young's modulus +-0.05 relative")

    def test_bodies_only(self):
        r = run("r", perturbation={"jitter": jitter(), "bodies": [
            {"name": "a", "jitter": jitter(position=0.002)}, {"name": "b", "jitter": jitter(position=0.005)}]})
        self.assertEqual(statistics.jitter_text(r), "position +-0.005 m")

    def test_older_and_missing_records_state_none(self):
        self.assertEqual(statistics.jitter_text(run("none")), "")
        old = run("old", perturbation={"position_m": 1e-9, "offsets_m": [[1e-10, 0, 0]]})
        self.assertEqual(statistics.jitter_text(old), "")
        self.assertEqual(statistics.jitter_text(run("zero", perturbation={"jitter": jitter(), "bodies": []})), "")

    def test_captions_count_runs_and_state_the_jitter(self):
        drawn = {"jitter": jitter(velocity=0.001), "bodies": []}
        runs = [run(f"s{s}", seed=s, perturbation=drawn) for s in range(5)]
        note = statistics.runs_note(runs)
        self.assertIn("n = 5 runs (seeds) per configuration: each point or bar is their median", note)
        self.assertIn("velocity +-0.001 m/s", note)
        self.assertIn("thin curves", statistics.runs_note(runs, "each seed drawn as thin curves"))
        self.assertIn("One run per configuration", statistics.runs_note(runs[:1]))
        # a noise-floor run's nudge is the divergence figure's business, not a jitter of the repeats
        floor = run("floor", "full", "none", overrides=["perturb.position=1e-09"], divergence={"compared_steps": 8},
                    perturbation={"jitter": jitter(position=1e-9), "bodies": []})
        self.assertNotIn("1e-09", statistics.runs_note([floor]))
        self.assertEqual(statistics.runs_note([]), "")


if __name__ == "__main__":
    unittest.main()
