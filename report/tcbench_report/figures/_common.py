"""Helpers shared by several figures (not a figure: the leading underscore)."""
from collections import defaultdict

from .. import pairing, statistics


def by_scene(runs):
    """{scene: [runs]} in scene order."""
    groups = defaultdict(list)
    for r in runs:
        groups[r.scene].append(r)
    return dict(sorted(groups.items()))


def width_for(count, per_item=0.7, minimum=6.0, maximum=40.0):
    """Figure width in inches for count bars or ticks, so labels stay readable."""
    return min(maximum, max(minimum, per_item * count + 2))


def wrapped(method_label):
    """A method label with settings, "interruptible(fine_tasks=true,reserve_apply=true)", one setting a line,
    so neighbouring tick labels do not run into each other."""
    return method_label.replace("(", "(\n").replace(",", ",\n")


def broken(text, width=16):
    """text with every line longer than width broken after an underscore ("interruptible_no_\nextrapolation"),
    so a long method name under a narrow bar does not run into its neighbours."""
    lines = []
    for line in text.split("\n"):
        while len(line) > width and "_" in line[1:width]:
            cut = line.rindex("_", 1, width) + 1
            lines.append(line[:cut])
            line = line[cut:]
        lines.append(line)
    return "\n".join(lines)


def tick_label(run, with_scene=True, with_response=False):
    parts = ([run.scene] if with_scene else []) + [wrapped(run.method_label)]
    if run.budget_kind != "none":
        parts.append(run.budget_label)
    if with_response:
        parts.append(run.response)
    return "\n".join(parts)


def mixed_responses(runs):
    """True when runs integrate contact in more than one mode: labels must then say which."""
    return len({r.response for r in runs}) > 1


def grid(count, columns=2):
    """(rows, columns) for count panels."""
    cols = min(columns, max(1, count))
    return (count + cols - 1) // cols, cols


# ---------------------------------------------------------------- bars by budget, panels by response

METHOD_ORDER = ("full", "every_nth", "interruptible", "interruptible_no_extrapolation", "interruptible_tracked")


def method_order(run):
    return (METHOD_ORDER.index(run.method) if run.method in METHOD_ORDER else len(METHOD_ORDER), run.method_label)


def method_colours(runs):
    """{method label: colour}, the same in every panel of a figure."""
    labels = sorted({r.method_label for r in runs}, key=lambda label: method_order(
        next(r for r in runs if r.method_label == label)))
    return {label: f"C{k % 10}" for k, label in enumerate(labels)}


def by_response(runs):
    """[(mode, [runs])], implicit first: one panel per contact response."""
    from ..loader import response_order
    groups = {}
    for r in runs:
        groups.setdefault(r.response, []).append(r)
    return sorted(groups.items(), key=lambda item: response_order(item[0]))


def response_title(mode, runs):
    """A panel's name for its mode; says so when the runs predate run.json's "response" field."""
    return f"{mode} response" + ("" if all(r.response_recorded for r in runs) else " (not recorded: older run)")


def budget_groups(runs):
    """[(tick label, [runs])]: no budget first, then from the largest budget to the smallest; within one,
    by method and seed. Runs of different lengths (a 600-step and a 2000-step sweep) never share a group."""
    lengths = len({r.record.get("steps") for r in runs}) > 1
    groups = {}
    for r in sorted(runs, key=lambda r: (r.budget_order(), r.record.get("steps") or 0, method_order(r),
                                         r.seed if r.seed is not None else -1, r.name)):
        key = (r.budget_label, r.record.get("steps") if lengths else None)
        groups.setdefault(key, []).append(r)
    return [(("no budget" if label == "none" else label) + (f"\n{steps} steps" if steps is not None else ""), members)
            for (label, steps), members in groups.items()]


def bars_width(runs):
    """Inches one budget_bars panel needs."""
    return max(3.5, 0.32 * len(runs) + 0.5 * len(budget_groups(runs)) + 1.2)


def budget_bars(ax, ctx, runs, key, colours, note=None, group_note=None):
    """One bar per configuration of summary `key` (> 0: log scales), grouped by budget along x and
    coloured by method: a single run's value, or the median of a configuration's repeats with its
    bootstrap 95 % interval as a whisker; hatched with a red edge when a run is not ok; a black segment
    across each bar at its reference's value (full, no budget, same setup; the references' median).
    note(run) -> extra text written above a single run's bar; group_note(runs) the same for a configuration's
    repeats (a rate: "collapsed 2/5 (...)").
    Returns (the runs drawn and their references, the values drawn) for log_limits."""
    x, ticks, labels, used, values = 0.0, [], [], [], []
    for label, members in budget_groups(runs):
        start = x
        # Repeats of one configuration (runs that differ only by seed) share one bar: their median, with
        # its bootstrap 95 % interval as a whisker (statistics.py).
        for group in statistics.repeats(members):
            r = group[0]
            measured = [m.metric(key) for m in group if m.metric(key) is not None]
            value, lo, hi = statistics.bootstrap_median(measured) if measured else (None, None, None)
            ok = all(m.status == "ok" for m in group)
            if value is not None and value > 0:
                ax.bar(x, value, width=0.8, color=colours[r.method_label], hatch=None if ok else "xx",
                       edgecolor="none" if ok else "red", linewidth=0.8)
                values.append(value)
                if lo is not None and lo > 0:
                    ax.errorbar(x, value, yerr=[[value - lo], [hi - value]], color="0.2", lw=0.8, capsize=2)
                    values.extend([lo, hi])
            refs = [ref for ref in (ctx.reference(m) for m in group) if ref is not None]
            ref_values = [ref.metric(key) for ref in refs if ref.metric(key) is not None]
            ref_value = statistics.median(ref_values) if ref_values else None
            if ref_value is not None and ref_value > 0:
                ax.hlines(ref_value, x - 0.48, x + 0.48, colors="k", linewidth=1.4)
                values.append(ref_value)
                used.extend(refs)
            text = "n/a" if value is None else f"{value:.3g}"
            if len(group) > 1:
                text = f"median of {len(group)}: {text}" + (f" [{lo:.3g}, {hi:.3g}]" if lo is not None else "")
            bad = [m for m in group if m.status != "ok"]
            if bad:
                text += f", {bad[0].status}" if len(group) == 1 else f", {len(bad)} of {len(group)} not ok"
            extra = (note(r) if note else None) if len(group) == 1 else (group_note(group) if group_note else None)
            if extra:
                text += f", {extra}"
            if pairing.is_noise_floor(r):  # full nudged by perturb.position: the divergence floor, not another full
                text += ", noise-floor run (perturbed)"
            top = max([v for v in (value, ref_value, hi) if v is not None and v > 0] or [min(values, default=1)])
            ax.text(x, top * 1.08, text, rotation=90,
                    ha="center", va="bottom", fontsize=5.5)
            used.extend(group)
            x += 1
        ticks.append((start + x - 1) / 2)
        labels.append(label)
        x += 0.6
    ax.set_xticks(ticks, labels, fontsize=7)
    ax.set_xlim(-0.8, x - 0.6 + 0.2)
    ax.set_yscale("log")
    return used, values


def log_limits(axes, values):
    """One log range for panels sharing their y axis, with room above the bars for the rotated notes."""
    if values:
        for ax in axes:
            ax.set_ylim(min(values) / 3, max(values) * 40)


def bars_legend(ax, colours, runs):
    """Methods, the reference segment, and the mark of a run that is not ok; outside the panel, right."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    handles = [Patch(color=c, label=label) for label, c in colours.items()]
    handles.append(Line2D([], [], color="k", lw=1.4, label="full, same setup\n(reference)"))
    if any(r.status != "ok" for r in runs):
        handles.append(Patch(facecolor="white", hatch="xx", edgecolor="red", label="run not ok"))
    ax.legend(handles=handles, fontsize=6.5, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0)
