"""Sensitivity of the spatial hash: how the cell size and the table size a user sets move recall,
handling time and the largest task's cost.

Drawn from the sweeps that declare "hash_sensitivity" (experiments/sweeps/paper/7_hash_sensitivity.toml):
runs that set `collision.cell_size` or `collision.table_size` (as "auto*K" or a number), and the runs of
the scene's defaults ("auto"), which sit at factor 1 on both axes. One row of panels per scene and
measure, one column per parameter: the cell size over the mean tet edge, the table size over its automatic
size (next_prime(2 tets + 1), the detector's own default; "auto*K" is next_prime(floor(2 K tets) + 1), so
about K). The factors are read from what the run resolved (run.json "collision": cell_size_m over
mean_edge_m, table_size over the automatic size of its tets), so a size given as a number lands where it
belongs; a run recorded without that block is placed by its override ("auto*K": K; no override: 1) and
a number without it cannot be placed. The largest task's cost is its wall-clock p99 (summary.max_task_us,
wall budgets only) where a line's runs all have it, else the largest single charge in work units
(summary.max_task_work), on the right-hand axis. Repeats of a configuration (runs differing only by seed)
are one point: the median with its bootstrap 95 % interval.
"""
from matplotlib.ticker import NullFormatter

from .. import statistics
from ..context import plt
from ._common import method_colours, method_order

TITLE = "Sensitivity of the hash: cell size and table size"
ORDER = 9
SCOPE = "declared"
FILE = "fig9_hash_sensitivity"
PARAMETERS = (("cell_size", "cell size / mean tet edge"),
              ("table_size", "table size / automatic size (next prime from 2 tets + 1)"))
TASK_US, TASK_WORK = "max_task_us.p99", "max_task_work"
TASK = "largest task"  # the measure that falls back from TASK_US to TASK_WORK
METRICS = (("recall_mean", "recall (mean over oracle steps)", False),
           ("handling_ms.p50", "handling time p50 (ms)", True),
           (TASK, "largest task p99 (µs)", True))
TASK_WORK_LABEL = "largest task (work units; lines\nwithout a wall budget, hollow)"


def override(run, parameter):
    """The value the run's `collision.<parameter>=...` override gives, as written; None without one."""
    for o in run.overrides:
        key, _, value = o.partition("=")
        if key.strip() == f"collision.{parameter}":
            return value.strip().strip("'\"")
    return None


def varied(run):
    """The hash parameter the run sets ('cell_size', 'table_size'), or None for the scene's default."""
    for name, _ in PARAMETERS:
        if override(run, name) is not None:
            return name
    return None


def next_prime(n):
    """The detector's next_prime (method/detection/spatial_hash.cpp): the first odd prime from n | 1."""
    if n <= 2:
        return 2
    c = n | 1
    while any(c % d == 0 for d in range(3, int(c ** 0.5) + 1, 2)):
        c += 2
    return c


def automatic_table_size(tets):
    return next_prime(2 * int(tets) + 1)


def requested_factor(text):
    """K of "auto*K", 1 for "auto", None for a number (or anything else)."""
    if text == "auto":
        return 1.0
    if text.startswith("auto*"):
        try:
            return float(text[5:])
        except ValueError:
            return None
    return None


def factor(run, parameter):
    """The run's size relative to its automatic value: from what run.json "collision" resolved where it
    has it, else from the override ("auto*K": K; none: the scene's default, 1); None when neither tells."""
    c = run.record.get("collision") or {}
    if parameter == "cell_size" and c.get("cell_size_m") and c.get("mean_edge_m"):
        return c["cell_size_m"] / c["mean_edge_m"]
    if parameter == "table_size" and c.get("table_size") and c.get("tets"):
        return c["table_size"] / automatic_table_size(c["tets"])
    text = override(run, parameter)
    return 1.0 if text is None else requested_factor(text)


def line_label(run):
    return run.method_label + ("" if run.budget_label == "none" else f" @ {run.budget_label}")


def lines(runs, scene, parameter):
    """{line label: [runs]}: the scene's runs that vary `parameter` or neither (the defaults) and can be
    placed on its axis, by method label and budget, in method order."""
    out = {}
    for r in sorted(runs, key=lambda r: (method_order(r), r.budget_order(), r.name)):
        if r.scene == scene and varied(r) in (None, parameter) and factor(r, parameter) is not None:
            out.setdefault(line_label(r), []).append(r)
    return out


def task_key(runs):
    """TASK_US when every run has it (a wall budget), else TASK_WORK."""
    return TASK_US if runs and all(r.metric(TASK_US) is not None for r in runs) else TASK_WORK


def points(runs, scene, parameter, key):
    """{line label: [(factor, median, lo, hi, n)]} sorted by factor: one point per configuration, a single
    run's value or the median of its repeats with the bootstrap 95 % interval (lo, hi None for one run).
    key TASK picks task_key per line."""
    out = {}
    for label, members in lines(runs, scene, parameter).items():
        k = task_key(members) if key == TASK else key
        for group in statistics.repeats(members):
            median, lo, hi, n = statistics.summarise(r.metric(k) for r in group)
            if median is not None:
                out.setdefault(label, []).append((factor(group[0], parameter), median, lo, hi, n))
    return {label: sorted(p, key=lambda p: p[0]) for label, p in out.items()}


def scenes_drawn(runs):
    """The scenes with a run that sets the cell or the table size and can be placed."""
    return sorted({r.scene for r in runs if varied(r) and factor(r, varied(r)) is not None})


def draw_line(ax, pts, colour, budgeted, label, hollow=False):
    ax.plot([p[0] for p in pts], [p[1] for p in pts], marker="o", ms=3, lw=1, color=colour,
            ls=(":" if hollow else "-") if budgeted else "--", mfc="white" if hollow else colour, label=label)
    for x, y, lo, hi, _ in pts:
        if lo is not None:
            ax.errorbar(x, y, yerr=[[y - lo], [hi - y]], color=colour, lw=0.7, capsize=1.5)


def draw(ctx, runs):
    scenes = scenes_drawn(runs)
    if not scenes:
        return ctx.missing(TITLE, "no run of the sweeps declaring this figure sets collision.cell_size or "
                                  "collision.table_size")
    colours = method_colours(runs)
    fig, axes = plt.subplots(len(METRICS) * len(scenes), len(PARAMETERS),
                             figsize=(4.2 * len(PARAMETERS) + 2.5, 2.5 * len(METRICS) * len(scenes)), squeeze=False)
    used, handles = [], {}
    for number, scene in enumerate(scenes):
        for col, (parameter, axis_label) in enumerate(PARAMETERS):
            members = lines(runs, scene, parameter)
            used += [r for rs in members.values() for r in rs]
            factors = sorted({round(factor(r, parameter), 3) for rs in members.values() for r in rs} | {1.0})
            for row, (key, metric_label, log) in enumerate(METRICS):
                ax = axes[len(METRICS) * number + row][col]
                twin = None
                for label, pts in points(runs, scene, parameter, key).items():
                    first = members[label][0]
                    colour, budgeted = colours.get(first.method_label, "0.3"), first.budget_label != "none"
                    if key == TASK and task_key(members[label]) == TASK_WORK:
                        if twin is None:
                            twin = ax.twinx()
                            twin.set_yscale("log")
                            twin.set_ylabel(TASK_WORK_LABEL, fontsize=6)
                            twin.tick_params(which="both", labelsize=6)
                        draw_line(twin, pts, colour, budgeted, label, hollow=True)
                    else:
                        draw_line(ax, pts, colour, budgeted, label)
                    handles.setdefault(label, (colour, budgeted))
                ax.set_xscale("log")
                if log:
                    ax.set_yscale("log")
                ax.axvline(1.0, color="0.7", lw=0.6)
                ax.set_title(f"{scene}: {parameter.replace('_', ' ')}", fontsize=8)
                if row == len(METRICS) - 1:
                    ax.set_xlabel(axis_label, fontsize=7)
                if col == 0:
                    ax.set_ylabel(metric_label, fontsize=7)
                ax.tick_params(which="both", labelsize=6)
                # Tick the factors that were run: a log axis over less than a decade labels nothing else.
                ax.xaxis.set_minor_formatter(NullFormatter())
                ax.set_xticks(factors, [f"{f:g}" for f in factors])
    from matplotlib.lines import Line2D
    legend = [Line2D([], [], color=c, ls="-" if budgeted else "--", marker="o", ms=3, label=label)
              for label, (c, budgeted) in handles.items()]
    if legend:
        axes[0][-1].legend(handles=legend, fontsize=6, loc="upper left", bbox_to_anchor=(1.25, 1.0))
    return ctx.save(fig, FILE, f"{TITLE}: {', '.join(scenes)}",
                    "Each column varies one parameter of the spatial hash (the other at its automatic value), as a "
                    "factor of its automatic value (log scale; the scene's default, auto, at 1, grey line): the "
                    "cell size as a multiple of the mean tet edge, the table size as a multiple of next_prime(2 "
                    "tets + 1), both as the run resolved them (run.json collision). Rows, per scene: mean recall "
                    "against the oracle, median (p50) handling time, and the largest task's cost: the p99 over "
                    "steps of the longest interval between two budget checks (summary max_task_us, wall budgets "
                    "only: the granularity a budget sees), or, for a line without a wall budget, the largest "
                    "single charge in work units (max_task_work, hollow markers, right-hand axis). One line per "
                    "method and budget; dashed: unbudgeted, solid: under the budget named.", used)
