"""The neural experiment's files in the report: found beneath the root, drawn, and the three seed-002 claims
judged from them either way (active better, worse, mixed). Run by ctest with /usr/bin/python3."""
import json
import os
import shutil
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

from tcbench_report import claims, neural  # noqa: E402
from tcbench_report.claims import FAILS, HOLDS, INCONCLUSIVE, UNMEASURED  # noqa: E402
from tcbench_report.context import Context  # noqa: E402
from tcbench_report.figures import neural as neural_figure  # noqa: E402
from tcbench_report.loader import Results  # noqa: E402

HEADER = "preset,strategy,seed,labels,gradient_steps,test_codes,accuracy,fnr,fpr,precision,recall\n"
ALM_HEADER = ("preset,strategy,seed,margin,attempted,network_feasible,resolved,resolved_share,median_distance,"
              "mean_distance,median_reference_distance,median_distance_ratio,mean_evaluations\n")


def write(root, final, alm):
    """final: {(strategy, seed): (accuracy, fnr)} at 300 labels (and a bootstrap row at 100); alm: {strategy:
    resolved of 10}."""
    d = os.path.join(root, "7_neural")
    os.makedirs(d)
    with open(os.path.join(d, "learning.csv"), "w") as f:
        f.write(HEADER)
        for (strategy, seed), (acc, fnr) in final.items():
            f.write(f"finger_small,{strategy},{seed},100,400,50,0.7,0.5,0.1,0.8,0.5\n")
            f.write(f"finger_small,{strategy},{seed},300,1200,50,{acc},{fnr},0.1,0.8,{1 - fnr}\n")
    with open(os.path.join(d, "alm.csv"), "w") as f:
        f.write(ALM_HEADER)
        for strategy, resolved in alm.items():
            f.write(f"finger_small,{strategy},1,0,10,10,{resolved},{resolved / 10},0.3,0.3,0.5,0.6,100\n")
    with open(os.path.join(d, "neural.json"), "w") as f:
        json.dump({"build": {"git_sha": "abc"}, "machine": {"cpu": "test"},
                   "presets": [{"preset": "finger_small", "vertices": 464, "tets": 1512, "test_codes": 50,
                                "test_colliding": 17, "label_ms_per_code": 2.0, "detector_eval_us_median": 6.0}]}, f)


class Ctx:
    def __init__(self, root):
        self.results = Results(root)


def verdict(claim_id, root):
    claim = next(c for c in claims.CLAIMS if c.id == claim_id)
    return claim.rule([], Ctx(root))


class NeuralClaims(unittest.TestCase):
    def setUp(self):
        self.root = tempfile.mkdtemp()

    def tearDown(self):
        shutil.rmtree(self.root)

    def test_active_better_everywhere_holds(self):
        write(self.root, {("active", 1): (0.9, 0.1), ("active", 2): (0.92, 0.12), ("active", 3): (0.91, 0.1),
                          ("supervised", 1): (0.85, 0.2), ("supervised", 2): (0.88, 0.15),
                          ("supervised", 3): (0.9, 0.11)}, {"active": 9, "supervised": 2})
        measured, v = verdict("neural_active_accuracy", self.root)
        self.assertEqual(v, HOLDS)
        self.assertIn("active higher in 3/3", measured)
        self.assertEqual(verdict("neural_active_fnr", self.root)[1], HOLDS)
        measured, v = verdict("neural_alm_resolves", self.root)
        self.assertEqual(v, HOLDS)
        self.assertIn("9/10", measured)

    def test_two_seeds_are_too_few_to_hold(self):
        write(self.root, {("active", 1): (0.9, 0.1), ("active", 2): (0.92, 0.12),
                          ("supervised", 1): (0.85, 0.2), ("supervised", 2): (0.88, 0.15)}, {"active": 9, "supervised": 2})
        measured, v = verdict("neural_active_accuracy", self.root)
        self.assertEqual(v, INCONCLUSIVE)
        self.assertIn("active higher in 2/2", measured)

    def test_better_on_most_but_not_every_seed_is_inconclusive(self):
        write(self.root, {("active", s): (0.9, 0.1) for s in (1, 2, 3)} | {("active", 4): (0.8, 0.3)} |
              {("supervised", s): (0.85, 0.2) for s in (1, 2, 3, 4)}, {"active": 9, "supervised": 2})
        self.assertEqual(verdict("neural_active_accuracy", self.root)[1], INCONCLUSIVE)
        self.assertEqual(verdict("neural_active_fnr", self.root)[1], INCONCLUSIVE)

    def test_active_worse_fails_and_mixed_is_inconclusive(self):
        write(self.root, {("active", 1): (0.80, 0.1), ("active", 2): (0.95, 0.3),
                          ("supervised", 1): (0.85, 0.2), ("supervised", 2): (0.88, 0.15)}, {"active": 1, "supervised": 9})
        # accuracy: mean active 0.875 > 0.865 but only 1 of 2 seeds: inconclusive
        self.assertEqual(verdict("neural_active_accuracy", self.root)[1], INCONCLUSIVE)
        # fnr: mean active 0.2 > 0.175 (worse) and 1 of 2 seeds better: inconclusive
        self.assertEqual(verdict("neural_active_fnr", self.root)[1], INCONCLUSIVE)
        self.assertEqual(verdict("neural_alm_resolves", self.root)[1], FAILS)

    def test_clearly_worse_fails(self):
        write(self.root, {("active", s): (0.8, 0.3) for s in (1, 2, 3)} | {("supervised", s): (0.9, 0.1) for s in (1, 2, 3)},
              {"active": 4, "supervised": 4})
        self.assertEqual(verdict("neural_active_accuracy", self.root)[1], FAILS)
        self.assertEqual(verdict("neural_active_fnr", self.root)[1], FAILS)
        self.assertEqual(verdict("neural_alm_resolves", self.root)[1], INCONCLUSIVE)

    def test_a_few_codes_more_is_not_enough(self):
        write(self.root, {("active", 1): (0.9, 0.1), ("supervised", 1): (0.85, 0.2)}, {"active": 6, "supervised": 4})
        self.assertEqual(verdict("neural_alm_resolves", self.root)[1], INCONCLUSIVE)

    def test_no_results_is_not_measured(self):
        self.assertEqual(verdict("neural_active_accuracy", self.root), (UNMEASURED, UNMEASURED))
        self.assertEqual(verdict("neural_alm_resolves", self.root), (UNMEASURED, UNMEASURED))

    def test_the_figure_is_drawn_from_the_files(self):
        write(self.root, {("active", 1): (0.9, 0.1), ("supervised", 1): (0.85, 0.2)}, {"active": 6, "supervised": 4})
        ctx = Context(Results(self.root), os.path.join(self.root, "report"))
        sections = neural_figure.draw(ctx, [])
        self.assertEqual(len(sections), 1)
        self.assertTrue(os.path.exists(os.path.join(self.root, "report", sections[0].image)))
        self.assertIn("finger_small: 464 vertices", sections[0].caption)
        self.assertIn("6/10 resolved", sections[0].caption)
        found = neural.find(self.root)
        self.assertEqual(neural.final_rows(found[0], "finger_small")["active"][0]["labels"], 300)

    def test_without_files_the_figure_says_why(self):
        ctx = Context(Results(self.root), os.path.join(self.root, "report"))
        section = neural_figure.draw(ctx, [])
        self.assertIsNotNone(section.missing)


if __name__ == "__main__":
    unittest.main()
