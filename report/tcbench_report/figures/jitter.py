"""Jitter of resting contact: the scene's summary "jitter", and whether the stack still stands.

Drawn from the sweeps that declare "jitter"; the scene decides what its jitter
measures (a stack: RMS vertical velocity over the settled half).
"""
from ..context import plt
from ..paper import STANDING_FRACTION
from ._common import tick_label, width_for

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


def draw(ctx, runs):
    runs = sorted((r for r in runs if r.metric("jitter") is not None),
                  key=lambda r: (r.scene, r.budget_kind != "none", r.method_label, r.name))
    if not runs:
        return ctx.missing(TITLE, "no run of the sweeps declaring this figure has summary.jitter")
    several = len({r.scene for r in runs}) > 1
    fig, ax = plt.subplots(figsize=(width_for(len(runs), 0.8), 3.8))
    values = [r.metric("jitter") for r in runs]
    ax.bar(range(len(runs)), values, color=["tab:green" if r.status == "ok" else "tab:red" for r in runs])
    ax.set_yscale("log")
    ax.set_xticks(range(len(runs)), [tick_label(r, several) for r in runs], fontsize=6)
    ax.set(ylabel="jitter (scene's measure, m/s)")
    for k, r in enumerate(runs):
        note = f"{values[k]:.3g}" + ("" if r.status == "ok" else f"\n{r.status}")
        if collapsed(r):
            note += f"\ncollapsed\n(top {r.metric('top_centre_height_m.final'):.2f} m)"
        ax.text(k, values[k], note, ha="center", va="bottom", fontsize=6)
    scenes = ", ".join(sorted({r.scene for r in runs}))
    return ctx.save(fig, FILE, f"{TITLE}: {scenes}",
                    "Each run's jitter as its scene measures it (a stack: RMS vertical velocity of the objects over "
                    "the second half of the run; red: run not ok); 'collapsed' where the top object's centre ended "
                    f"below {100 * STANDING_FRACTION:g} % of its starting height.", runs)
