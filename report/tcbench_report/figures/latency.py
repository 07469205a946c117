"""Latency against pass-through: steps until a true penetration gets a depth-based force.

Drawn from the sweeps that declare "latency" (they run the oracle on every
step, which latency needs). Repeats of a configuration (seeds with a
jittered initial state) share one bar: the median of their longest latency
with its bootstrap 95 % interval, and the pass-through as a rate with its
Wilson 95 % interval.
"""
from .. import statistics
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


def bars(runs):
    """[(first run of the configuration, its runs, median max latency or None, lo, hi, mean of means,
    tunnelled count)] ordered by scene, method and latency."""
    out = []
    for group in statistics.repeats(selected(runs)):
        worst = [r.metric("latency_steps.max") for r in group if r.metric("latency_steps.max") is not None]
        means = [r.metric("latency_steps.mean") for r in group if r.metric("latency_steps.mean") is not None]
        median, lo, hi = statistics.bootstrap_median(worst) if worst else (None, None, None)
        tunnelled = sum(1 for r in group if r.metric("tunneling"))
        out.append((group[0], group, median, lo, hi, statistics.median(means) if means else None, tunnelled))
    return sorted(out, key=lambda b: (b[0].scene, b[0].method_label, b[2] or 0, b[0].name))


def draw(ctx, runs):
    rows = bars(runs)
    if not rows:
        return ctx.missing(TITLE, "no run of the sweeps declaring this figure has summary.latency_steps "
                                  "(needs --oracle every)")
    several = len({r.scene for r, *_ in rows}) > 1
    fig, ax = plt.subplots(figsize=(width_for(len(rows), 0.8), 3.8))
    for k, (r, group, worst, lo, hi, mean, tunnelled) in enumerate(rows):
        if worst is not None:
            ax.bar(k, worst, color="tab:orange", alpha=0.5)
            if lo is not None:
                ax.errorbar(k, worst, yerr=[[worst - lo], [hi - worst]], color="0.2", lw=0.8, capsize=2)
        if mean is not None:
            ax.scatter([k], [mean], color="k", s=12)
        n = len(group)
        text = ("tunnels" if tunnelled else "holds") if n == 1 else f"tunnels {tunnelled}/{n}"
        if n > 1 and tunnelled:
            low, high = statistics.wilson_interval(tunnelled, n)
            text += f"\n({100 * low:.0f}-{100 * high:.0f} %)"
        ax.text(k, max(worst or 0, hi or 0) + 0.3, text, ha="center", fontsize=5.5, rotation=90 if n > 1 else 0,
                va="bottom", color="tab:red" if tunnelled else "tab:green")
    ax.axhline(LATENCY_STEPS, color="k", ls="--", lw=0.8, label=f"{PAPER}: <= {LATENCY_STEPS} steps holds")
    ax.set_xticks(range(len(rows)), [tick_label(r, several) for r, *_ in rows], fontsize=6)
    ax.set(ylabel="latency (steps): max bar, mean dot")
    ax.legend(fontsize=7)
    scenes = ", ".join(sorted({r.scene for r, *_ in rows}))
    used = [m for _, group, *_ in rows for m in group]
    return ctx.save(fig, FILE, f"{TITLE}: {scenes}",
                    "Steps from a vertex's first true penetration to its first depth-based force, over the "
                    "penetration episodes of each run: the bar is the longest (max), the dot the mean "
                    "(summary latency_steps), and whether the objects passed through each other. With "
                    "repeats, the bar is the median over the seeds of each run's longest latency (whisker: "
                    "bootstrap 95 % interval), the dot the median of the means, and pass-through is a count "
                    "of runs with its Wilson 95 % interval.", used)
