"""Cost against scene size: handling time against the number of tetrahedra.

Drawn from the sweeps that declare "scaling". Only scenes run at several sizes
(by their scene overrides) make a curve; one curve per scene, method and budget.
"""
from collections import defaultdict

from matplotlib.ticker import NullFormatter

from ..context import plt

TITLE = "Cost against scene size"
ORDER = 8
SCOPE = "declared"
FILE = "fig8_scaling"


def curves(runs):
    """{legend: [runs]} for every scene with at least two sizes."""
    sizes = defaultdict(set)
    for r in runs:
        sizes[r.scene].add(r.dynamic_tets())
    several = len([s for s in sizes if len(sizes[s]) > 1]) > 1
    out = defaultdict(list)
    for r in runs:
        if len(sizes[r.scene]) > 1:
            out[(f"{r.scene}: " if several else "") + r.label()].append(r)
    return dict(sorted(out.items()))


def draw(ctx, runs):
    runs = [r for r in runs if r.metric("handling_ms.p50") is not None and r.dynamic_tets() > 0]
    lines = curves(runs)
    if not lines:
        return ctx.missing(TITLE, "no scene of the sweeps declaring this figure was run at two or more sizes")
    fig, ax = plt.subplots(figsize=(6, 4))
    for legend, rs in lines.items():
        pts = sorted((r.dynamic_tets(), r.metric("handling_ms.p50"), r.metric("handling_ms.p99")) for r in rs)
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", label=f"{legend} p50")
        if all(p[2] is not None for p in pts):
            ax.plot([p[0] for p in pts], [p[2] for p in pts], "x:", label=f"{legend} p99")
    ax.set(xscale="log", yscale="log", xlabel="tetrahedra (dynamic objects)",
           ylabel="handling time per step (ms)")
    # Tick the sizes that were run: a log axis over less than a decade labels its minor ticks on top of each other.
    sizes = sorted({r.dynamic_tets() for rs in lines.values() for r in rs})
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xticks(sizes, [str(n) for n in sizes])
    ax.legend(fontsize=7)
    scenes = ", ".join(sorted({r.scene for rs in lines.values() for r in rs}))
    return ctx.save(fig, FILE, f"{TITLE}: {scenes}",
                    "Collision handling time per step, its median (p50, solid) and p99 (dotted), against the "
                    "number of tetrahedra of the dynamic objects.", [r for rs in lines.values() for r in rs])
