"""Handling time per step, with and without a budget (the paper's figure 4).

One panel per scene; one curve per method label. Every scene and method in the
results appears, so a user's own scene or method shows up unasked.
"""
from ..context import plt
from .. import pairing
from ._common import by_scene, grid

TITLE = "Handling time per step with and without a budget (the paper's figure 4)"
ORDER = 1
SCOPE = "all"
FILE = "fig1_handling_time"

# Which run stands for a method label in a scene: a wall budget shows the
# budget being held (the paper's figure), then the unbudgeted run, then work.
KIND_PREFERENCE = {"wall_ms": 0, "none": 1, "work": 2}


def representatives(runs):
    """One run per method label, preferring the reference's setup (scene overrides, RNG seed)."""
    refs = [r for r in runs if pairing.is_reference(r)]
    home = pairing.setup(refs[0]) if refs else None
    chosen = {}
    for r in sorted(runs, key=lambda r: (pairing.setup(r) != home, KIND_PREFERENCE.get(r.budget_kind, 3), r.name)):
        chosen.setdefault(r.method_label, r)
    return sorted(chosen.values(), key=lambda r: (not pairing.is_reference(r), r.method_label))


def draw(ctx, runs):
    panels = [(scene, representatives(rs)) for scene, rs in by_scene(runs).items()]
    panels = [(scene, [r for r in rs if "handling_ms" in r.steps()]) for scene, rs in panels]
    panels = [(scene, rs) for scene, rs in panels if rs]
    if not panels:
        return ctx.missing(TITLE, "no run has a steps.csv with handling_ms")
    rows, cols = grid(len(panels))
    fig, axes = plt.subplots(rows, cols, figsize=(6 * cols, 3.6 * rows), squeeze=False)
    sources = []
    for ax, (scene, rs) in zip(axes.flat, panels):
        for r in rs:
            s = r.steps()
            ax.plot(s["step"], s["handling_ms"], lw=0.6, label=r.label())
        for value in sorted({r.budget_value for r in rs if r.budget_kind == "wall_ms" and r.budget_value}):
            ax.axhline(value, color="k", ls="--", lw=0.8, label=f"budget {value:.3g} ms")
        ax.set(title=scene, xlabel="step", ylabel="collision handling (ms)")
        ax.legend(fontsize=6)
        sources += rs
    for ax in list(axes.flat)[len(panels):]:
        ax.set_visible(False)
    return ctx.save(fig, FILE, TITLE,
                    "Collision handling time of every step (the steps.csv series, no statistic) in each scene, one "
                    "run per method: under a wall-clock budget (dashed) where there is one, else without a budget.",
                    sources)
