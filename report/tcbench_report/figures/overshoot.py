"""Budget granularity: how far handling time overshoots a wall-clock budget, on the wall clock (what a
deadline sees) and in the handling thread's CPU time (what the method itself spent), side by side: where
the two differ, the machine took the time, not the method."""
from .. import statistics
from ..context import plt
from ..paper import OVERSHOOT_PCT, PAPER
from ._common import mixed_responses, tick_label, width_for

TITLE = "Budget granularity"
ORDER = 2
SCOPE = "all"
FILE = "fig2_overshoot"
PANELS = (("overshoot_pct", "wall clock (the deadline)"),
          ("overshoot_cpu_pct", "handling thread CPU time (the method's own)"))


def selected(runs):
    """Runs with an overshoot in their summary: those under a wall-clock budget, any method."""
    return [r for r in runs if r.metric("overshoot_pct.p99") is not None]


def draw(ctx, runs):
    all_runs = selected(runs)
    if not all_runs:
        return ctx.missing(TITLE, "no run under a wall-clock budget with overshoot_pct in its summary")
    # One column per configuration: a run's p50, p99 and max, or their medians over its repeats (seeds),
    # the p99's bootstrap 95 % interval as a bar. [noisy]: some of its runs ran on a busy machine.
    groups = sorted(statistics.repeats(all_runs),
                    key=lambda g: (g[0].scene, g[0].method_label, g[0].budget_value or 0, g[0].name))
    runs = [g[0] for g in groups]
    noisy_group = [any(m.timing == "noisy" for m in g) for g in groups]
    fig, axes = plt.subplots(1, 2, sharey=True, figsize=(2 * width_for(len(runs), 0.45), 4.2))
    x = list(range(len(runs)))
    labels = [tick_label(r, with_response=mixed_responses(runs)) + (f" (n={len(g)})" if len(g) > 1 else "")
              + (" [noisy]" if noisy else "") for r, g, noisy in zip(runs, groups, noisy_group)]
    for ax, (key, title) in zip(axes, PANELS):
        for stat, marker in (("p50", "o"), ("p99", "s"), ("max", "^")):
            points = []
            for i, g in zip(x, groups):
                values = [m.metric(f"{key}.{stat}") for m in g if m.metric(f"{key}.{stat}") is not None]
                if values:
                    median, lo, hi = statistics.bootstrap_median(values)
                    points.append((i, median, lo, hi))
            if points:
                ax.scatter([p[0] for p in points], [p[1] for p in points], marker=marker, label=stat)
                if stat == "p99":
                    for i, median, lo, hi in points:
                        if lo is not None:
                            ax.errorbar(i, median, yerr=[[median - lo], [hi - median]], color="0.3", lw=0.7)
        if key == "overshoot_pct":
            # The machine's own floor beside each run: a null handler's overshoot p99 over as many windows of
            # the budget's length (summary.timing.floor); runs recorded before it have none.
            floors = [(i, statistics.median(values)) for i, g in zip(x, groups)
                      if (values := [v for m in g if (v := m.metric("timing.floor.overshoot_pct.p99")) is not None])]
            if floors:
                ax.scatter([f[0] for f in floors], [f[1] for f in floors], marker="_", s=120, color="0.4",
                           label="machine floor p99 (null handler)")
        ax.axhline(OVERSHOOT_PCT, color="k", ls="--", lw=0.8, label=f"{PAPER}: < {OVERSHOOT_PCT:g} %")
        ax.set_xticks(x, labels, fontsize=6, rotation=60, ha="right")
        for tick, noisy in zip(ax.get_xticklabels(), noisy_group):
            if noisy:
                tick.set_color("tab:red")
        ax.set_yscale("symlog", linthresh=10)  # the 5 % line and overshoots of 1000 % in one view
        ax.set_title(title, fontsize=8)
        ax.legend(fontsize=7)
    axes[0].set(ylabel="handling time over budget (%, linear below 10)")
    noisy = sum(r.timing == "noisy" for r in all_runs)
    runs = all_runs
    return ctx.save(fig, FILE, TITLE,
                    "How far handling time overshoots the wall-clock budget: the p50 (median), p99 and max over all "
                    "steps of each run (summary overshoot_pct, overshoot_cpu_pct), on the wall clock (left) and "
                    "in the handling thread's CPU time (right). The grey dash is the machine's floor: the p99 "
                    "overshoot of a null handler that only polls the clock, spun for one window of the budget "
                    "after each step of the run (summary.timing.floor); a run near it overshoots what any method "
                    "would here. Runs marked [noisy] "
                    f"(red; {noisy} of {len(all_runs)} runs) ran on a busy machine (summary.timing): their wall overshoot is "
                    "partly the scheduler's.",
                    runs)
