"""Repeats (issue 21): the statistics against the C++ side's reference values, runs grouped by configuration
(everything but the seed), bars and latency drawn as medians with intervals, verdicts as rates with Wilson
intervals, a jittered full run is a reference and not a noise floor, and the hash-sensitivity figure's data.
Run by ctest with /usr/bin/python3."""
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

from tcbench_report import claims, pairing, statistics  # noqa: E402
from tcbench_report.figures import latency  # noqa: E402
from tcbench_report.loader import Run  # noqa: E402

JITTER = ["perturb.velocity=0.1", "perturb.position=0.005"]


def run(name, method="interruptible", budget="full-work/4", seed=0, overrides=JITTER, scene="fast_sphere_torus",
        collision=None, **summary):
    kind = "none" if budget == "none" else "work" if budget.startswith("full-work/") else "wall_ms"
    record = {"scene": scene, "method": method, "seed": seed, "response": "implicit", "steps": 150,
              "overrides": list(overrides), "settings": {}, "budget": {"kind": kind, "label": budget},
              "summary": summary, "status": "ok",
              "perturbation": {"jitter": {"position_m": 0.005, "velocity_m_per_s": 0.1, "rotation_rad": 0,
                                          "material_rel": 0}}}
    if collision:
        record["collision"] = collision
    return Run("/nonexistent", record, name)


class Statistics(unittest.TestCase):
    def test_the_values_tcbench_prints(self):
        # tests/experiments/statistics/statistics_test.cpp checks the C++ side against the same numbers.
        self.assertEqual(statistics.mix64(0), 0xE220A8397B1DCDAF)
        self.assertEqual(statistics.uniform01(0, 0, 0), 0.13870941014555427)
        self.assertEqual(statistics.bootstrap_median([3.0, 1.0, 4.0, 1.0, 5.0, 9.0, 2.0, 6.0]), (3.5, 1.0, 6.0))
        self.assertEqual(statistics.bootstrap_median([2.0]), (2.0, None, None))
        self.assertEqual(statistics.bootstrap_median([1.5] * 4), (1.5, 1.5, 1.5))
        lo, hi = statistics.wilson_interval(0, 10)
        self.assertEqual(lo, 0.0)
        self.assertAlmostEqual(hi, 0.2775327998628892, places=12)
        lo, hi = statistics.wilson_interval(5, 10)
        self.assertAlmostEqual(lo, 0.236593090512564, places=12)
        self.assertAlmostEqual(hi, 0.7634069094874361, places=12)
        self.assertEqual(statistics.wilson_interval(10, 10)[1], 1.0)
        self.assertIsNone(statistics.wilson_interval(0, 0))
        self.assertEqual(statistics.rate_text(4, 5), "4/5 (80 %, 95 % CI 38-96 %)")
        self.assertEqual(statistics.rate_text(1, 1), "1/1")


class Repeats(unittest.TestCase):
    def test_grouped_by_everything_but_the_seed(self):
        runs = [run(f"i-s{s}", seed=s) for s in (2, 0, 1)] + [run("i8", budget="full-work/8"),
                                                              run("plain", overrides=())]
        groups = statistics.repeats(runs)
        self.assertEqual([[r.name for r in g] for g in groups], [["i-s0", "i-s1", "i-s2"], ["i8"], ["plain"]])
        self.assertIn("1 to 3 runs (seeds) per configuration", statistics.runs_note(runs))
        self.assertIn("velocity +-0.1 m/s", statistics.runs_note(runs))
        self.assertIn("One run per configuration", statistics.runs_note(runs[3:4]))

    def test_a_jittered_full_run_is_a_reference_not_a_noise_floor(self):
        full = run("full", "full", budget="none")
        self.assertTrue(pairing.is_reference(full))
        self.assertFalse(pairing.is_noise_floor(full))
        floor = run("floor", "full", budget="none", overrides=["perturb.position=1e-09"],
                    divergence={"compared_steps": 8})
        self.assertTrue(pairing.is_noise_floor(floor))

    def test_full_with_a_setting_of_ours_is_not_the_reference(self):
        kept = run("kept", "full", budget="none")
        kept.record["method_label"] = "full(keep_table=true)"
        self.assertFalse(pairing.is_reference(kept))
        kept.record["method_label"] = "full"  # every setting at its default
        self.assertTrue(pairing.is_reference(kept))


class LatencyBars(unittest.TestCase):
    def test_one_bar_per_configuration_with_median_interval_and_tunnelling_count(self):
        runs = [run(f"s{s}", seed=s, latency_steps={"mean": 2.0, "max": float(m)}, tunneling=int(m > 30))
                for s, m in enumerate((10, 20, 30, 40, 50))]
        [(first, group, median, lo, hi, mean, tunnelled)] = latency.bars(runs)
        self.assertEqual((first.name, len(group), median, mean, tunnelled), ("s0", 5, 30.0, 2.0, 2))
        self.assertLessEqual(lo, median)
        self.assertGreaterEqual(hi, median)


class Verdicts(unittest.TestCase):
    def test_counts_carry_their_wilson_interval_when_runs_repeat(self):
        self.assertEqual(claims.per_budget_verdict([("full-work/3", 5, 5)]),
                         f"{claims.HOLDS} at its budget (full-work/3 (5/5 (100 %, 95 % CI 57-100 %) runs))")
        self.assertIn("full-work/6 in 4/5 (80 %, 95 % CI 38-96 %) runs",
                      claims.per_budget_verdict([("full-work/3", 5, 5), ("full-work/6", 4, 5)]))
        self.assertEqual(claims.per_budget_verdict([("full-work/3", 1, 1)]),
                         f"{claims.HOLDS} at its budget (full-work/3)")  # one run: as before
        self.assertEqual(claims.share(0, 10), f"{claims.FAILS} (0/10 (0 %, 95 % CI 0-28 %) runs)")


if __name__ == "__main__":
    unittest.main()
