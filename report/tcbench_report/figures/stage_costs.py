"""Where handling time goes: the mean time per step of each stage of the collision cycle, and of applying
forces outside it (summary.stages), stacked; with the stage the budget stopped the cycle in.

One panel per scene, one bar per method label, budget (and contact response or scene overrides where a scene
mixes them): the runs differing only in their RNG seed are averaged (the stages' means add up to the
total's mean, their medians would not), and beside such a bar the median of the runs' totals with its
bootstrap 95 % interval. A run without summary.stages (recorded before the stage meter) is left out.
"""
from ..context import plt
from .. import pairing, statistics
from ..loader import response_order
from ._common import by_scene, method_order, width_for, wrapped

TITLE = "Stage costs: where handling time goes"
ORDER = 3.5  # beside the speed-up
SCOPE = "all"
FILE = "fig3b_stage_costs"

# summary.stages in the order of the cycle (method/handler/stage_costs.hpp), apply last: time outside the cycle.
STAGES = ("prioritize", "hash_tets", "query_points", "hash_surface", "border_depth", "propagate", "forces", "apply")
COLOURS = dict(zip(STAGES, ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown",
                            "tab:pink", "tab:gray")))
UNACCOUNTED = "not in a stage (call, clock reads)"  # summary.stages_ms_unaccounted_mean


def stage_costs(run):
    """{stage: {ms_mean, ms_max, work_mean, interrupted_steps}} from summary.stages, or None when the run has
    none (older runs, or a run that took no step)."""
    stages = run.summary.get("stages")
    return stages if isinstance(stages, dict) and stages else None


def number(value):
    return value if isinstance(value, (int, float)) and not isinstance(value, bool) else None


def bar_key(run):
    """Runs sharing a bar: the same scene, method label, budget, contact response, mesh order, scene overrides
    and length; only the seed may differ."""
    _, _, response, mesh_order, overrides = pairing.setup(run)
    return run.scene, run.method_label, run.budget_label, response, mesh_order, overrides, run.record.get("steps")


def bars(runs):
    """{scene: [bar]} of the runs with summary.stages, scenes in order, bars by method then budget. A bar is a
    dict: label (method label, budget, and what else differs within the scene), runs, ms [mean ms per step of
    each stage, in STAGES order, averaged over the runs], interrupted [steps interrupted in each stage, per run,
    averaged], unaccounted (mean ms per step, averaged; None when no run has it), steps (per run)."""
    out = {}
    for scene, members in by_scene([r for r in runs if stage_costs(r)]).items():
        groups = {}
        for r in sorted(members, key=lambda r: (method_order(r), r.budget_order(), response_order(r.response),
                                                r.seed if r.seed is not None else -1, r.name)):
            groups.setdefault(bar_key(r), []).append(r)
        keys = list(groups)
        varies = [len({key[k] for key in keys}) > 1 for k in range(len(keys[0]))]
        scene_bars = []
        for key, group in groups.items():
            _, label, budget, response, mesh_order, overrides, steps = key
            parts = [wrapped(label), "no budget" if budget == "none" else budget]
            parts += [f"{response} response"] if varies[3] else []
            parts += [f"mesh_order={mesh_order}"] if varies[4] else []
            parts += list(overrides) if varies[5] else []
            parts += [f"{steps} steps"] if varies[6] else []
            if len(group) > 1:
                parts.append(f"mean of {len(group)} seeds")
            costs = [stage_costs(r) for r in group]
            unaccounted = [number(r.summary.get("stages_ms_unaccounted_mean")) for r in group]
            unaccounted = [u for u in unaccounted if u is not None]
            scene_bars.append({
                "label": "\n".join(parts), "runs": group,
                "ms": [mean(number((c.get(s) or {}).get("ms_mean")) for c in costs) for s in STAGES],
                "interrupted": [mean(number((c.get(s) or {}).get("interrupted_steps")) for c in costs)
                                for s in STAGES],
                "unaccounted": mean(unaccounted) if unaccounted else None,
                "steps": mean(number(r.record.get("steps")) for r in group),
                "total": statistics.summarise([total(r) for r in group]),
            })
        out[scene] = scene_bars
    return out


def total(run):
    """The run's handling time per step its stages account for: the stages' ms_mean and the unaccounted
    rest, summed (what its stacked bar reaches); None without stages."""
    costs = stage_costs(run)
    if not costs:
        return None
    parts = [number((costs.get(s) or {}).get("ms_mean")) for s in STAGES]
    parts.append(number(run.summary.get("stages_ms_unaccounted_mean")))
    return sum(p for p in parts if p is not None)


def mean(values):
    """The mean of the numbers among values; None (not reported) is left out, never counted as 0. 0.0 when
    no value is known (the bar then draws nothing for it)."""
    values = [v for v in values if v is not None]
    return sum(values) / len(values) if values else 0.0


def interruption_note(bar):
    """"interrupted 212 of 300 steps\nmostly propagate (180)", "never interrupted", or for a method without a
    collision cycle (method none: every stage 0) that it has none."""
    total = sum(bar["interrupted"])
    if not any(bar["ms"]):
        return "no time in any stage\n(no collision cycle)"
    if total <= 0:
        return "never interrupted"
    top = max(range(len(STAGES)), key=lambda k: bar["interrupted"][k])
    of = f" of {bar['steps']:.0f}" if bar["steps"] else ""
    return f"interrupted {total:.0f}{of} steps\nmostly {STAGES[top]} ({bar['interrupted'][top]:.0f})"


def draw(ctx, runs):
    scenes = bars(runs)
    if not scenes:
        return ctx.missing(TITLE, "no run has summary.stages (runs recorded before the stage meter)")
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    most = max(len(b) for b in scenes.values())
    fig, axes = plt.subplots(len(scenes), 1, figsize=(width_for(most, 1.7, minimum=7.5), 4.6 * len(scenes)),
                             squeeze=False)
    sources, marked, hatched, diamond = [], False, False, False
    for ax, (scene, scene_bars) in zip(axes[:, 0], scenes.items()):
        tops = []
        for x, bar in enumerate(scene_bars):
            bottom = 0.0
            for stage, ms, interrupted in zip(STAGES, bar["ms"], bar["interrupted"]):
                if ms > 0:
                    ax.bar(x, ms, bottom=bottom, width=0.6, color=COLOURS[stage], linewidth=0)
                if interrupted > 0:  # the stages the budget stopped the cycle in: a mark beside their segment
                    ax.plot(x + 0.36, bottom + ms / 2, marker="<", color="k",
                            ms=3 + 5 * interrupted / max(sum(bar["interrupted"]), 1), ls="none")
                    marked = True
                bottom += ms
            if bar["unaccounted"] is not None and bar["unaccounted"] > 0:
                ax.bar(x, bar["unaccounted"], bottom=bottom, width=0.6, color="white", edgecolor="0.5",
                       hatch="....", linewidth=0.5)
                hatched = True
                bottom += bar["unaccounted"]
            text = f"{bottom:.3g} ms"
            median, lo, hi, n = bar["total"]
            if n > 1:  # repeats: the median of their totals, its bootstrap 95 % interval, left of the bar
                text = f"mean {bottom:.3g} ms\n{statistics.estimate_text(median, lo, hi, n)} ms"
                ax.plot(x - 0.38, median, marker="D", color="k", ms=3, ls="none")
                if lo is not None:
                    ax.errorbar(x - 0.38, median, yerr=[[median - lo], [hi - median]], color="k", lw=0.7, capsize=1.5)
                    bottom = max(bottom, hi)
                diamond = True
            tops.append(bottom)
            ax.text(x, bottom, f"{text}\n{interruption_note(bar)}", ha="center", va="bottom", fontsize=6)
            sources += bar["runs"]
        ax.set_xticks(range(len(scene_bars)), [b["label"] for b in scene_bars], fontsize=6.5)
        ax.set_xlim(-0.6, max(len(scene_bars), 2) - 0.4)
        ax.set_ylim(0, max(tops + [1e-9]) * 1.35)  # room for the notes above the bars
        ax.set_ylabel("handling time, mean ms per step", fontsize=8)
        ax.set_title(scene, fontsize=9)
        ax.tick_params(axis="y", labelsize=7)
    handles = [Patch(color=COLOURS[s], label=s + (" (outside the cycle)" if s == "apply" else "")) for s in STAGES]
    if hatched:
        handles.append(Patch(facecolor="white", edgecolor="0.5", hatch="....", label=UNACCOUNTED))
    if marked:
        handles.append(Line2D([], [], color="k", marker="<", ls="none", ms=5,
                              label="cycle interrupted in this stage\n(larger: more of the steps)"))
    if diamond:
        handles.append(Line2D([], [], color="k", marker="D", ms=3, lw=0.7,
                              label="median of the seeds' totals,\nbootstrap 95 % interval"))
    axes[0, 0].legend(handles=handles, fontsize=6.5, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
    return ctx.save(fig, FILE, TITLE,
                    "Collision handling time per step split by stage (summary.stages.*.ms_mean: the mean ms per "
                    "step, every step counted, steps a stage did not run in as 0), stacked in the cycle's order "
                    "from prioritize to forces, then apply (applying forces, extrapolating and bookkeeping outside "
                    "the cycle); dotted on top, the handling time no stage covers (stages_ms_unaccounted_mean). The "
                    "total is written above each bar. One bar per method and budget in each scene, averaged over "
                    "the runs that differ only in their seed; runs recorded before the stage meter are left out. "
                    "Marks beside a bar and its note give the steps in which the budget stopped the cycle, per "
                    "run (summary.stages.*.interrupted_steps), and the stage that happened in most.",
                    sources, "each bar stacks the stages' means over the seeds (means add up to the total's mean), "
                             "and the diamond left of it is the median of the seeds' totals with its bootstrap 95 % "
                             "interval")
