"""The viewer's picture of a run pair (tcbench view), taken by tcbench reproduce.

reproduce writes DIR/viewer/viewer.json and, where a browser could start, the
screenshot it names: plates20's stack under full beside interruptible at
full-work/3, its last recorded frame, points coloured by the oracle's verdict.
The report copies the picture and says how to open the same runs live in the
viewer; where reproduce could not take it, the reason is said. Results that
reproduce did not make (no viewer.json) get nothing here.
"""
import json
import os
import shutil

from ..context import Section

TITLE = "Viewer: the stack under full beside interruptible"
ORDER = 10
SCOPE = "all"


def draw(ctx, runs):
    record_path = os.path.join(ctx.results.root, "viewer", "viewer.json")
    if not os.path.isfile(record_path):
        return []
    with open(record_path) as f:
        record = json.load(f)
    by_dir = {os.path.abspath(r.dir): r for r in runs if getattr(r, "dir", None)}
    shown = [by_dir.get(os.path.abspath(d)) for d in record.get("runs", [])]
    shown = [r for r in shown if r is not None]
    if record.get("status") != "ok" or not record.get("screenshot"):
        return ctx.missing(TITLE, f"tcbench reproduce took no screenshot: {record.get('reason') or 'no reason given'}")
    source = os.path.join(ctx.results.root, "viewer", record["screenshot"])
    if not os.path.isfile(source):
        return ctx.missing(TITLE, f"{source} is missing")
    target = os.path.join(ctx.fig_dir, "viewer_" + record["screenshot"])
    shutil.copyfile(source, target)
    command = "tcbench view " + " ".join(record.get("runs", []))
    caption = (f"The recorded frame at or before step {record.get('step')} of each run, as the viewer shows it: "
               "points the method held coloured by the oracle's verdict (green: both, red: the oracle only, "
               "missed; yellow: the method only), penetration vectors at five times the depth, and the per-step "
               f"plot under the views (handling time against the budget, recall, max depth, kinetic energy). "
               f"Open the same runs to play, scrub and toggle the overlays: {command}")
    return Section(TITLE, caption, shown, image=os.path.relpath(target, ctx.out))
