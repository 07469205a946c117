"""tcbench report DIR: figures, summary.md and index.html from a results directory.

Reads every run.json (and, for time series, steps.csv) beneath DIR and every
sweep.json naming runs and the figures they feed; never runs a simulation.
Writes DIR/report/{index.html, summary.md, figures/*.png, *.svg} and, where a
sweep declares the animation and runs recorded frames, one GIF per scene. Each
figure names the runs it was drawn from and the build and machine they came
from; a figure without data says why instead of being drawn empty.

Exit status: 0 written; 2 bad input (no such directory, no complete run).
"""
import os
import sys
import traceback

from . import claims, figures, loader, render
from .context import Context


def draw_all(ctx):
    """(sections, notes): every figure's sections, and what the reader should know about the rest."""
    sections, notes, undeclared = [], [], []
    modules = figures.discover()
    for name, module in modules:
        runs = figures.runs_in_scope(name, module, ctx.runs)
        if module.SCOPE == "declared" and not runs:
            undeclared.append(name)  # not asked for: a plain `tcbench run` feeds only the generic figures
            continue
        try:
            drawn = module.draw(ctx, runs)
        except Exception as error:  # one broken figure must not cost the others
            traceback.print_exc()
            drawn = ctx.missing(getattr(module, "TITLE", name), f"the figure failed ({type(error).__name__}: {error})")
        sections += drawn if isinstance(drawn, list) else [drawn]
    if undeclared:
        notes.append("Scene-specific figures no sweep here declares (a sweep file's figures = [...]): "
                     + ", ".join(undeclared) + ".")
    known = {name for name, _ in modules}
    unknown = sorted({f for s in ctx.results.sweeps for f in s.figures} - known)
    if unknown:
        notes.append("Sweeps declare figures this report does not have: " + ", ".join(unknown) + ".")
    return sections, notes


def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if len(argv) == 2 else 2
    root = argv[1]
    if not os.path.isdir(root):
        why = "not a directory" if os.path.exists(root) else "no such directory"
        print(f"tcbench report: {root}: {why}", file=sys.stderr)
        return 2
    out = os.path.join(root, "report")
    for folder in (out, os.path.join(out, "figures")):
        if os.path.exists(folder) and not os.path.isdir(folder):
            print(f"tcbench report: {folder}: is a file, where the report writes a folder", file=sys.stderr)
            return 2
    results = loader.load(root)
    for path, why in results.skipped:
        print(f"tcbench report: skipped {path}: {why}", file=sys.stderr)
    if not results.runs:
        print(f"tcbench report: {root}: no complete run.json beneath it", file=sys.stderr)
        return 2
    ctx = Context(results, out)
    sections, notes = draw_all(ctx)
    outcomes = claims.judge(ctx)
    render.write(out, render.document(results, sections, outcomes, notes))
    print(f"report: {len(results.runs)} runs -> {os.path.join(out, 'index.html')}")
    return 0
