"""The speed/accuracy trade, judged as a time-critical user would: accuracy against the p99 of per-step
handling time, with a whisker to the slowest step (max), and the same accuracy against the median below it.

The median flatters a method whose cost comes in bursts (every_nth's median step does nothing, every n-th
step costs a full cycle): a deadline sees the p99 and the max. Recall is drawn as its mean over the oracle
steps beside its minimum, since one bad step makes the minimum 0. One row pair per scene, one curve per
method (and setup) joined across its budgets from the largest to the smallest.
"""
from ..context import plt
from .. import pairing, statistics
from ._common import by_scene, method_order

TITLE = "The speed/accuracy trade"
ORDER = 6
SCOPE = "all"
FILE = "fig6_tradeoff"

# The statistics of summary.handling_ms the x axes use: (statistic, axis label, row title, whisker statistic).
TIMES = (("p99", "p99 handling time per step (ms)\n(whisker: to the max step)", "against p99 (whisker to max)",
          "max"),
         ("p50", "median (p50) handling time per step (ms)", "against the median (p50)", None))
# One panel per accuracy measure: (title, y label, [(summary key, legend text, marker, line style)], scale:
# the summary's unit to the axis's; depths in mm, so no axis needs an offset like 1e-5).
PANELS = (("recall", "recall over oracle steps",
           (("recall_mean", "recall mean", "o", "-"), ("recall_min", "recall min", "v", "--")), 1.0),
          ("mean depth error", "depth error, mean (mm)", (("depth_err.mean", "depth error mean", "o", "-"),), 1e3),
          ("deepest true penetration", "true penetration, max (mm)", (("max_depth", "max depth", "o", "-"),), 1e3))
# Distinct at a glance, neighbours too (interruptible and interruptible_tracked are drawn side by side).
PALETTE = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:olive", "tab:cyan", "tab:brown",
           "tab:pink", "tab:gray")
ACCURACY_KEYS = ("recall_min", "recall_mean")  # a scene is drawn when the oracle gave it a recall


def handling(stat):
    return f"handling_ms.{stat}"


def curves(runs):
    """{legend: [runs]}: one curve per method label; per setup too when a scene has several
    (contact response, mesh order, scene overrides, RNG seeds), so different experiments are never joined by
    a line. The legend names only what differs between the setups."""
    setups = [pairing.setup(r) for r in runs]
    varies = [len({s[k] for s in setups}) > 1 for k in range(5)]  # scene, seed, response, mesh order, overrides
    out = {}
    for r, (_, seed, response, mesh_order, overrides) in zip(runs, setups):
        # Seeds are repeats of one configuration: points() draws their median, so they share a curve.
        parts = (([f"{response} response"] if varies[2] else []) + ([f"mesh_order={mesh_order}"] if varies[3] else [])
                 + (list(overrides) if varies[4] else []))
        key = r.method_label + (" [" + " ".join(parts) + "]" if parts else "")
        out.setdefault(key, []).append(r)
    return dict(sorted(out.items(), key=lambda item: (method_order(item[1][0]), item[0])))


def points(runs, stat, key, whisker=None):
    """[(x, y, whisker x or None, run)]: x the run's handling_ms.<stat>, y its summary `key`, the whisker
    its handling_ms.<whisker>; runs missing x or y are left out. In budget order (no budget, then from the
    largest budget to the smallest), so a curve follows the budget rather than zigzagging along x."""
    out = []
    for group in statistics.repeats(runs):
        measured = [m for m in group if m.metric(handling(stat)) is not None and m.metric(key) is not None]
        if not measured:
            continue
        # Repeats (seeds) of one configuration: one point at the medians, its first run standing for it.
        x = statistics.median([m.metric(handling(stat)) for m in measured])
        y = statistics.median([m.metric(key) for m in measured])
        ws = [m.metric(handling(whisker)) for m in measured if whisker and m.metric(handling(whisker)) is not None]
        out.append((x, y, statistics.median(ws) if ws else None, measured[0]))
    return sorted(out, key=lambda p: (p[3].budget_order(), p[3].seed if p[3].seed is not None else -1, p[3].name))


def spread(runs, point_run, key):
    """(lo, hi) of the bootstrap 95 % interval of `key` over point_run's repeats among runs, or None."""
    group = [r for r in runs if statistics.configuration(r) == statistics.configuration(point_run)]
    _, lo, hi = statistics.bootstrap_median([r.metric(key) for r in group if r.metric(key) is not None])
    return None if lo is None else (lo, hi)


def scenes_drawn(runs):
    """{scene: [runs]}: the scenes the oracle measured a recall in, with their runs that have a handling time
    for some x axis."""
    out = {}
    for scene, rs in by_scene(runs).items():
        if not any(r.metric(k) is not None for r in rs for k in ACCURACY_KEYS):
            continue
        rs = [r for r in rs if any(r.metric(handling(stat)) is not None for stat, *_ in TIMES)]
        if rs:
            out[scene] = rs
    return out


def colour_map(scenes):
    """{curve legend: colour}, the same for a method in every scene."""
    names = {}
    for rs in scenes.values():
        for name, members in curves(rs).items():
            names.setdefault(name, members[0])
    ordered = sorted(names, key=lambda name: (method_order(names[name]), name))
    return {name: PALETTE[k % len(PALETTE)] for k, name in enumerate(ordered)}


def legend(ax, colours, used_styles, whiskers):
    from matplotlib.lines import Line2D
    handles = [Line2D([], [], color=c, lw=1.5, label=name) for name, c in colours.items()]
    for _, _, series, _ in PANELS:
        for key, text, marker, style in series:
            if key in used_styles and len(series) > 1:  # a panel with one series needs no key to its marks
                handles.append(Line2D([], [], color="0.3", marker=marker, ls=style, ms=4, label=text,
                                      mfc="0.3" if style == "-" else "white"))
    if whiskers:
        handles.append(Line2D([], [], color="0.3", lw=0.8, alpha=0.6, marker="|", ms=7,
                              label="whisker: p99 to max"))
    ax.legend(handles=handles, fontsize=6.5, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0)


def draw(ctx, runs):
    scenes = scenes_drawn(runs)
    if not scenes:
        return ctx.missing(TITLE, "no run with the oracle (recall_min or recall_mean in its summary) and a "
                                  "handling time")
    fig, axes = plt.subplots(2 * len(scenes), len(PANELS), figsize=(15, 3.3 * 2 * len(scenes)), squeeze=False)
    sources, palette = [], colour_map(scenes)
    for number, (scene, rs) in enumerate(scenes.items()):
        lines = curves(rs)
        colours = {name: palette[name] for name in lines}
        used_styles, whiskers = set(), False
        for (stat, xlabel, row_title, whisker), row in zip(TIMES, axes[2 * number:2 * number + 2]):
            for ax, (title, ylabel, series, scale) in zip(row, PANELS):
                for name, members in lines.items():
                    for key, _, marker, style in series:
                        pts = points(members, stat, key, whisker)
                        if not pts:
                            continue
                        used_styles.add(key)
                        pts = [(x, scale * y, w, r) for x, y, w, r in pts]
                        xs, ys = [p[0] for p in pts], [p[1] for p in pts]
                        ax.plot(xs, ys, ls=style, marker=marker, ms=4, lw=1, color=colours[name],
                                mfc=colours[name] if style == "-" else "white")
                        if key == "recall_mean" and len(pts) > 1:  # name the ends: which way the budget shrinks
                            for x, y, _, r in (pts[0], pts[-1]):
                                ax.annotate(r.budget_label, (x, y), xytext=(3, 3), textcoords="offset points",
                                            fontsize=5.5, color=colours[name])
                        for x, y, w, r in pts:
                            interval = spread(members, r, key)
                            if interval is not None:
                                ax.errorbar(x, y, yerr=[[y - scale * interval[0]], [scale * interval[1] - y]],
                                            color=colours[name], lw=0.7, capsize=1.5)
                            if w is not None and w > x:
                                whiskers = True
                                ax.plot([x, w], [y, y], color=colours[name], lw=0.8, alpha=0.6, marker="|",
                                        ms=7, markevery=[1])
                ax.set_xlabel(xlabel, fontsize=8)
                ax.set_ylabel(ylabel, fontsize=8)
                ax.set_title(f"{scene}: {title}, {row_title}", fontsize=8.5)
                ax.tick_params(labelsize=7)
                ax.set_xlim(left=-0.03 * ax.get_xlim()[1])  # a point at 0 ms (every_nth's median) shows whole
        for row in axes[2 * number:2 * number + 2]:
            row[0].set_ylim(-0.04, 1.04)  # recall is a share
        legend(axes[2 * number][-1], colours, used_styles, whiskers)
        sources += rs
    return ctx.save(fig, FILE, TITLE,
                    "Each point is one run, or the medians of a configuration's repeats (seeds) with the "
                    "accuracy's bootstrap 95 % interval as a vertical bar; one curve per method across its budgets, joined from the largest budget "
                    "to the smallest (the recall panels name both ends). Upper row of each scene: accuracy against "
                    "the p99 of per-step collision handling time (summary handling_ms.p99), a whisker reaching the "
                    "slowest step (max); lower row: the same against the median (p50), which flatters methods whose "
                    "cost comes in bursts (every_nth's median step does no work). Recall (oracle steps) as its mean "
                    "(filled, solid) and its minimum (hollow, dashed): one bad step makes the minimum 0. Depth "
                    "error: the mean over all oracle depth errors; penetration: the deepest true one (max), in mm.",
                    sources)
