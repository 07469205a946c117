"""How settled resting contact is: chatter and kinetic energy over the second half of the run.

Drawn from the sweeps that declare "settling". One row per measure
(settled_max_speed_median: the median over the second half of each step's
fastest vertex; settled_kinetic_energy.mean), one panel per contact response,
bars grouped by budget and coloured by method, full's value (same setup)
marked across each bar.
"""
from ..context import plt
from ._common import (bars_legend, bars_width, budget_bars, by_response, by_scene, log_limits, method_colours,
                      response_title)

TITLE = "Settling of resting contact"
ORDER = 4.5  # beside the jitter
SCOPE = "declared"
FILE = "fig4b_settling"
MEASURES = (("settled_max_speed_median", "settled fastest vertex,\nmedian (m/s)"),
            ("settled_kinetic_energy.mean", "settled kinetic\nenergy, mean (J)"))


def draw(ctx, runs):
    runs = [r for r in runs if any(r.metric(key) is not None for key, _ in MEASURES)]
    if not runs:
        return ctx.missing(TITLE, "no run of the sweeps declaring this figure has settled_max_speed_median or "
                                  "settled_kinetic_energy in its summary")
    rows = [(scene, key, name, by_response([r for r in rs if r.metric(key) is not None]))
            for scene, rs in by_scene(runs).items() for key, name in MEASURES]
    rows = [row for row in rows if row[3]]
    cols = max(len(modes) for *_, modes in rows)
    widths = [max(bars_width(modes[k][1]) for *_, modes in rows if k < len(modes)) for k in range(cols)]
    fig, axes = plt.subplots(len(rows), cols, figsize=(sum(widths) + 1.6, 3.6 * len(rows)), squeeze=False,
                             sharey="row", gridspec_kw={"width_ratios": widths})
    colours, used = method_colours(runs), []
    for number, ((scene, key, name, modes), ax_row) in enumerate(zip(rows, axes)):
        values = []
        for k, ax in enumerate(ax_row):
            if k >= len(modes):
                ax.set_visible(False)
                continue
            mode, rs = modes[k]
            drawn, shown = budget_bars(ax, ctx, rs, key, colours)
            used, values = used + drawn, values + shown
            ax.set_title(f"{scene}, {response_title(mode, rs)}", fontsize=9)
            if k == 0:
                ax.set_ylabel(name, fontsize=8)
        log_limits(ax_row[:len(modes)], values)
        if number == 0:  # one legend: the colours are the same in every row
            bars_legend(ax_row[len(modes) - 1], colours, runs)
    scenes = ", ".join(sorted({r.scene for r in runs}))
    return ctx.save(fig, FILE, f"{TITLE}: {scenes}",
                    "How still the scene is over the second half of each run: the median of each step's fastest "
                    "vertex speed (chatter) and the mean kinetic energy, from the run summaries; one panel per "
                    "contact response (implicit or explicit penalty contact), bars grouped by budget from the "
                    "largest to the smallest and coloured by method; the black mark across a bar is full's value "
                    "in the same setup (with repeats, the median of their references'). Log scales. Hatched in red: "
                    "the run is not ok (with repeats: how many of them are not).", used)
