"""Handling time per step, with and without a budget (the paper's figure 4).

One panel per scene; one curve per method label. Every scene and method in the
results appears, so a user's own scene or method shows up unasked. Where the run
standing for a method has repeats (runs differing only by seed), every repeat's
series is drawn, thin and in one colour: a per-step curve has no median to take.
"""
from ..context import plt
from .. import pairing, statistics
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


def curves(runs):
    """[[runs]]: for each representative (one per method label), it and its repeats (same configuration,
    other seeds) that have a handling_ms series, sorted by seed."""
    out = []
    for r in representatives(runs):
        key = statistics.configuration(r)
        group = [m for m in runs if statistics.configuration(m) == key and "handling_ms" in m.steps()]
        if group:
            out.append(sorted(group, key=statistics.seed_order))
    return out


REPEATS = ("each seed's series is drawn as its own thin curve in the colour of its configuration (no statistic "
           "across seeds)")


def draw(ctx, runs):
    panels = [(scene, curves(rs)) for scene, rs in by_scene(runs).items()]
    panels = [(scene, groups) for scene, groups in panels if groups]
    if not panels:
        return ctx.missing(TITLE, "no run has a steps.csv with handling_ms")
    rows, cols = grid(len(panels))
    fig, axes = plt.subplots(rows, cols, figsize=(6 * cols, 3.6 * rows), squeeze=False)
    sources = []
    for ax, (scene, groups) in zip(axes.flat, panels):
        for k, group in enumerate(groups):
            if len(group) == 1:  # one run: drawn as it always was
                s = group[0].steps()
                ax.plot(s["step"], s["handling_ms"], lw=0.6, color=f"C{k % 10}", label=group[0].label())
                continue
            for j, r in enumerate(group):
                s = r.steps()
                ax.plot(s["step"], s["handling_ms"], lw=0.3, alpha=0.6, color=f"C{k % 10}",
                        label=f"{r.label()} ({len(group)} seeds, one thin curve each)" if j == 0 else None)
        rs = [r for group in groups for r in group]
        for value in sorted({r.budget_value for r in rs if r.budget_kind == "wall_ms" and r.budget_value}):
            ax.axhline(value, color="k", ls="--", lw=0.8, label=f"budget {value:.3g} ms")
        ax.set(title=scene, xlabel="step", ylabel="collision handling (ms)")
        ax.legend(fontsize=6)
        sources += rs
    for ax in list(axes.flat)[len(panels):]:
        ax.set_visible(False)
    return ctx.save(fig, FILE, TITLE,
                    "Collision handling time of every step (the steps.csv series, no statistic) in each scene, one "
                    "configuration per method: under a wall-clock budget (dashed) where there is one, else without a "
                    "budget.", sources, REPEATS)
