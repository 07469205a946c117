"""Sensitivity of the spatial hash: how the cell size and the table size a user sets move recall,
handling time and the largest task's cost.

Drawn from the sweeps that declare "hash_sensitivity" (experiments/sweeps/paper/7_hash_sensitivity.toml):
runs that set `collision.cell_size` or `collision.table_size` (as "auto*K" or a number), and the runs of
the scene's defaults, which sit at factor 1 on both axes. The factors are read from what the run resolved
(run.json "collision": cell_size_m over mean_edge_m, table_size over 2 tets + 1), so a number given in
metres lands where it belongs.
"""
from matplotlib.ticker import NullFormatter

from .. import statistics
from ..context import plt
from ._common import method_colours

TITLE = "Sensitivity of the hash: cell size and table size"
ORDER = 9
SCOPE = "declared"
FILE = "fig9_hash_sensitivity"
PARAMETERS = (("cell_size", "cell size / mean tet edge"), ("table_size", "table size / (2 tets + 1)"))
METRICS = (("recall_mean", "recall (mean)", False), ("handling_ms.p50", "handling time p50 (ms)", True),
           ("max_task_us.p99", "largest task p99 (µs)", True))


def varied(run):
    """The hash parameter the run sets ('cell_size', 'table_size'), or None for the scene's default."""
    for o in run.overrides:
        key = o.partition("=")[0].strip()
        for name, _ in PARAMETERS:
            if key == f"collision.{name}":
                return name
    return None


def factor(run, parameter):
    """The resolved size relative to its automatic value, or None when run.json does not record it."""
    c = run.record.get("collision") or {}
    if parameter == "cell_size" and c.get("cell_size_m") and c.get("mean_edge_m"):
        return c["cell_size_m"] / c["mean_edge_m"]
    if parameter == "table_size" and c.get("table_size") and c.get("tets"):
        return c["table_size"] / (2 * c["tets"] + 1)
    return None


def points(runs, scene, parameter, key):
    """{method label with budget: [(factor, median, lo, hi, n)]} sorted by factor."""
    out = {}
    for group in statistics.repeats([r for r in runs if r.scene == scene and varied(r) in (None, parameter)]):
        r = group[0]
        x = factor(r, parameter)
        values = [m.metric(key) for m in group if m.metric(key) is not None]
        if x is None or not values:
            continue
        median, lo, hi = statistics.bootstrap_median(values)
        label = r.method_label + ("" if r.budget_label == "none" else f" @ {r.budget_label}")
        out.setdefault(label, []).append((x, median, lo, hi, len(group)))
    return {label: sorted(p) for label, p in out.items()}


def draw(ctx, runs):
    runs = [r for r in runs if factor(r, "cell_size") is not None]
    if not any(varied(r) for r in runs):
        return ctx.missing(TITLE, "no run of the sweeps declaring this figure sets collision.cell_size or "
                                  "collision.table_size (and records its resolved hash in run.json)")
    scenes = sorted({r.scene for r in runs})
    colours = method_colours(runs)
    columns = [(scene, parameter, axis_label) for scene in scenes for parameter, axis_label in PARAMETERS]
    fig, axes = plt.subplots(len(METRICS), len(columns), figsize=(3.0 * len(columns), 2.4 * len(METRICS)),
                             squeeze=False)
    for col, (scene, parameter, axis_label) in enumerate(columns):
        for row, (key, metric_label, log) in enumerate(METRICS):
            ax = axes[row][col]
            for label, pts in points(runs, scene, parameter, key).items():
                method = label.split(" @ ")[0]
                xs = [p[0] for p in pts]
                ys = [p[1] for p in pts]
                ax.plot(xs, ys, marker="o", ms=3, lw=1, color=colours.get(method, "0.3"),
                        ls="-" if " @ " in label else "--", label=label)
                for x, y, lo, hi, _ in pts:
                    if lo is not None:
                        ax.errorbar(x, y, yerr=[[y - lo], [hi - y]], color=colours.get(method, "0.3"), lw=0.7)
            ax.set_xscale("log")
            if log:
                ax.set_yscale("log")
            ax.axvline(1.0, color="0.7", lw=0.6)
            if row == 0:
                ax.set_title(f"{scene}: {parameter.replace('_', ' ')}", fontsize=8)
            if row == len(METRICS) - 1:
                ax.set_xlabel(axis_label, fontsize=7)
            if col == 0:
                ax.set_ylabel(metric_label, fontsize=7)
            ax.tick_params(which="both", labelsize=6)
            ax.xaxis.set_minor_formatter(NullFormatter())
            ax.yaxis.set_minor_formatter(NullFormatter())
    handles, labels = axes[0][0].get_legend_handles_labels()
    if handles:
        axes[0][-1].legend(handles, labels, fontsize=6, loc="upper left", bbox_to_anchor=(1.02, 1.0))
    used = [r for r in runs if r.scene in scenes]
    return ctx.save(fig, FILE, f"{TITLE}: {', '.join(scenes)}",
                    "Each column varies one parameter of the spatial hash (the other at its automatic value, "
                    "factor 1, grey line): the cell size as a multiple of the mean tet edge, the table size as a "
                    "multiple of its automatic size. Rows: mean recall against the oracle, median handling "
                    "time, and the p99 of the largest task's cost (wall budgets only: the granularity a budget "
                    "sees). Dashed: unbudgeted; solid: under the budget named.", used)
