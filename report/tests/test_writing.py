"""How the report writes: every figure to a temporary name beside it, renamed into place, so an interrupted
report leaves no half-written figure; a `report` or `figures` path that is a file is bad input (exit 2, one line),
not a traceback. Run by ctest with /usr/bin/python3."""
import io
import os
import shutil
import sys
import tempfile
import unittest
from contextlib import redirect_stderr

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

from tcbench_report import main as report_main  # noqa: E402
from tcbench_report.context import Context  # noqa: E402
from tcbench_report.loader import Results  # noqa: E402


class WriteFigureTest(unittest.TestCase):
    def setUp(self):
        self.root = tempfile.mkdtemp()
        self.ctx = Context(Results(self.root), os.path.join(self.root, "report"))

    def tearDown(self):
        shutil.rmtree(self.root)

    def listing(self):
        return sorted(os.listdir(self.ctx.fig_dir))

    def test_the_figure_is_written_beside_its_name_then_renamed(self):
        seen = []

        def write(path):
            seen.append(path)
            self.assertTrue(path.endswith(".png"))  # matplotlib picks the format by the extension
            self.assertEqual(os.path.dirname(path), self.ctx.fig_dir)  # same file system: the rename is atomic
            with open(path, "w") as f:
                f.write("new")

        final = self.ctx.write_figure("a.png", write)
        self.assertEqual(final, os.path.join(self.ctx.fig_dir, "a.png"))
        self.assertNotEqual(seen[0], final)
        self.assertEqual(self.listing(), ["a.png"])
        with open(final) as f:
            self.assertEqual(f.read(), "new")

    def test_a_failed_write_keeps_the_old_figure_and_leaves_no_temporary_file(self):
        with open(os.path.join(self.ctx.fig_dir, "a.png"), "w") as f:
            f.write("old")

        def fail_halfway(path):
            with open(path, "w") as f:
                f.write("ha")
            raise RuntimeError("interrupted")

        with self.assertRaises(RuntimeError):
            self.ctx.write_figure("a.png", fail_halfway)
        self.assertEqual(self.listing(), ["a.png"])
        with open(os.path.join(self.ctx.fig_dir, "a.png")) as f:
            self.assertEqual(f.read(), "old")


class FiguresGoThroughWriteFigureTest(unittest.TestCase):
    """The figures' writers call write_figure, so none writes straight to its final name."""

    def setUp(self):
        self.root = tempfile.mkdtemp()
        self.ctx = Context(Results(self.root), os.path.join(self.root, "report"))
        self.written = []
        write_figure = self.ctx.write_figure

        def recording(name, write):
            self.written.append(name)
            return write_figure(name, write)

        self.ctx.write_figure = recording

    def tearDown(self):
        shutil.rmtree(self.root)

    def test_save_writes_both_formats_through_it(self):
        import matplotlib.pyplot as plt
        self.ctx.save(plt.figure(), "x", "Title", "caption", [])
        self.assertEqual(self.written, ["x.png", "x.svg"])
        self.assertEqual(sorted(os.listdir(self.ctx.fig_dir)), ["x.png", "x.svg"])

    def test_no_figure_module_writes_a_figure_itself(self):
        # The modules that write files: each must name write_figure and call no writer on a final path.
        figures = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tcbench_report", "figures")
        for name in sorted(os.listdir(figures)):
            if not name.endswith(".py"):
                continue
            with open(os.path.join(figures, name)) as f:
                text = f.read()
            with self.subTest(module=name):
                for writer in ("savefig(", ".save(", "copyfile(", "copy("):
                    for line in text.splitlines():
                        if writer in line and "write_figure" not in line and "ctx.save(" not in line:
                            self.fail(f"{name}: '{line.strip()}' writes a figure without write_figure")


class BadOutputPathTest(unittest.TestCase):
    def setUp(self):
        self.root = tempfile.mkdtemp()

    def tearDown(self):
        shutil.rmtree(self.root)

    def run_main(self, root):
        err = io.StringIO()
        with redirect_stderr(err):
            code = report_main.main(["make_report.py", root])
        return code, err.getvalue()

    def test_a_file_given_as_the_results_directory_is_named_as_such(self):
        path = os.path.join(self.root, "t.sh")
        open(path, "w").close()
        code, err = self.run_main(path)
        self.assertEqual(code, 2)
        self.assertIn("not a directory", err)

    def test_a_file_where_the_report_folder_goes_is_bad_input(self):
        for folder in ("report", os.path.join("report", "figures")):
            with self.subTest(folder=folder):
                report = os.path.join(self.root, "report")
                if os.path.isfile(report):
                    os.remove(report)
                shutil.rmtree(report, ignore_errors=True)
                if folder != "report":
                    os.makedirs(os.path.join(self.root, "report"))
                open(os.path.join(self.root, folder), "w").close()
                code, err = self.run_main(self.root)
                self.assertEqual(code, 2)
                self.assertEqual(err.strip().splitlines(),
                                 [f"tcbench report: {os.path.join(self.root, folder)}: is a file, "
                                  "where the report writes a folder"])


if __name__ == "__main__":
    unittest.main()
