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
    fig, ax = plt.subplots(figsize=(width_for(len(rows), 1.05), 3.8))  # room for interruptible_no_extrapolation
    ratios = [ratio for _, _, ratio in rows]
    ax.bar(range(len(rows)), ratios, color="tab:blue")
    for k, (run, _, ratio) in enumerate(rows):
        note = f"{ratio:.2f}x"
        recall, depth = run.metric("recall_min"), run.metric("max_depth")
        if recall is not None:
            note += f"\nrecall {recall:.2f}"
        if depth is not None:
            note += f"\ndepth {1000 * depth:.1f} mm"
        ax.text(k, ratio, note, ha="center", va="bottom", fontsize=6)
    ax.margins(y=0.2)  # room for the labels above the bars
    ax.axhline(SPEEDUP, color="k", ls="--", lw=0.8, label=f"{PAPER}: up to {SPEEDUP:g}x")
    ax.set_xticks(range(len(rows)), [tick_label(run, with_response=mixed) for run, _, _ in rows], fontsize=6)
    ax.set(ylabel="median handling time: reference / run")
    ax.legend(fontsize=7)
    return ctx.save(fig, FILE, TITLE,
                    "Median handling time of the reference run (full, no budget, same setup) over the budgeted "
                    "run's; labels give the minimum recall and the deepest true penetration where the oracle ran.",
                    [x for row in rows for x in row[:2]])
