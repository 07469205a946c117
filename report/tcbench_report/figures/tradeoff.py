"""The speed/accuracy trade: one row per scene, one curve per method across budgets."""
from ..context import plt
from .. import pairing
from ._common import by_scene

TITLE = "The speed/accuracy trade"
ORDER = 6
SCOPE = "all"
FILE = "fig6_tradeoff"
METRICS = (("depth_err.mean", "mean depth error (m)"), ("recall_min", "minimum recall"),
           ("max_depth", "deepest true penetration (m)"))


def curves(runs):
    """{legend: [runs]}: one curve per method label; per setup too when a scene has several
    (contact response, scene overrides, RNG seeds), so different experiments are never joined by a line.
    The legend names only what differs between the setups."""
    setups = [pairing.setup(r) for r in runs]
    varies = [len({s[k] for s in setups}) > 1 for k in range(4)]  # scene, seed, response, overrides
    out = {}
    for r, (_, seed, response, overrides) in zip(runs, setups):
        parts = ([f"{response} response"] if varies[2] else []) + (list(overrides) if varies[3] else []) \
            + ([f"rng={seed}"] if varies[1] else [])
        key = r.method_label + (" [" + " ".join(parts) + "]" if parts else "")
        out.setdefault(key, []).append(r)
    return dict(sorted(out.items()))


def draw(ctx, runs):
    scenes = {scene: [r for r in rs if r.metric("handling_ms.p50") is not None]
              for scene, rs in by_scene(runs).items()
              if any(r.metric("recall_min") is not None for r in rs)}
    scenes = {s: rs for s, rs in scenes.items() if rs}
    if not scenes:
        return ctx.missing(TITLE, "no run with the oracle (recall_min in its summary)")
    fig, axes = plt.subplots(len(scenes), len(METRICS), figsize=(14, 3.4 * len(scenes)), squeeze=False)
    sources = []
    for row, (scene, rs) in zip(axes, scenes.items()):
        lines = curves(rs)
        for ax, (key, name) in zip(row, METRICS):
            for legend, members in lines.items():
                pts = sorted((r.metric("handling_ms.p50"), r.metric(key)) for r in members
                             if r.metric(key) is not None)
                if pts:
                    ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", ms=3, label=legend)
            ax.set(xlabel="median handling (ms)", ylabel=name, title=scene)
        if row[-1].get_legend_handles_labels()[0]:  # one legend a scene, beside its last panel
            row[-1].legend(fontsize=6, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0)
        sources += rs
    return ctx.save(fig, FILE, TITLE, "Each point is one run; one curve per method across its budgets.", sources)
