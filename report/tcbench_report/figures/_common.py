"""Helpers shared by several figures (not a figure: the leading underscore)."""
from collections import defaultdict

from .. import pairing


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


def budget_bars(ax, ctx, runs, key, colours, note=None):
    """One bar per run of summary `key` (> 0: log scales), grouped by budget along x and coloured by
    method; hatched with a red edge when the run is not ok; a black segment across each bar at its
    reference's value (full, no budget, same setup). note(run) -> extra text written above the bar.
    Returns (the runs drawn and their references, the values drawn) for log_limits."""
    x, ticks, labels, used, values = 0.0, [], [], [], []
    for label, members in budget_groups(runs):
        start = x
        for r in members:
            value = r.metric(key)
            ok = r.status == "ok"
            if value is not None and value > 0:
                ax.bar(x, value, width=0.8, color=colours[r.method_label], hatch=None if ok else "xx",
                       edgecolor="none" if ok else "red", linewidth=0.8)
                values.append(value)
            ref = ctx.reference(r)
            ref_value = ref.metric(key) if ref else None
            if ref_value is not None and ref_value > 0:
                ax.hlines(ref_value, x - 0.48, x + 0.48, colors="k", linewidth=1.4)
                values.append(ref_value)
                used.append(ref)
            text = "n/a" if value is None else f"{value:.3g}"
            text += "" if ok else f", {r.status}"
            extra = note(r) if note else None
            if extra:
                text += f", {extra}"
            if pairing.is_noise_floor(r):  # full under a perturb.* override: the divergence floor, not another full
                text += ", noise-floor run (perturbed)"
            if len(members) > 1 and len({m.seed for m in members if m.method_label == r.method_label}) > 1:
                text = f"seed {r.seed}: {text}"
            top = max([v for v in (value, ref_value) if v is not None and v > 0] or [min(values, default=1)])
            ax.text(x, top * 1.08, text, rotation=90,
                    ha="center", va="bottom", fontsize=5.5)
            used.append(r)
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
