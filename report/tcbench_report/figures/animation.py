"""Side-view animation of recorded runs, the reference beside a budgeted run.

Drawn from the sweeps that declare "animation" and recorded frames (--record);
one GIF per scene, named after the scene. A trajectory has no median: where the
runs shown have repeats (other seeds), the caption says which seed is shown and
of how many.
"""
import os
import re

from ..context import Section, plt
from .. import pairing, statistics
from ._common import by_scene

TITLE = "Animation"
ORDER = 9
SCOPE = "declared"
PANELS = 2  # the reference and one budgeted run: a third doubles the GIF for little
FPS = 10


def read_pvd(run_dir):
    """[(time, [[x, y], ...])] from frames.pvd and its ASCII VTU files (side view: x, y)."""
    with open(os.path.join(run_dir, "frames.pvd")) as f:
        entries = re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', f.read())
    frames = []
    for t, name in entries:
        with open(os.path.join(run_dir, name)) as f:
            text = f.read()
        pts = []
        for block in re.findall(r"<Points>\s*<DataArray[^>]*>(.*?)</DataArray>", text, re.S):
            vals = block.split()
            pts += [[float(vals[i]), float(vals[i + 1])] for i in range(0, len(vals) - 2, 3)]
        frames.append((float(t), pts))
    return frames


def pick(runs):
    """The reference first, then a budgeted run of the same setup (else any budgeted run)."""
    refs = [r for r in runs if pairing.is_reference(r)]
    others = sorted((r for r in runs if r.budget_kind != "none"),
                    key=lambda r: (bool(refs) and pairing.setup(r) != pairing.setup(refs[0]), r.method_label, r.name))
    return (refs[:1] + others)[:PANELS]


def bounds(frames):
    xs = [p[0] for fr in frames for _, pts in fr for p in pts]
    ys = [p[1] for fr in frames for _, pts in fr for p in pts]
    pad = 0.05 * max(max(xs) - min(xs), max(ys) - min(ys), 1e-6)
    return (min(xs) - pad, max(xs) + pad), (min(ys) - pad, max(ys) + pad)


def seeds_note(chosen, runs):
    """' Each is one run of its configuration: interruptible @ full/3 seed 0 of 5, ...' for the chosen runs that
    have repeats among runs (with the jitter their seeds drew); '' when none has."""
    parts = []
    for r in chosen:
        n = sum(1 for m in runs if statistics.configuration(m) == statistics.configuration(r))
        if n > 1:
            parts.append(f"{r.label()} seed {r.seed} of {n} seeds")
    if not parts:
        return ""
    jitters = sorted({statistics.jitter_text(r) for r in chosen} - {""})
    return (" One run of each configuration is shown, not a median: " + ", ".join(parts) + "."
            + (f" Initial-state jitter drawn per seed: {'; '.join(jitters)}." if jitters else ""))


def animate(ctx, scene, runs, note=""):
    from matplotlib.animation import FuncAnimation, PillowWriter

    frames = [read_pvd(r.dir) for r in runs]
    count = min(len(f) for f in frames)
    if count == 0 or not any(pts for fr in frames for _, pts in fr):
        return ctx.missing(f"{TITLE}: {scene}", "the recorded frames hold no points")
    xlim, ylim = bounds(frames)
    fig, axes = plt.subplots(1, len(runs), figsize=(4 * len(runs), 4), squeeze=False)
    dots = []
    for ax, r in zip(axes[0], runs):
        ax.set(xlim=xlim, ylim=ylim, aspect="equal", title=r.label(), xlabel="x (m)")
        dots.append(ax.scatter([], [], s=1))
    axes[0][0].set_ylabel("y (m)")
    title = f"{TITLE}: {scene}"
    fig.suptitle(scene)  # reserve its room before the layout; show() updates the time
    ctx.sign(fig, title, runs)

    def show(k):
        for d, fr in zip(dots, frames):
            d.set_offsets(fr[k][1] or [[float("nan"), float("nan")]])
        fig.suptitle(f"{scene}, t = {frames[0][k][0]:.2f} s")
        return dots

    name = f"{scene}.gif"
    animation = FuncAnimation(fig, show, frames=count, blit=False)
    ctx.write_figure(name, lambda path: animation.save(path, writer=PillowWriter(fps=FPS)))
    plt.close(fig)
    return Section(title, f"Side view of {', '.join(r.label() for r in runs)}.{note}", list(runs),
                   image=f"figures/{name}")


def draw(ctx, runs):
    recorded = by_scene(r for r in runs if r.has_frames())
    if not recorded:
        return ctx.missing(TITLE, "no run of the sweeps declaring this figure recorded frames (--record)")
    sections = []
    for scene, rs in recorded.items():
        chosen = pick(rs)
        if len(chosen) < 2:
            sections.append(ctx.missing(f"{TITLE}: {scene}", "needs a recorded reference run and a recorded "
                                                            "budgeted run"))
        else:
            sections.append(animate(ctx, scene, chosen, seeds_note(chosen, rs)))
    return sections
