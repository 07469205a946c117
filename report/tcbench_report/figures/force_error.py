"""How wrong the applied contact forces are, against what it costs: each run's per-step force error
(summary.force_error: the method's applied force field against full's from the same state in the same step)
over the p99 of its per-step handling time, and where the error comes from (the source of each force).

Drawn from every run with summary.force_error (runs with --force-reference). One row per scene and contact
response: left, relative L2 error (median, whisker to the p95) against handling time p99, one marker per
method label and budget; right, per run, the mean error beside each source's part of it, with the shares of
missed and ghost points. A configuration with repeats (runs differing only by seed) is one marker and one
group of bars: the medians over its runs, the p50's and the mean's bootstrap 95 % interval as a black
error bar. Noise-floor runs (full under a perturb.* override) are left out: full against full from the same
state, 0 by construction.
"""
import math

from ..context import plt
from .. import pairing, statistics
from ..loader import response_order
from ._common import broken, method_colours, method_order, response_title, tick_label

TITLE = "Force error against handling time"
ORDER = 6.5  # beside the trade-off
SCOPE = "all"
FILE = "fig6b_force_error"

ERROR = "force_error.relative_l2"  # {mean, p50, p95, p99, max} of the relative L2 error over sampled steps
TIME = "handling_ms.p99"
# summary.force_error.by_source, in the order a force's depth gets older.
SOURCES = ("computed", "held", "extrapolated", "tracked")
SOURCE_COLOURS = dict(zip(SOURCES, ("tab:green", "tab:orange", "tab:red", "tab:purple")))
MARKERS = ("o", "s", "^", "D", "v", "P", "X", "*", "<", ">")


def has_force_error(run):
    return run.metric("force_error.samples") is not None and not pairing.is_noise_floor(run)


def rows(runs):
    """[((scene, response), [runs])]: the runs with summary.force_error (noise-floor runs left out) by scene and
    contact response, scenes in order, implicit first; within a row by method, budget and seed."""
    groups = {}
    for r in runs:
        if has_force_error(r):
            groups.setdefault((r.scene, r.response), []).append(r)
    order = sorted(groups, key=lambda key: (key[0], response_order(key[1])))
    return [(key, sorted(groups[key], key=lambda r: (method_order(r), r.budget_order(),
                                                     r.seed if r.seed is not None else -1, r.name)))
            for key in order]


def point(run):
    """The left panel's point of a run: {x: handling_ms.p99, p50, p95 of the relative L2 error}, or None
    when the run has no handling time or no defined error (every sample undefined)."""
    x, p50, p95 = run.metric(TIME), run.metric(f"{ERROR}.p50"), run.metric(f"{ERROR}.p95")
    if x is None or p50 is None:
        return None
    return {"x": x, "p50": p50, "p95": p95 if p95 is not None else p50}


def breakdown(run):
    """The right panel's bars of a run: {mean: relative_l2.mean (None when undefined), parts: {source:
    relative_l2_part_mean} for the sources that occurred, points: {source: points}, missed, ghost (the
    shares' means, None when not measured), samples, undefined}."""
    sources = ((run.summary.get("force_error") or {}).get("by_source")) or {}
    parts, points = {}, {}
    for s in SOURCES:
        entry = sources.get(s) or {}
        count = entry.get("points")
        if isinstance(count, (int, float)) and count > 0:
            points[s] = count
            part = run.metric(f"force_error.by_source.{s}.relative_l2_part_mean")
            if part is not None:
                parts[s] = part
    return {"mean": run.metric(f"{ERROR}.mean"), "parts": parts, "points": points,
            "missed": run.metric("force_error.missed_share.mean"), "ghost": run.metric("force_error.ghost_share.mean"),
            "samples": run.metric("force_error.samples"), "undefined": run.metric("force_error.undefined_samples")}


def group_point(group):
    """point() of a configuration: one run's own, or for repeats the medians of x, p50 and p95 over the runs
    with a point, with lo, hi (the p50's bootstrap 95 % interval) and n; None when no run has a point."""
    points = [p for p in (point(r) for r in group) if p is not None]
    if len(group) == 1 or not points:
        return dict(points[0], lo=None, hi=None, n=len(points)) if points else None
    p50, lo, hi = statistics.bootstrap_median_interval([p["p50"] for p in points])
    return {"x": statistics.median([p["x"] for p in points]), "p50": p50,
            "p95": statistics.median([p["p95"] for p in points]), "lo": lo, "hi": hi, "n": len(points)}


def group_breakdown(group):
    """breakdown() of a configuration: one run's own, or for repeats the medians over its runs of the mean
    error (mean_interval: its bootstrap 95 % interval), of each source's part (over the runs it occurred in)
    and of the missed and ghost shares; points, samples and undefined samples summed; n the runs."""
    if len(group) == 1:
        return dict(breakdown(group[0]), mean_interval=None, n=1)
    bs = [breakdown(r) for r in group]

    def med(values):
        return statistics.median([v for v in values if v is not None])

    mean, lo, hi = statistics.bootstrap_median_interval([b["mean"] for b in bs if b["mean"] is not None])
    parts = {s: med(b["parts"].get(s) for b in bs) for s in SOURCES if any(s in b["parts"] for b in bs)}
    points = {s: sum(b["points"].get(s, 0) for b in bs) for s in SOURCES if any(s in b["points"] for b in bs)}

    def total(key):
        values = [b[key] for b in bs if b[key] is not None]
        return sum(values) if values else None

    return {"mean": mean, "mean_interval": None if lo is None else (lo, hi), "parts": parts, "points": points,
            "missed": med(b["missed"] for b in bs), "ghost": med(b["ghost"] for b in bs),
            "samples": total("samples"), "undefined": total("undefined"), "n": len(group)}


def share_text(value):
    return "n/a" if value is None else f"{100 * value:.3g} %"


def top_of(members):
    """The highest bar of a breakdown panel (0 when none)."""
    values = [v for g in statistics.repeats(members) for b in [group_breakdown(g)]
              for v in [b["mean"], *b["parts"].values(), *(b.get("mean_interval") or ())] if v is not None]
    return max(values + [0.0])


def breakdown_note(b):
    """The text above a run's bars: missed and ghost shares (means over samples), each source's share of the
    run's force points, samples."""
    note = f"median of {b['n']} runs:\n" if b.get("n", 1) > 1 else ""
    note += f"missed {share_text(b['missed'])}\nghost {share_text(b['ghost'])}"
    total = sum(b["points"].values())
    if total:
        note += "\npoints:" + "".join(f"\n{s} {100 * n / total:.0f} %" for s, n in b["points"].items())
    if b["samples"] is not None:
        note += f"\n{b['samples']:.0f} samples"
    if b["undefined"]:
        note += f"\n{b['undefined']:.0f} undefined"
    return note


def y_scale(values):
    """("symlog", linthresh) when there are zeros beside positive values, ("log", None) when the positive ones
    span a decade or more, ("linear", None) otherwise: full's 0 stays on the axis."""
    positive = [v for v in values if v > 0]
    if not positive:
        return "linear", None
    if any(v <= 0 for v in values):
        return "symlog", 10 ** math.floor(math.log10(min(positive)))
    return ("log", None) if max(positive) >= 10 * min(positive) else ("linear", None)


def point_label(run, p):
    return "0 (full)" if p["p50"] == 0 and run.method_label == pairing.REFERENCE_METHOD else f"{p['p50']:.3g}"


def draw_points(ax, members, colours, markers):
    """Left panel. Returns the runs drawn."""
    drawn, values, xs = [], [], []
    for group in statistics.repeats(members):
        p, r = group_point(group), group[0]
        if p is None:
            continue
        colour, marker = colours[r.method_label], markers[r.budget_label]
        if p["p95"] > p["p50"]:
            ax.plot([p["x"], p["x"]], [p["p50"], p["p95"]], color=colour, lw=1, alpha=0.7)
            ax.plot(p["x"], p["p95"], marker="_", color=colour, ms=8)
        if p["lo"] is not None:  # repeats: the median p50's bootstrap 95 % interval
            ax.errorbar(p["x"], p["p50"], yerr=[[p["p50"] - p["lo"]], [p["hi"] - p["p50"]]], color="k", lw=0.7,
                        capsize=2)
            values += [p["lo"], p["hi"]]
        ax.plot(p["x"], p["p50"], marker=marker, color=colour, ms=6, ls="none", mec="k", mew=0.4)
        label = point_label(r, p) + (f" (median of {p['n']})" if len(group) > 1 else "")
        ax.annotate(label, (p["x"], p["p50"]), xytext=(5, -3), textcoords="offset points", fontsize=6)
        values += [p["p50"], p["p95"]]
        xs.append(p["x"])
        drawn += group
    scale, linthresh = y_scale(values)
    if scale == "symlog":
        ax.set_yscale("symlog", linthresh=linthresh, linscale=0.4)
        ax.set_ylim(-0.2 * linthresh, max(values) * 3)
    elif scale == "log":
        ax.set_yscale("log")
        ax.set_ylim(min(values) / 2, max(values) * 3)
    else:
        ax.set_ylim(0, max(values + [1e-3]) * 1.25)
    ax.set_xlim(0, max(xs + [1e-3]) * 1.2)
    ax.set_xlabel("p99 handling time per step (ms)", fontsize=8)
    ax.set_ylabel("force error, relative L2 per sampled step\n(marker: p50; whisker: to p95)", fontsize=8)
    ax.tick_params(labelsize=7)
    return drawn


def draw_breakdown(ax, members):
    """Right panel: per run, the mean error (grey) and each source's part (coloured). Returns the sources
    drawn."""
    width, used, top = 0.16, set(), 0.0
    groups = statistics.repeats(members)
    for k, group in enumerate(groups):
        b = group_breakdown(group)
        bars = [("mean", b["mean"], "0.35")] + [(s, b["parts"][s], SOURCE_COLOURS[s]) for s in SOURCES
                                                if s in b["parts"] and b["parts"][s] is not None]
        start = k - width * (len(bars) - 1) / 2
        highest = 0.0
        for j, (name, value, colour) in enumerate(bars):
            if value is None:
                continue
            ax.bar(start + j * width, value, width=width * 0.95, color=colour, linewidth=0)
            tip = value
            if name == "mean" and b["mean_interval"] is not None:  # repeats: the median's bootstrap interval
                lo, hi = b["mean_interval"]
                ax.errorbar(start + j * width, value, yerr=[[value - lo], [hi - value]], color="k", lw=0.7,
                            capsize=1.5)
                tip = max(value, hi)
            ax.text(start + j * width, tip, f" {value:.2g}", rotation=90, ha="center", va="bottom", fontsize=5)
            used.add(name)
            highest = max(highest, tip)
            top = max(top, tip)
        ax.text(k, highest + 0.12 * top_of(members), breakdown_note(b), ha="center", va="bottom", fontsize=5.5)
    seeds_vary = len({m.seed for m in members}) > 1

    def tick(group):
        text = broken(tick_label(group[0], with_scene=False))
        if len(group) > 1:
            return text + f"\n(n={len(group)} seeds)"
        return text + (f"\nseed {group[0].seed}" if seeds_vary else "")

    ax.set_xticks(range(len(groups)), [tick(g) for g in groups], fontsize=6)
    ax.set_xlim(-0.6, max(len(groups), 2) - 0.4)
    ax.set_ylim(0, max(top, 1e-3) * 1.75)  # room for the notes
    ax.set_ylabel("relative L2 error: mean, and each\nsource's part (mean over its samples)", fontsize=8)
    ax.tick_params(labelsize=7)
    return used


def draw(ctx, runs):
    groups = rows(runs)
    if not groups:
        return ctx.missing(TITLE, "no run has summary.force_error (runs without --force-reference)")
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    everything = [r for _, members in groups for r in members]
    colours = method_colours(runs)  # over all runs in scope: a method's colour is the divergence figure's too
    drawn = {r.method_label for r in everything}
    budgets = sorted({r.budget_label: r for r in everything}.values(), key=lambda r: r.budget_order())
    markers = {r.budget_label: MARKERS[k % len(MARKERS)] for k, r in enumerate(budgets)}
    most = max(len(statistics.repeats(members)) for _, members in groups)
    fig, axes = plt.subplots(len(groups), 2, figsize=(6.0 + max(5.0, 1.3 * most) + 2.0, 4.6 * len(groups)),
                             squeeze=False, gridspec_kw={"width_ratios": [6.0, max(5.0, 1.3 * most)]})
    used, sources = [], set()
    for (left, right), ((scene, mode), members) in zip(axes, groups):
        draw_points(left, members, colours, markers)
        sources |= draw_breakdown(right, members)
        title = f"{scene}, {response_title(mode, members)}"
        left.set_title(f"{title}: error against cost", fontsize=9)
        right.set_title(f"{title}: error by source of the force", fontsize=9)
        used += members
    handles = [Line2D([], [], color=c, lw=0, marker="o", ms=6, label=label) for label, c in colours.items()
               if label in drawn]
    handles += [Line2D([], [], color="0.4", lw=0, marker=markers[r.budget_label], ms=6,
                       label="no budget" if r.budget_label == "none" else r.budget_label) for r in budgets]
    axes[0, 0].legend(handles=handles, fontsize=6.5, loc="best")
    bar_handles = [Patch(color="0.35", label="relative L2, mean over samples")]
    bar_handles += [Patch(color=SOURCE_COLOURS[s], label=f"part: {s}") for s in SOURCES if s in sources]
    axes[0, 1].legend(handles=bar_handles, fontsize=6.5, loc="upper left", bbox_to_anchor=(1.01, 1.0),
                      borderaxespad=0)
    return ctx.save(fig, FILE, TITLE,
                    "Left: each run's force error, the relative L2 error of the per-vertex contact force field it "
                    "applied in a sampled step against the one full handling applied from the same state in the "
                    "same step (summary.force_error.relative_l2; 0: identical), as the median (p50, marker) with a "
                    "whisker up to the p95 over sampled steps, against the p99 of per-step handling time "
                    "(summary handling_ms.p99); colour: method, marker: budget; full is 0 by definition (a log "
                    "axis turns linear near 0 to show it). Right: per run, the mean relative L2 error over samples "
                    "(grey) beside the part of it from each source of the forces (by_source.*.relative_l2_part_mean: "
                    "computed this step, held from an earlier step, extrapolated, tracked), each the mean over the "
                    "samples that source occurred in. These are parts, not a sum: squared parts add up in quadrature "
                    "with the missed and reaction-only vertices to a sample's error, and a source present in only "
                    "some samples can exceed the mean over all. Above the bars: the mean share of full's points "
                    "the run gave no force (missed) and of its points full gave none (ghost). One row per scene "
                    "and contact response; noise-floor runs (full, perturbed) are left out.",
                    used, "each marker is the median of their p50s (the p95 whisker the median of their p95s, x "
                          "the median of their p99 handling times) with the p50's bootstrap 95 % interval as a "
                          "black error bar, and each group of bars the medians over the runs (the mean error's "
                          "bootstrap 95 % interval in black; points and samples summed)")
