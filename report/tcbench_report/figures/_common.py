"""Helpers shared by several figures (not a figure: the leading underscore)."""
from collections import defaultdict


def by_scene(runs):
    """{scene: [runs]} in scene order."""
    groups = defaultdict(list)
    for r in runs:
        groups[r.scene].append(r)
    return dict(sorted(groups.items()))


def width_for(count, per_item=0.7, minimum=6.0, maximum=40.0):
    """Figure width in inches for count bars or ticks, so labels stay readable."""
    return min(maximum, max(minimum, per_item * count + 2))


def tick_label(run, with_scene=True):
    parts = ([run.scene] if with_scene else []) + [run.method_label]
    if run.budget_kind != "none":
        parts.append(run.budget_label)
    return "\n".join(parts)


def grid(count, columns=2):
    """(rows, columns) for count panels."""
    cols = min(columns, max(1, count))
    return (count + cols - 1) // cols, cols
