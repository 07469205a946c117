"""Cost against scene size: handling time against the number of tetrahedra.

Drawn from the sweeps that declare "scaling". Only scenes run at several sizes
(by their scene overrides) make a curve; one curve per scene, method and budget.
A size with repeats (runs differing only by seed) is one point: the median of
their p50 with its bootstrap 95 % interval, and the median of their p99.
A curve of three or more sizes carries the exponent of its p50 (the slope of
a least-squares line through log p50 against log tets) and the range it was
fitted over, in the legend and the caption. The caption gives beside it the
exponent of the work units a step, which are counted, not timed: where the
time's exponent is the larger, a unit of work took longer at the larger
sizes (on the machine that ran it), rather than more work being done.
"""
import math
from collections import defaultdict

from matplotlib.ticker import NullFormatter

from .. import statistics
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


def points(runs):
    """[(tets, p50, lo, hi, p99, n)] of a curve's runs, one per configuration, by size: one run's values, or
    the medians of its repeats with the p50's bootstrap 95 % interval (lo, hi None for one run)."""
    out = []
    for group in statistics.repeats(runs):
        p50, lo, hi, n = statistics.summarise(r.metric("handling_ms.p50") for r in group)
        tails = [r.metric("handling_ms.p99") for r in group]
        p99 = statistics.median(tails) if all(t is not None for t in tails) else None
        out.append((statistics.median([r.dynamic_tets() for r in group]), p50, lo, hi, p99, n))
    return sorted(out, key=lambda p: p[0])


def work_points(runs):
    """[(tets, work units a step)] of a curve's runs, one per configuration by size: the median over its repeats
    of summary.work_units_total over the run's steps; a configuration with a run that lacks either is left out."""
    out = []
    for group in statistics.repeats(runs):
        total = [r.metric("work_units_total") for r in group]
        steps = [r.record.get("steps") for r in group]
        if all(w is not None for w in total) and all(isinstance(n, int) and n > 0 for n in steps):
            out.append((statistics.median([r.dynamic_tets() for r in group]),
                        statistics.median([w / n for w, n in zip(total, steps)])))
    return sorted(out)


def exponent(pts):
    """(slope, smallest tets, largest tets) of log p50 against log tets over points (tets, p50, ...), or None
    for fewer than three distinct sizes with a positive p50 (two points fit any power law exactly)."""
    xy = [(math.log(p[0]), math.log(p[1])) for p in pts if p[0] > 0 and p[1] is not None and p[1] > 0]
    if len({x for x, _ in xy}) < 3:
        return None
    mx = sum(x for x, _ in xy) / len(xy)
    my = sum(y for _, y in xy) / len(xy)
    slope = sum((x - mx) * (y - my) for x, y in xy) / sum((x - mx) ** 2 for x, _ in xy)
    return slope, round(math.exp(min(x for x, _ in xy))), round(math.exp(max(x for x, _ in xy)))


def draw(ctx, runs):
    runs = [r for r in runs if r.metric("handling_ms.p50") is not None and r.dynamic_tets() > 0]
    lines = curves(runs)
    if not lines:
        return ctx.missing(TITLE, "no scene of the sweeps declaring this figure was run at two or more sizes")
    fig, ax = plt.subplots(figsize=(8.5, 4))
    fits = []
    worked = False  # some fit has a work exponent beside it
    for k, (legend, rs) in enumerate(lines.items()):
        pts = points(rs)
        fit = exponent(pts)
        label = f"{legend} p50"
        if fit:
            label += f" (exponent {fit[0]:.2f})"
            work = exponent(work_points(rs))
            worked = worked or work is not None
            fits.append(f"{legend}: {fit[0]:.2f} over {fit[1]}..{fit[2]} tets"
                        + (f" (work units a step: {work[0]:.2f} over {work[1]}..{work[2]} tets)" if work else ""))
        # One colour per curve, its p99 dotted in the same colour.
        [line] = ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", color=f"C{k % 10}", label=label)
        for tets, p50, lo, hi, _, _ in pts:
            if lo is not None:
                ax.errorbar(tets, p50, yerr=[[p50 - lo], [hi - p50]], color=line.get_color(), lw=0.8, capsize=2)
        if all(p[4] is not None for p in pts):
            ax.plot([p[0] for p in pts], [p[4] for p in pts], "x:", color=line.get_color(), label=f"{legend} p99")
    ax.set(xscale="log", yscale="log", xlabel="tetrahedra (objects that change shape)",
           ylabel="handling time per step (ms)")
    # Tick the sizes that were run: a log axis over less than a decade labels its minor ticks on top of each other.
    sizes = sorted({r.dynamic_tets() for rs in lines.values() for r in rs})
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xticks(sizes, [str(n) for n in sizes])
    ax.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.01, 0.5))
    fig.tight_layout()
    scenes = ", ".join(sorted({r.scene for rs in lines.values() for r in rs}))
    return ctx.save(fig, FILE, f"{TITLE}: {scenes}",
                    "Collision handling time per step, its median (p50, solid) and p99 (dotted), against the "
                    "number of tetrahedra of the objects that change shape (integrated or latent-driven)."
                    + (" Exponent of the p50 (least-squares slope of log time against log tets): " + "; ".join(fits)
                       + "." if fits else "")
                    + (" Work units count the cycle's operations, the same on every machine: where time grows"
                       " faster than work, a unit of work took longer at the larger sizes (one cause: tables that"
                       " outgrow the caches)." if worked else ""),
                    [r for rs in lines.values() for r in rs],
                    "each point is their median (the p50's bootstrap 95 % interval as a bar; the p99 the median of "
                    "theirs)")
