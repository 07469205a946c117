"""Jitter of resting contact: the scene's summary "jitter", and whether the stack still stands.

Drawn from the sweeps that declare "jitter"; the scene decides what its jitter
measures (a stack: RMS vertical velocity over the settled half). One panel per
scene and contact response (implicit, explicit), bars grouped by budget, full's
value (same setup) marked across each bar.
"""
from .. import statistics
from ..context import plt
from ..paper import STANDING_FRACTION
from ._common import (bars_legend, bars_width, budget_bars, by_response, by_scene, log_limits, method_colours,
                      response_title)

TITLE = "Jitter of resting contact"
ORDER = 4
SCOPE = "declared"
FILE = "fig4_jitter"


def collapsed(run):
    """True when the top centre ended below STANDING_FRACTION of its start; None when not measured."""
    h0, h1 = run.metric("top_centre_height_m.initial"), run.metric("top_centre_height_m.final")
    if h0 is None or h1 is None:
        return None
    return h1 < STANDING_FRACTION * h0


def note(run):
    return f"collapsed (top {run.metric('top_centre_height_m.final'):.2f} m)" if collapsed(run) else None


def group_note(group):
    """For repeats: how many of the runs that measured it collapsed, with its Wilson 95 % interval; None when
    none did."""
    measured = [collapsed(r) for r in group if collapsed(r) is not None]
    fallen = sum(measured)
    return f"collapsed {statistics.rate_text(fallen, len(measured))}" if fallen else None


def panels(runs):
    """[[(title, runs)]]: a row per scene, a panel per contact response in it."""
    return [[(f"{scene}, {response_title(mode, ms)}", ms) for mode, ms in by_response(rs)]
            for scene, rs in by_scene(runs).items()]


def draw(ctx, runs):
    runs = [r for r in runs if r.metric("jitter") is not None]
    if not runs:
        return ctx.missing(TITLE, "no run of the sweeps declaring this figure has summary.jitter")
    rows = panels(runs)
    cols = max(len(row) for row in rows)
    widths = [max(bars_width(rs) for row in rows if k < len(row) for rs in [row[k][1]]) for k in range(cols)]
    fig, axes = plt.subplots(len(rows), cols, figsize=(sum(widths) + 1.6, 4.6 * len(rows)), squeeze=False,
                             sharey="row", gridspec_kw={"width_ratios": widths})
    colours, used = method_colours(runs), []
    for number, (row, ax_row) in enumerate(zip(rows, axes)):
        values = []
        for k, ax in enumerate(ax_row):
            if k >= len(row):
                ax.set_visible(False)
                continue
            title, rs = row[k]
            drawn, shown = budget_bars(ax, ctx, rs, "jitter", colours, note, group_note)
            used, values = used + drawn, values + shown
            ax.set_title(title, fontsize=9)
            if k == 0:
                ax.set_ylabel("jitter (scene's measure, m/s)")
        log_limits(ax_row[:len(row)], values)
        if number == 0:  # one legend: the colours are the same in every row
            bars_legend(ax_row[len(row) - 1], colours, runs)
    scenes = ", ".join(sorted({r.scene for r in runs}))
    return ctx.save(fig, FILE, f"{TITLE}: {scenes}",
                    "Each run's jitter (summary.jitter: the RMS of the objects' vertical velocity over the second "
                    "half of the run), one panel per contact response (implicit or explicit penalty "
                    "contact; a run recorded before the option is explicit), bars grouped by budget from the "
                    "largest to the smallest and coloured by method; the black mark across a bar is full's jitter "
                    "in the same setup. Hatched in red: the run is not ok; 'collapsed' where the top object's "
                    f"centre ended below {100 * STANDING_FRACTION:g} % of its starting height (our threshold); for "
                    "repeats, how many of the runs did, with its Wilson 95 % interval. With repeats the bar is "
                    "their median jitter and the black mark the median of their references'.",
                    used)
