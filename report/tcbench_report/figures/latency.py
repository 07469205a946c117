"""Latency against pass-through: steps until a true penetration gets a depth-based force.

Drawn from the sweeps that declare "latency" (they run the oracle on every
step, which latency needs).
"""
from ..context import plt
from ..paper import LATENCY_STEPS, PAPER
from ._common import tick_label, width_for

TITLE = "Latency and tunnelling"
ORDER = 5
SCOPE = "declared"
FILE = "fig5_latency"


def selected(runs):
    """Runs with a measured latency, plus those that never gave a depth-based force
    (no latency to measure) but were watched by the oracle on every step: they show
    what no handling lets through."""
    return [r for r in runs if r.metric("latency_steps.max") is not None
            or (r.record.get("oracle") in ("every", "every:1") and r.metric("tunneling") is not None)]


def draw(ctx, runs):
    runs = sorted(selected(runs), key=lambda r: (r.scene, r.method_label, r.metric("latency_steps.max") or 0, r.name))
    if not runs:
        return ctx.missing(TITLE, "no run of the sweeps declaring this figure has summary.latency_steps "
                                  "(needs --oracle every)")
    several = len({r.scene for r in runs}) > 1
    fig, ax = plt.subplots(figsize=(width_for(len(runs), 0.8), 3.8))
    for k, r in enumerate(runs):
        mean, worst = r.metric("latency_steps.mean"), r.metric("latency_steps.max")
        if worst is not None:
            ax.bar(k, worst, color="tab:orange", alpha=0.5)
            ax.scatter([k], [mean], color="k", s=12)
        tunnelled = r.metric("tunneling")
        ax.text(k, (worst or 0) + 0.3, "tunnels" if tunnelled else "holds", ha="center", fontsize=6,
                color="tab:red" if tunnelled else "tab:green")
    ax.axhline(LATENCY_STEPS, color="k", ls="--", lw=0.8, label=f"{PAPER}: <= {LATENCY_STEPS} steps holds")
    ax.set_xticks(range(len(runs)), [tick_label(r, several) for r in runs], fontsize=6)
    ax.set(ylabel="latency (steps): max bar, mean dot")
    ax.legend(fontsize=7)
    scenes = ", ".join(sorted({r.scene for r in runs}))
    return ctx.save(fig, FILE, f"{TITLE}: {scenes}",
                    "Steps from a vertex's first true penetration to its first depth-based force, over the "
                    "penetration episodes of each run: the bar is the longest (max), the dot the mean "
                    "(summary latency_steps); and whether the objects passed through each other.", runs)
