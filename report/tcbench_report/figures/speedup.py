"""Speed-up of every budgeted run over its reference, with the accuracy it cost: the handling time's (what the
paper claims) and, beside it, the whole step's (handling + dynamics: what an application gains).

Each run is compared with its own reference (same seed: the same jittered start). A configuration with
repeats (runs differing only by seed) is one group of bars: the median of its runs' ratios, with the
bootstrap 95 % interval as a whisker; its labels give the medians.
"""
from ..context import plt
from ..paper import PAPER, SPEEDUP
from .. import pairing, statistics
from ..loader import response_order
from ._common import method_order, mixed_responses, tick_label, width_for

TITLE = "Speed-up over the full method, with the accuracy it cost"
ORDER = 3
SCOPE = "all"
FILE = "fig3_speedup"

# The bars beside each run: (what is timed, statistic, colour, hatch, x offset). The colour is the statistic,
# the hatch the whole step; a ratio that cannot be computed (a run older than step_ms) is left out.
SERIES = (("handling time", "p50", "tab:blue", None, -0.3),
          ("handling time", "p99", "tab:orange", None, -0.1),
          ("whole step (handling + dynamics)", "p50", "tab:blue", "////", 0.1),
          ("whole step (handling + dynamics)", "p99", "tab:orange", "////", 0.3))


def ratios(rows):
    """[[ratio or None per row] per SERIES entry] for (run, reference, median handling speed-up) rows."""
    return [[pairing.speedup(run, ref, stat, pairing.HANDLING if what == "handling time" else pairing.STEP)
             for run, ref, _ in rows] for what, stat, *_ in SERIES]


def configurations(rows):
    """[[(run, reference, ratio)]]: the rows of each configuration (its repeats, by seed), in the order of
    their first row."""
    groups = {}
    for row in rows:
        groups.setdefault(statistics.configuration(row[0]), []).append(row)
    return [sorted(g, key=lambda row: statistics.seed_order(row[0])) for g in groups.values()]


def estimates(group):
    """[(median, lo, hi, n) per SERIES entry] of a configuration's ratios: one run's ratio itself (lo, hi
    None), or the median of its repeats' with the bootstrap 95 % interval."""
    return [statistics.summarise(values) for values in ratios(group)]


def ratio_text(name, estimate):
    value, lo, hi, n = estimate
    if value is None:
        return None
    return f"{name} {value:.2f}x" + (f" [{lo:.2f}, {hi:.2f}]" if n > 1 and lo is not None else "")


def label_note(group):
    """The text above a configuration's bars: the ratios (medians with intervals for repeats), the recall's
    mean and minimum and the deepest true penetration (medians for repeats)."""
    median, tail, step_median, step_tail = estimates(group)
    lines = [f"median of {len(group)} runs:"] if len(group) > 1 else []
    lines += [ratio_text("p50", median)]
    lines += [t for t in (ratio_text("p99", tail),) if t]
    lines += [ratio_text("step p50", step_median) or "step n/a"]
    lines += [t for t in (ratio_text("step p99", step_tail),) if t]
    runs = [run for run, *_ in group]
    for key, name, scale, fmt in (("recall_mean", "recall mean", 1, "{:.2f}"),
                                  ("recall_min", "recall min", 1, "{:.2f}"),
                                  ("max_depth", "depth max", 1000, "{:.1f} mm")):
        value = statistics.median([r.metric(key) for r in runs if r.metric(key) is not None])
        if value is not None:
            lines.append(f"{name} {fmt.format(scale * value)}")
    return "\n".join(lines)


def draw(ctx, runs):
    rows = pairing.budgeted_with_reference(runs, ctx.runs)
    rows.sort(key=lambda row: (row[0].scene, method_order(row[0]), row[0].budget_order(),
                               response_order(row[0].response), row[0].name))
    if not rows:
        return ctx.missing(TITLE, "no budgeted run with a reference (method full, no budget, same scene, "
                                  "scene overrides and random-number setting) and handling_ms.p50 in both summaries")
    groups = configurations(rows)
    firsts = [group[0][0] for group in groups]
    mixed = mixed_responses(firsts)
    fig, ax = plt.subplots(figsize=(width_for(len(groups), 1.3), 4.8))  # room for interruptible_no_extrapolation
    series = list(zip(*[estimates(group) for group in groups]))  # per SERIES entry: an estimate per group
    for (what, stat, colour, hatch, offset), values in zip(SERIES, series):
        drawn = [(k, value, lo, hi) for k, (value, lo, hi, _) in enumerate(values) if value is not None]
        if drawn:
            ax.bar([k + offset for k, *_ in drawn], [value for _, value, *_ in drawn], width=0.2,
                   color=colour if hatch is None else "none", edgecolor=colour if hatch else None,
                   hatch=hatch, linewidth=0.8 if hatch else 0,
                   label=f"{'median (p50)' if stat == 'p50' else 'p99'} {what}: reference / run")
            for k, value, lo, hi in drawn:
                if lo is not None:
                    ax.errorbar(k + offset, value, yerr=[[value - lo], [hi - value]], color="0.2", lw=0.7,
                                capsize=1.5)
    for k, group in enumerate(groups):
        tops = [v for values in series for v in (values[k][0], values[k][2]) if v is not None]
        ax.text(k, max(tops), label_note(group), ha="center", va="bottom", fontsize=6)
    ax.margins(y=0.3)  # room for the labels above the bars
    ax.axhline(SPEEDUP, color="k", ls="--", lw=0.8, label=f"{PAPER}: up to {SPEEDUP:g}x")
    ax.set_xticks(range(len(groups)), [tick_label(run, with_response=mixed) + (f"\n(n={len(group)})" if len(group) > 1
                                                                             else "")
                                       for run, group in zip(firsts, groups)], fontsize=6)
    ax.set(ylabel="speed-up: reference / run\n(time per step: handling; hatched: whole step)")
    ax.legend(fontsize=7)
    return ctx.save(fig, FILE, TITLE,
                    "Handling time per step of the reference run (full, no budget, same setup) over the budgeted "
                    "run's, as the median (p50, blue: what the speed-up claim judges) and as the p99 (orange: "
                    "what a deadline sees); beside them, hatched, the same two ratios of the whole step (step_ms: "
                    "handling + dynamics, the implicit contact solve included), what the application gains. Labels "
                    "give the ratios (\"step n/a\": the run or its reference predates step_ms) and, where the oracle "
                    "ran, the recall's mean and minimum over oracle steps and the deepest true penetration (max). Each "
                    "run is divided by its own reference (the same seed).",
                    [x for row in rows for x in row[:2]],
                    "each group of bars is the median of their ratios with its bootstrap 95 % interval (whisker), "
                    "and the labels give medians")
