"""The neural self-collision detector (seed 002): accuracy and false-negative rate on held-out codes against
the labels spent, active against supervised learning (mean over seeds, min-max band), and the ALM's resolution
by margin (bars, with the distance moved over the reference distance). Drawn from `tcbench neural experiment` results anywhere beneath the report's root; runs play no part.
"""
import math
import os

from .. import neural, statistics
from ..context import Section, plt

TITLE = "Neural self-collision detector: active vs supervised learning"
ORDER = 9
SCOPE = "all"
FILE = "fig_neural_learning"
COLOURS = {"active": "tab:red", "supervised": "tab:blue"}


def curve(rows, key):
    """(labels, mean, min, max) over seeds, by labels spent."""
    by_labels = {}
    for r in rows:
        if not math.isnan(r[key]):
            by_labels.setdefault(r["labels"], []).append(r[key])
    xs = sorted(by_labels)
    return (xs, [sum(by_labels[x]) / len(by_labels[x]) for x in xs], [min(by_labels[x]) for x in xs],
            [max(by_labels[x]) for x in xs])


def alm_text(results):
    rows = sorted(results.alm, key=lambda r: (r["preset"], r["strategy"], r["margin"], r["seed"]))
    groups = {}
    for r in rows:
        groups.setdefault((r["preset"], r["strategy"], r["margin"]), []).append(r)
    parts = []
    for (preset, strategy, margin), rs in groups.items():
        resolved = sum(r["resolved"] for r in rs)
        attempted = sum(r["attempted"] for r in rs)
        ratio = neural.mean([r["median_distance_ratio"] for r in rs])
        parts.append(f"{preset} {strategy} margin {margin:g}: {int(resolved)}/{int(attempted)} resolved, "
                     f"distance {ratio:.2f}x the reference")
    return "; ".join(parts)


def draw_alm(ax, rows, preset):
    """The ALM table as bars: per margin and strategy, the share of colliding codes resolved (pooled over seeds;
    bars: 95 % Wilson interval over the distinct codes) and, on each bar, the median distance moved over the
    oracle's reference distance."""
    if not rows:
        ax.set_axis_off()
        ax.text(0.5, 0.5, "no ALM rows", ha="center", va="center", fontsize=8)
        return
    margins = sorted({r["margin"] for r in rows})
    width = 0.38
    for k, strategy in enumerate(("supervised", "active")):
        for i, margin in enumerate(margins):
            rs = [r for r in rows if r["strategy"] == strategy and r["margin"] == margin]
            if not rs:
                continue
            resolved, attempted = sum(r["resolved"] for r in rs), sum(r["attempted"] for r in rs)
            codes = max(1, round(attempted / len(rs)))
            share = resolved / max(1, attempted)
            lo, hi = statistics.wilson_interval(round(codes * share), codes)
            x = i + (k - 0.5) * width
            ax.bar(x, share, width, color=COLOURS[strategy], alpha=0.8, label=strategy if i == 0 else None)
            ax.errorbar(x, share, yerr=[[max(0.0, share - lo)], [max(0.0, hi - share)]], color="0.2", lw=0.8, capsize=2)
            ratio = neural.mean([r["median_distance_ratio"] for r in rs])
            ax.text(x, min(share + 0.03, 0.97), f"{ratio:.2f}x", ha="center", va="bottom", fontsize=6)
    ax.set_xticks(range(len(margins)), [f"{m:g}" for m in margins])
    ax.set(ylim=(0, 1), xlabel="margin (logits)", ylabel="colliding codes resolved (oracle)")
    ax.set_title(f"{preset}: ALM resolution (label: distance / reference)", fontsize=9)
    ax.legend(fontsize=7)


def draw(ctx, runs):
    found = neural.find(ctx.results.root)
    if not found:
        return ctx.missing(TITLE, "no neural experiment results (neural.json and learning.csv; "
                                  "`tcbench neural experiment --out DIR`) beneath the report's folder")
    sections = []
    for number, results in enumerate(found):
        presets = neural.presets(results)
        fig, axes = plt.subplots(len(presets), 3, figsize=(14, 3.6 * len(presets)), squeeze=False)
        for row, preset in zip(axes, presets):
            draw_alm(row[2], [r for r in results.alm if r["preset"] == preset], preset)
            for ax, (key, name) in zip(row, (("accuracy", "accuracy"), ("fnr", "false-negative rate"))):
                for strategy in ("supervised", "active"):
                    rows = [r for r in results.learning if r["preset"] == preset and r["strategy"] == strategy]
                    if not rows:
                        continue
                    xs, mean, lo, hi = curve(rows, key)
                    seeds = len({r["seed"] for r in rows})
                    ax.plot(xs, mean, marker="o", ms=3, color=COLOURS[strategy], label=f"{strategy} ({seeds} seeds)")
                    ax.fill_between(xs, lo, hi, color=COLOURS[strategy], alpha=0.2, lw=0)
                ax.set_xlabel("labels (exact oracle calls)", fontsize=8)
                ax.set_ylabel(name, fontsize=8)
                ax.set_title(f"{preset}: {name} on held-out codes", fontsize=9)
                ax.legend(fontsize=7)
        meta = results.meta
        sizes = ", ".join(f"{p['preset']}: {p['vertices']} vertices, {p['tets']} tets, {p['test_codes']} test codes "
                          f"({p['test_colliding']} colliding), label {p['label_ms_per_code']:.2f} ms/code, detector "
                          f"{p['detector_eval_us_median']:.1f} us/evaluation against {p.get('full_step_ms_median', math.nan):.2f} ms "
                          f"for a step of the full method" for p in meta.get("presets", []))
        stem = FILE if number == 0 else f"{FILE}_{number}"
        title = f"{TITLE} ({os.path.relpath(results.directory, ctx.results.root)})"
        caption = (f"Accuracy and false-negative rate of the detector (colliding when its logit > 0) on held-out "
                   f"codes labelled by the exact oracle, against the labels spent; both strategies get the same "
                   f"labels and gradient steps and share each seed's bootstrap. Lines: mean over seeds; bands: "
                   f"min-max. {sizes}. ALM (margins in logits, resolved = the oracle finds no penetration at the "
                   f"ALM's code; distance: median over codes of the latent distance moved over the distance to "
                   f"a collision-free code found by bisection towards the rest pose): {alm_text(results) or 'not run'}.")
        fig.text(0.01, 0.005, f"{title}. build {meta.get('build', {}).get('git_sha', '?')[:10]}; machine "
                              f"{meta.get('machine', {}).get('cpu', '?')}.", fontsize=6, color="0.35")
        fig.tight_layout(rect=(0, 0.03, 1, 1))
        for ext in ("png", "svg"):
            ctx.write_figure(f"{stem}.{ext}", lambda path: fig.savefig(path, dpi=110))
        plt.close(fig)
        sections.append(Section(title, caption, [], image=f"figures/{stem}.png", vector=f"figures/{stem}.svg"))
    return sections
