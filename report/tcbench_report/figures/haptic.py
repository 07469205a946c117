"""The force a haptic device would render: |probe force| over time, per run.

Drawn from the sweeps that declare "haptic". The legend's numbers are each
run's summary.probe_force_change_rms (so `tcbench check` can gate the same
number); the curves are the steps.csv time series. Repeats of a configuration
(runs differing only by seed) are drawn as thin curves in one colour, and their
change is given as the median with its bootstrap 95 % interval.
"""
import math

from .. import statistics
from ..context import plt

TITLE = "The haptic force signal"
ORDER = 7
SCOPE = "declared"
FILE = "fig7_haptic"
COLUMNS = ("probe_force_x", "probe_force_y", "probe_force_z")


def magnitude(steps):
    return [math.sqrt(sum((steps[c][i] or 0.0) ** 2 for c in COLUMNS)) for i in range(len(steps["time_s"]))]


def draw(ctx, runs):
    runs = sorted((r for r in runs if r.metric("probe_force_change_rms") is not None),
                  key=lambda r: (r.scene, r.budget_kind != "none", r.method_label, r.name))
    runs = [r for r in runs if all(c in r.steps() for c in COLUMNS + ("time_s",))]
    if not runs:
        return ctx.missing(TITLE, "no run of the sweeps declaring this figure has summary.probe_force_change_rms "
                                  "and probe force columns in steps.csv")
    several = len({r.scene for r in runs}) > 1
    fig, ax = plt.subplots(figsize=(10, 3.8))
    notes = []
    for k, group in enumerate(statistics.repeats(runs)):
        r = group[0]
        name = f"{r.scene}: {r.label()}" if several else r.label()
        if len(group) == 1:  # one run: drawn as it always was
            change = r.metric("probe_force_change_rms")
            ax.plot(r.steps()["time_s"], magnitude(r.steps()), lw=0.7, color=f"C{k % 10}",
                    label=f"{name} (change {change:.3g} N/step)")
            notes.append(f"{name}: RMS force change per step {change:.3g} N")
            continue
        change = statistics.estimate_text(*statistics.summarise(m.metric("probe_force_change_rms") for m in group))
        for j, m in enumerate(group):
            ax.plot(m.steps()["time_s"], magnitude(m.steps()), lw=0.35, alpha=0.6, color=f"C{k % 10}",
                    label=f"{name}, {len(group)} seeds (change {change} N/step)" if j == 0 else None)
        notes.append(f"{name}: RMS force change per step {change} N over {len(group)} seeds")
    ax.set(xlabel="time (s)", ylabel="|probe force| (N)")
    ax.legend(fontsize=7)
    scenes = ", ".join(sorted({r.scene for r in runs}))
    return ctx.save(fig, FILE, f"{TITLE}: {scenes}",
                    "Force the device would render, per run; the change is the RMS of the step-to-step change of "
                    "|probe force| (summary.probe_force_change_rms). " + "; ".join(notes) + ".", runs,
                    "each seed's curve is drawn thin in its configuration's colour, and the change is their median "
                    "with its bootstrap 95 % interval")
