"""The viewer's screenshot in the report: copied and captioned with the command that opens the same runs when
reproduce took it, the reason said when it could not, nothing when reproduce did not run. Run by ctest with
/usr/bin/python3."""
import json
import os
import shutil
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

from tcbench_report.context import Context  # noqa: E402
from tcbench_report.figures import viewer  # noqa: E402
from tcbench_report.loader import Results  # noqa: E402

PNG = b"\x89PNG\r\n\x1a\n" + b"\0" * 32  # the report copies the file; it never decodes it


class ViewerFigureTest(unittest.TestCase):
    def setUp(self):
        self.root = tempfile.mkdtemp()
        os.makedirs(os.path.join(self.root, "viewer"))

    def tearDown(self):
        shutil.rmtree(self.root)

    def record(self, **fields):
        with open(os.path.join(self.root, "viewer", "viewer.json"), "w") as f:
            json.dump({"runs": ["/r/full", "/r/interruptible"], "step": 300, **fields}, f)

    def draw(self):
        return viewer.draw(Context(Results(self.root), os.path.join(self.root, "report")), [])

    def test_the_screenshot_is_copied_and_says_how_to_open_the_runs(self):
        with open(os.path.join(self.root, "viewer", "shot.png"), "wb") as f:
            f.write(PNG)
        self.record(status="ok", screenshot="shot.png", reason="")
        section = self.draw()
        self.assertIsNone(section.missing)
        with open(os.path.join(self.root, "report", section.image), "rb") as f:
            self.assertEqual(f.read(), PNG)
        self.assertIn("tcbench view /r/full /r/interruptible", section.caption)
        self.assertIn("step 300", section.caption)

    def test_a_screenshot_that_could_not_be_taken_says_why(self):
        self.record(status="skipped", screenshot=None, reason="no browser could start here")
        section = self.draw()
        self.assertIn("no browser could start here", section.missing)

    def test_a_named_screenshot_that_is_gone_is_not_drawn(self):
        self.record(status="ok", screenshot="gone.png", reason="")
        self.assertIn("gone.png is missing", self.draw().missing)

    def test_results_without_screenshot_or_recording_get_nothing(self):
        self.assertEqual(self.draw(), [])

    def test_every_recorded_run_gets_its_command(self):
        class Run:
            def __init__(self, name, directory):
                self.name, self.dir = name, directory
        recorded = os.path.join(self.root, "sweep", "a")
        os.makedirs(recorded)
        open(os.path.join(recorded, "replay.json"), "w").close()
        plain = os.path.join(self.root, "sweep", "b")
        os.makedirs(plain)
        sections = viewer.draw(Context(Results(self.root), os.path.join(self.root, "report")),
                               [Run("sweep/a", recorded), Run("sweep/b", plain)])
        self.assertEqual(len(sections), 1)
        self.assertIn(f"sweep/a: tcbench view {recorded}", sections[0].caption)
        self.assertNotIn("sweep/b", sections[0].caption)
        self.assertIn("1 recorded run open", sections[0].caption)


if __name__ == "__main__":
    unittest.main()
