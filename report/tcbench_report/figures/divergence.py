"""How far a run's state drifted from full handling's, measured against the noise floor: full's own drift
under a 1e-9 m perturbation of the initial state (summary.divergence of the run and of its noise-floor run).

Drawn from every run with summary.divergence (runs with --reference: the sweep's full run). One column per
contact response, three rows per scene: RMS vertex distance at the last compared step, the largest linear
momentum difference, the orientation drift at the last compared step; one bar per method label and budget,
the floor marked across the bars and each bar labelled with its multiple of it. A configuration with repeats
(runs differing only by seed, each compared with its own seed's full run and floor) is one bar: the median
over its runs with the bootstrap 95 % interval as a whisker, the median of their floors across it, and the
median of the runs' multiples of their own floors (with its interval) as the label.
"""
from ..context import plt
from .. import pairing, statistics
from ..loader import response_order
from ._common import broken, method_colours, method_order, response_title, tick_label

TITLE = "Divergence from full handling, against the noise floor"
ORDER = 6.6  # after the force error
SCOPE = "all"
FILE = "fig6c_divergence"

# (summary key, axis label): the panels of a row.
STATS = ((pairing.DIVERGENCE, "RMS vertex distance to full,\nlast compared step (m)"),
         ("divergence.linear_momentum_diff_n_s.max", "linear momentum difference\nto full, max over steps (N s)"),
         ("divergence.orientation_drift_deg.final", "orientation drift to full,\nlast compared step (degrees)"))
NO_FLOOR = "no noise-floor run"


def has_divergence(run):
    return run.metric("divergence.compared_steps") is not None and not pairing.is_noise_floor(run)


def bars(runs, all_runs):
    """[((scene, response), [bar])]: the runs with summary.divergence (noise-floor runs are the floor, not
    bars) by scene and contact response, implicit first; bars by method, budget and seed. A bar is a dict:
    run, floor (its noise-floor run among all_runs, or None), values {summary key: (value, floor's value,
    multiple of the floor)} for each of STATS (None where missing)."""
    groups = {}
    for r in runs:
        if has_divergence(r):
            groups.setdefault((r.scene, r.response), []).append(r)
    out = []
    for key in sorted(groups, key=lambda key: (key[0], response_order(key[1]))):
        members = sorted(groups[key], key=lambda r: (method_order(r), r.budget_order(),
                                                     r.seed if r.seed is not None else -1, r.name))
        row = []
        for r in members:
            floor = pairing.noise_floor(r, all_runs)
            row.append({"run": r, "floor": floor,
                        "values": {k: (r.metric(k), floor.metric(k) if floor else None,
                                       pairing.floor_multiple(r, floor, k)) for k, _ in STATS}})
        out.append((key, row))
    return out


def bar_note(bar, key):
    """"1.71e-04\n357x floor", "n/a", or the value and NO_FLOOR for the bar's summary key."""
    value, floor_value, multiple = bar["values"][key]
    if value is None:
        return "n/a"
    if multiple is not None:
        return f"{value:.3g}\n{multiple:.3g}x floor"
    if bar["floor"] is None:
        return f"{value:.3g}\n{NO_FLOOR}"
    return f"{value:.3g}\n{'floor is 0: no multiple' if floor_value == 0 else 'no floor'}"


def bar_groups(row):
    """[[bar]]: the bars of one configuration together (repeats, by seed), in the row's order."""
    groups = {}
    for bar in row:
        groups.setdefault(statistics.configuration(bar["run"]), []).append(bar)
    return [sorted(g, key=lambda b: statistics.seed_order(b["run"])) for g in groups.values()]


def group_values(group, key):
    """(median value, lo, hi, median floor value, median multiple, its lo, its hi, n) of summary `key` over a
    configuration's bars (None where no bar has it; lo, hi None below 2 values)."""
    value, lo, hi, n = statistics.summarise(b["values"][key][0] for b in group)
    floor_value = statistics.median([b["values"][key][1] for b in group if b["values"][key][1] is not None])
    multiple, m_lo, m_hi, _ = statistics.summarise(b["values"][key][2] for b in group)
    return value, lo, hi, floor_value, multiple, m_lo, m_hi, n


def group_note(group, key):
    """bar_note for one run; for repeats 'median of 5: 1.71e-04 [1.2e-04, 2.3e-04]\n357x floor [...]'."""
    if len(group) == 1:
        return bar_note(group[0], key)
    value, lo, hi, floor_value, multiple, m_lo, m_hi, n = group_values(group, key)
    if value is None:
        return "n/a"
    text = f"median of {n}: {value:.3g}" + (f"\n[{lo:.3g}, {hi:.3g}]" if lo is not None else "")
    if multiple is not None:
        return text + f"\n{multiple:.3g}x floor" + (f" [{m_lo:.3g}, {m_hi:.3g}]" if m_lo is not None else "")
    return text + f"\n{NO_FLOOR if floor_value is None else 'no multiple (floor 0)'}"


def tick(bar, row, group=None):
    r = bar["run"]
    text = broken(tick_label(r, with_scene=False))
    if group is not None and len(group) > 1:
        text += f"\n(n={len(group)} seeds)"
    elif len({b["run"].seed for b in row}) > 1:
        text += f"\nseed {r.seed}"
    overrides = {pairing.floor_setup(b["run"])[-1] for b in row}  # the last: the scene overrides
    if len(overrides) > 1:
        text += "\n" + "\n".join(pairing.floor_setup(r)[-1])
    return text


def draw_panel(ax, row, key, colours):
    """Bars of summary `key`, log scale, the floor across each bar. Returns (values drawn, whether a floor was
    drawn)."""
    values, floors = [], {b["floor"].name for b in row if b["floor"] is not None}
    groups = bar_groups(row)
    for x, group in enumerate(groups):
        value, lo, hi, floor_value, *_ = group_values(group, key)
        ok = all(b["run"].status == "ok" for b in group)
        if value is not None and value > 0:
            ax.bar(x, value, width=0.6, color=colours[group[0]["run"].method_label],
                   hatch=None if ok else "xx", edgecolor="none" if ok else "red")
            values.append(value)
            if lo is not None and lo > 0:  # repeats: the median's bootstrap 95 % interval
                ax.errorbar(x, value, yerr=[[value - lo], [hi - value]], color="0.2", lw=0.8, capsize=2)
                values.extend([lo, hi])
        if floor_value is not None and floor_value > 0:
            if len(floors) > 1:  # several floors (seeds, overrides): each bar's own (repeats: their median)
                ax.hlines(floor_value, x - 0.4, x + 0.4, colors="k", linestyles="--", linewidth=1.2)
            values.append(floor_value)
        top = max([v for v in (value, floor_value, hi) if v is not None and v > 0] or [min(values, default=1.0)])
        ax.text(x, top * 1.15, group_note(group, key), ha="center", va="bottom", fontsize=6)
    if len(floors) == 1:
        floor_value = next(b["values"][key][1] for b in row if b["floor"] is not None)
        if floor_value is not None and floor_value > 0:
            ax.axhline(floor_value, color="k", ls="--", lw=1.2)
            ax.annotate(f"floor {floor_value:.3g}", (0, floor_value), xycoords=("axes fraction", "data"),
                        xytext=(3, 2), textcoords="offset points", fontsize=6)
    ax.set_yscale("log")
    if values:
        ax.set_ylim(min(values) / 4, max(values) * 10)
    ax.set_xticks(range(len(groups)), [tick(g[0], row, g) for g in groups], fontsize=6)
    ax.set_xlim(-0.6, max(len(groups), 2) - 0.4)
    ax.tick_params(axis="y", labelsize=7)
    return bool(floors)


def perturbations(runs):
    """The perturbations of the noise-floor runs among runs, "perturb.position=1e-09", or "none"."""
    found = sorted({o for r in runs if pairing.is_noise_floor(r) for o in r.overrides
                    if pairing.perturbation_override(o)})
    return ", ".join(found) or "none here"


def layout(rows):
    """[(scene, [((scene, response), [bar])])]: the rows of bars by scene, one column per contact response."""
    out = {}
    for key, row in rows:
        out.setdefault(key[0], []).append((key, row))
    return list(out.items())


def draw(ctx, runs):
    rows = bars(runs, ctx.runs)
    if not rows:
        return ctx.missing(TITLE, "no run has summary.divergence (runs without --reference; a sweep's "
                                  "divergence key adds it)")
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    drawn = {b["run"].method_label for _, row in rows for b in row}
    colours = method_colours(runs)  # over all runs in scope: a method's colour is the force error figure's too
    scenes = layout(rows)
    cols = max(len(columns) for _, columns in scenes)
    widths = [max(4.0, 0.8 * max(len(bar_groups(columns[k][1])) for _, columns in scenes if k < len(columns)) + 1.2)
              for k in range(cols)]
    fig, axes = plt.subplots(len(STATS) * len(scenes), cols,
                             figsize=(sum(widths) + 2.2, 3.2 * len(STATS) * len(scenes)), squeeze=False,
                             gridspec_kw={"width_ratios": widths})
    used, any_floor = [], False
    for number, (scene, columns) in enumerate(scenes):
        block = axes[len(STATS) * number:len(STATS) * (number + 1)]
        for k in range(cols):
            if k >= len(columns):
                for ax in block[:, k]:
                    ax.set_visible(False)
                continue
            (_, mode), row = columns[k]
            members = [b["run"] for b in row]
            floors = [b["floor"] for b in row if b["floor"] is not None]
            for ax, (key, label) in zip(block[:, k], STATS):
                any_floor |= draw_panel(ax, row, key, colours)
                if k == 0:
                    ax.set_ylabel(label, fontsize=8)
            block[0, k].set_title(f"{scene}, {response_title(mode, members)}" + ("" if floors else f": {NO_FLOOR}"),
                                  fontsize=9)
            used += members + floors
    handles = [Patch(color=c, label=label) for label, c in colours.items() if label in drawn]
    if any_floor:
        handles.append(Line2D([], [], color="k", ls="--", lw=1.2, label="noise floor: full against full\n"
                                                                          "perturbed (same statistic)"))
    axes[0, cols - 1].legend(handles=handles, fontsize=6.5, loc="upper left", bbox_to_anchor=(1.02, 1.0),
                             borderaxespad=0)
    return ctx.save(fig, FILE, TITLE,
                    "Each run's state against the sweep's full run (method full, no budget, same scene, seed and "
                    "overrides) at the same step (summary.divergence): top, the RMS over vertices of their "
                    "distance at the last compared step (rms_m.final); middle, the largest difference of a body's "
                    "linear momentum over compared steps (linear_momentum_diff_n_s.max); bottom, the angle of a "
                    "body's best-fit rotation at the last compared step (orientation_drift_deg.final), the largest "
                    "over bodies. One column per contact response, three rows per scene. Log scales; "
                    "the dashed line is the noise floor, the same statistic of full against itself under a tiny "
                    f"perturbation of the initial state ({perturbations(used)}: the noise-floor run of the same "
                    "scene, seed, response and "
                    "other overrides), and each bar is labelled with its multiple of that floor: chaotic scenes "
                    "diverge from any perturbation, so only a multiple of the floor means something. "
                    f"\"{NO_FLOOR}\": the sweep made none (noise_floor = 0). Full itself is the reference (0) "
                    "and not drawn.",
                    used, "each bar is their median with its bootstrap 95 % interval, each run measured against "
                          "its own seed's full run and floor, the dashed mark the median of those floors and the "
                          "label the median multiple of them")
