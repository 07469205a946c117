"""Speed-up of every budgeted run over its reference, with the accuracy it cost: the handling time's (what the
paper claims) and, beside it, the whole step's (handling + dynamics: what an application gains)."""
from ..context import plt
from ..paper import PAPER, SPEEDUP
from .. import pairing
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


def draw(ctx, runs):
    rows = pairing.budgeted_with_reference(runs, ctx.runs)
    rows.sort(key=lambda row: (row[0].scene, method_order(row[0]), row[0].budget_order(),
                               response_order(row[0].response), row[0].name))
    if not rows:
        return ctx.missing(TITLE, "no budgeted run with a reference (method full, no budget, same scene, "
                                  "scene overrides and random-number setting) and handling_ms.p50 in both summaries")
    mixed = mixed_responses([run for run, _, _ in rows])
    fig, ax = plt.subplots(figsize=(width_for(len(rows), 1.3), 4.8))  # room for interruptible_no_extrapolation
    series = ratios(rows)
    for (what, stat, colour, hatch, offset), values in zip(SERIES, series):
        drawn = [(k, value) for k, value in enumerate(values) if value is not None]
        if drawn:
            ax.bar([k + offset for k, _ in drawn], [value for _, value in drawn], width=0.2,
                   color=colour if hatch is None else "none", edgecolor=colour if hatch else None,
                   hatch=hatch, linewidth=0.8 if hatch else 0,
                   label=f"{'median (p50)' if stat == 'p50' else 'p99'} {what}: reference / run")
    for k, (run, _, _) in enumerate(rows):
        median, tail, step_median, step_tail = (values[k] for values in series)
        note = f"p50 {median:.2f}x" + (f"\np99 {tail:.2f}x" if tail is not None else "")
        note += (f"\nstep p50 {step_median:.2f}x" if step_median is not None else "\nstep n/a")
        note += f"\nstep p99 {step_tail:.2f}x" if step_tail is not None else ""
        recall_mean, recall_min, depth = run.metric("recall_mean"), run.metric("recall_min"), run.metric("max_depth")
        if recall_mean is not None:
            note += f"\nrecall mean {recall_mean:.2f}"
        if recall_min is not None:
            note += f"\nrecall min {recall_min:.2f}"
        if depth is not None:
            note += f"\ndepth max {1000 * depth:.1f} mm"
        ax.text(k, max(v for v in (median, tail, step_median, step_tail) if v is not None), note, ha="center",
                va="bottom", fontsize=6)
    ax.margins(y=0.3)  # room for the labels above the bars
    ax.axhline(SPEEDUP, color="k", ls="--", lw=0.8, label=f"{PAPER}: up to {SPEEDUP:g}x")
    ax.set_xticks(range(len(rows)), [tick_label(run, with_response=mixed) for run, _, _ in rows], fontsize=6)
    ax.set(ylabel="speed-up: reference / run\n(time per step: handling; hatched: whole step)")
    ax.legend(fontsize=7)
    return ctx.save(fig, FILE, TITLE,
                    "Handling time per step of the reference run (full, no budget, same setup) over the budgeted "
                    "run's, as the median (p50, blue: what the speed-up claim judges) and as the p99 (orange: "
                    "what a deadline sees); beside them, hatched, the same two ratios of the whole step (step_ms: "
                    "handling + dynamics, the implicit contact solve included), what the application gains. Labels "
                    "give the ratios (\"step n/a\": the run or its reference predates step_ms) and, where the oracle "
                    "ran, the recall's mean and minimum over oracle steps and the deepest true penetration (max).",
                    [x for row in rows for x in row[:2]])
