"""Budget granularity: how far handling time overshoots a wall-clock budget."""
from ..context import plt
from ..paper import OVERSHOOT_PCT, PAPER
from ._common import mixed_responses, tick_label, width_for

TITLE = "Budget granularity"
ORDER = 2
SCOPE = "all"
FILE = "fig2_overshoot"


def selected(runs):
    """Runs with an overshoot in their summary: those under a wall-clock budget, any method."""
    return [r for r in runs if r.metric("overshoot_pct.p99") is not None]


def draw(ctx, runs):
    runs = sorted(selected(runs), key=lambda r: (r.scene, r.method_label, r.budget_value or 0, r.name))
    if not runs:
        return ctx.missing(TITLE, "no run under a wall-clock budget with overshoot_pct in its summary")
    fig, ax = plt.subplots(figsize=(width_for(len(runs), 0.6), 3.8))
    x = range(len(runs))
    for key, marker in (("p50", "o"), ("p99", "s"), ("max", "^")):
        ax.scatter(x, [r.metric(f"overshoot_pct.{key}") for r in runs], marker=marker, label=key)
    ax.axhline(OVERSHOOT_PCT, color="k", ls="--", lw=0.8, label=f"{PAPER}: < {OVERSHOOT_PCT:g} %")
    ax.set_xticks(list(x), [tick_label(r, with_response=mixed_responses(runs)) for r in runs], fontsize=6)
    ax.set(ylabel="handling time over budget (%)")
    ax.legend(fontsize=7)
    return ctx.save(fig, FILE, TITLE,
                    "How far handling time overshoots the wall-clock budget: percentiles over all steps of each run.",
                    runs)
