"""Speed-up of every budgeted run over its reference, with the accuracy it cost."""
from ..context import plt
from ..paper import PAPER, SPEEDUP
from .. import pairing
from ..loader import response_order
from ._common import method_order, mixed_responses, tick_label, width_for

TITLE = "Speed-up over the full method, with the accuracy it cost"
ORDER = 3
SCOPE = "all"
FILE = "fig3_speedup"


def draw(ctx, runs):
    rows = pairing.budgeted_with_reference(runs, ctx.runs)
    rows.sort(key=lambda row: (row[0].scene, method_order(row[0]), row[0].budget_order(),
                               response_order(row[0].response), row[0].name))
    if not rows:
        return ctx.missing(TITLE, "no budgeted run with a reference (method full, no budget, same scene, "
                                  "scene overrides and random-number setting) and handling_ms.p50 in both summaries")
    mixed = mixed_responses([run for run, _, _ in rows])
    fig, ax = plt.subplots(figsize=(width_for(len(rows), 1.05), 4.2))  # room for interruptible_no_extrapolation
    tails = [pairing.speedup(run, ref, "p99") for run, ref, _ in rows]
    ax.bar([k - 0.2 for k in range(len(rows))], [ratio for _, _, ratio in rows], width=0.4, color="tab:blue",
           label="median (p50) handling time: reference / run")
    drawn = [(k, tail) for k, tail in enumerate(tails) if tail is not None]
    if drawn:
        ax.bar([k + 0.2 for k, _ in drawn], [tail for _, tail in drawn], width=0.4, color="tab:orange",
               label="p99 handling time: reference / run")
    for k, ((run, _, ratio), tail) in enumerate(zip(rows, tails)):
        note = f"p50 {ratio:.2f}x" + (f"\np99 {tail:.2f}x" if tail is not None else "")
        recall_mean, recall_min, depth = run.metric("recall_mean"), run.metric("recall_min"), run.metric("max_depth")
        if recall_mean is not None:
            note += f"\nrecall mean {recall_mean:.2f}"
        if recall_min is not None:
            note += f"\nrecall min {recall_min:.2f}"
        if depth is not None:
            note += f"\ndepth max {1000 * depth:.1f} mm"
        ax.text(k, max(ratio, tail or 0), note, ha="center", va="bottom", fontsize=6)
    ax.margins(y=0.3)  # room for the labels above the bars
    ax.axhline(SPEEDUP, color="k", ls="--", lw=0.8, label=f"{PAPER}: up to {SPEEDUP:g}x")
    ax.set_xticks(range(len(rows)), [tick_label(run, with_response=mixed) for run, _, _ in rows], fontsize=6)
    ax.set(ylabel="speed-up: reference / run\n(handling time per step)")
    ax.legend(fontsize=7)
    return ctx.save(fig, FILE, TITLE,
                    "Handling time per step of the reference run (full, no budget, same setup) over the budgeted "
                    "run's, as the median (p50, blue: what the speed-up claim judges) and as the p99 (orange: "
                    "what a deadline sees). Labels give both ratios and, where the oracle ran, the recall's mean and "
                    "minimum over oracle steps and the deepest true penetration (max).",
                    [x for row in rows for x in row[:2]])
