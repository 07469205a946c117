"""Claims about the paper's method judge only runs with the paper's task granularity: our settings
fine_tasks, reserve_apply, apply_first, widen_stale, rehash_stale and predict_tasks make a run ours, drawn beside the paper's, never judged as it."""
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

from tcbench_report.claims import CLAIMS, PAPER_TASKS, Select  # noqa: E402
from tcbench_report.loader import Run  # noqa: E402


def run(name, method, settings=None):
    record = {"method": method, "summary": {"overshoot_pct": {"p99": 1.0}}, "budget": {"kind": "wall_ms"}}
    if settings is not None:
        record["settings"] = settings
    return Run("/nonexistent", record, name)


class PaperTasksOnly(unittest.TestCase):
    def test_our_settings_are_left_out_and_absent_ones_count_as_default(self):
        runs = [run("paper", "interruptible", {"fine_tasks": False, "reserve_apply": False}),
                run("ours", "interruptible", {"fine_tasks": True, "reserve_apply": True}),
                run("reserve only", "interruptible", {"fine_tasks": False, "reserve_apply": True}),
                run("widened only", "interruptible", {"widen_stale": True}),
                run("rehashed only", "interruptible", {"rehash_stale": True}),
                run("predicted only", "interruptible", {"predict_tasks": True}),
                run("applied first only", "interruptible", {"apply_first": True}),
                run("before the settings existed", "interruptible", {}),
                run("schema 1", "interruptible")]
        chosen = Select(methods=("interruptible",), settings=PAPER_TASKS)(runs)
        self.assertEqual([r.name for r in chosen], ["paper", "before the settings existed", "schema 1"])

    def test_every_claim_about_interruptible_uses_the_paper_tasks(self):
        for claim in CLAIMS:
            if "interruptible" in claim.select.methods:
                self.assertEqual(claim.select.settings, PAPER_TASKS, claim.id)


if __name__ == "__main__":
    unittest.main()
