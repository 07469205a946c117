"""The force a haptic device would render: |probe force| over time, per run.

Drawn from the sweeps that declare "haptic". The legend's numbers are each
run's summary.probe_force_change_rms (so `tcbench check` can gate the same
number); the curves are the steps.csv time series.
"""
import math

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
    for r in runs:
        change = r.metric("probe_force_change_rms")
        name = f"{r.scene}: {r.label()}" if several else r.label()
        ax.plot(r.steps()["time_s"], magnitude(r.steps()), lw=0.7, label=f"{name} (change {change:.3g} N/step)")
        notes.append(f"{name}: RMS force change per step {change:.3g} N")
    ax.set(xlabel="time (s)", ylabel="|probe force| (N)")
    ax.legend(fontsize=7)
    scenes = ", ".join(sorted({r.scene for r in runs}))
    return ctx.save(fig, FILE, f"{TITLE}: {scenes}",
                    "Force the device would render, per run; the change is the RMS of the step-to-step change of "
                    "|probe force| (summary.probe_force_change_rms). " + "; ".join(notes) + ".", runs)
