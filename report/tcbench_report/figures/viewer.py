"""The viewer's picture of a run pair (tcbench view), taken by tcbench reproduce.

reproduce writes DIR/viewer/viewer.json and, where a browser could start, the
screenshot it names: plates20's stack under full beside interruptible at
full-work/3, its last recorded frame, points coloured by the oracle's verdict.
The report copies the picture and says how to open the same runs live in the
viewer; where reproduce could not take it, the reason is said. Either way the
section lists the command that opens each recorded run (a run made with
--record has a replay.json); results with neither get nothing here. A static
report cannot play a replay itself: a page opened from a file may not read
other files, so the runs open through `tcbench view`.
"""
import json
import os
import shutil

from ..context import Section

TITLE = "Viewer: the stack under full beside interruptible"
LISTED_RUNS = 24  # recorded runs named with their command; past that, counted
ORDER = 10
SCOPE = "all"


def recorded(runs):
    """'Recorded runs open in the viewer: ...' with one tcbench view command a run, or '' without any."""
    replays = sorted((r for r in runs if os.path.isfile(os.path.join(r.dir, "replay.json"))), key=lambda r: r.name)
    if not replays:
        return ""
    listed = "; ".join(f"{r.name}: tcbench view {r.dir}" for r in replays[:LISTED_RUNS])
    more = f"; and {len(replays) - LISTED_RUNS} more" if len(replays) > LISTED_RUNS else ""
    return (f"{len(replays)} recorded run{'s' if len(replays) != 1 else ''} open in the viewer "
            f"(two at once play side by side): {listed}{more}.")


def draw(ctx, runs):
    record_path = os.path.join(ctx.results.root, "viewer", "viewer.json")
    listing = recorded(runs)
    if not os.path.isfile(record_path):
        return [Section("Viewer: recorded runs", listing)] if listing else []
    with open(record_path) as f:
        record = json.load(f)
    by_dir = {os.path.abspath(r.dir): r for r in runs if getattr(r, "dir", None)}
    shown = [by_dir.get(os.path.abspath(d)) for d in record.get("runs", [])]
    shown = [r for r in shown if r is not None]
    if record.get("status") != "ok" or not record.get("screenshot"):
        return ctx.missing(TITLE, f"tcbench reproduce took no screenshot: {record.get('reason') or 'no reason given'}. "
                                  f"{listing}".strip())
    source = os.path.join(ctx.results.root, "viewer", record["screenshot"])
    if not os.path.isfile(source):
        return ctx.missing(TITLE, f"{source} is missing. {listing}".strip())
    target = ctx.write_figure("viewer_" + record["screenshot"], lambda path: shutil.copyfile(source, path))
    command = "tcbench view " + " ".join(record.get("runs", []))
    caption = (f"The recorded frame at or before step {record.get('step')} of each run, as the viewer shows it: "
               "colliding points coloured by the oracle's verdict (green: the method and the oracle, red: the "
               "oracle only, missed; yellow: the method only; brown: the method only, touching), penetration "
               "vectors at five times the depth, and the per-step plot under the views (handling time, with the "
               "budget dashed where it is wall-clock; recall; max depth; kinetic energy). "
               f"Open the same runs to play, scrub and toggle the overlays: {command}. {listing}").strip()
    return Section(TITLE, caption, shown, image=os.path.relpath(target, ctx.out))
