"""The paper's claims, as a table of records, each judged from run summaries.

A claim judges the runs its figure draws (all runs for a generic figure, the
runs of the sweeps declaring it otherwise), narrowed to a method, its settings
and budget kinds. Every number a rule uses is a run.json summary value (or the
run's status), never recomputed from steps.csv, so `tcbench check` can gate
the same numbers. Where the paper is qualitative, a rule uses a threshold of
ours; the record names it in `ours` and the report flags it.
"""
from dataclasses import dataclass, field

from . import figures, pairing
from .paper import (EVERY_NTH_N, JITTER_FACTOR, LATENCY_STEPS, OVERSHOOT_PCT, SPEEDUP, SPEEDUP_MIN,
                    STANDING_FRACTION)

HOLDS, FAILS, UNMEASURED = "holds", "does not hold", "not measured"


@dataclass(frozen=True)
class Select:
    """Which of a figure's runs a claim is about."""
    methods: tuple = ()                           # registry names; () for any
    settings: dict = field(default_factory=dict)  # must match these of the run's settings
    budget_kinds: tuple = ()                      # "none", "wall_ms", "work"; () for any
    measured: tuple = ()                          # summary keys that must not be null: what the claim is about

    def __call__(self, runs):
        return [r for r in runs
                if (not self.methods or r.method in self.methods)
                and all(r.metric(key) is not None for key in self.measured)
                and all(r.settings.get(k) == v for k, v in self.settings.items())
                and (not self.budget_kinds or r.budget_kind in self.budget_kinds)]


@dataclass(frozen=True)
class Claim:
    id: str
    text: str
    paper: str       # the paper's value, as it states it
    figure: str      # the figure whose runs it judges
    select: Select
    metrics: tuple   # the summary keys its rule reads
    rule: object     # rule(runs, ctx) -> (what we measured, verdict)
    ours: tuple = ()  # thresholds of ours (not the paper's) the rule applies


@dataclass
class Outcome:
    claim: Claim
    measured: str
    verdict: str
    runs: list


# ---------------------------------------------------------------- rules

def plural(count, noun):
    return f"{count} {noun}{'' if count == 1 else 's'}"


def share(good, total):
    """The verdict of a claim judged run by run."""
    return HOLDS if good == total else FAILS if good == 0 else f"partly: {good} of {plural(total, 'run')}"


def worst_overshoot(runs, ctx):
    if not runs:
        return UNMEASURED, UNMEASURED
    worst = max(runs, key=lambda r: r.metric("overshoot_pct.p99"))
    p99 = worst.metric("overshoot_pct.p99")
    return (f"overshoot p99 up to {p99:.1f} % ({worst.name}; {plural(len(runs), 'run')})",
            HOLDS if p99 < OVERSHOOT_PCT else FAILS)


def best_speedup(runs, ctx):
    rows = pairing.budgeted_with_reference(runs, ctx.runs)
    if not rows:
        return UNMEASURED, UNMEASURED
    best = max(rows, key=lambda row: row[2])
    low = min(rows, key=lambda row: row[2])
    measured = f"up to {best[2]:.2f}x median ({best[0].name})"
    if len(rows) > 1:
        measured += f", down to {low[2]:.2f}x ({low[0].name}), {plural(len(rows), 'run')}"
    verdict = HOLDS if best[2] >= SPEEDUP_MIN else FAILS
    return measured, f"{verdict} (the budget sets it; what it costs is in the speed-up figure)"


def jitter_ratio(run, ctx):
    """The run's summary jitter over its reference's, or None when either is missing."""
    ref = ctx.reference(run)
    mine, theirs = run.metric("jitter"), ref.metric("jitter") if ref else None
    return mine / theirs if mine is not None and theirs else None


def rests_plausibly(runs, ctx):
    """Stable, still standing, nothing passed through, jitter within JITTER_FACTOR of the reference's."""
    if not runs:
        return UNMEASURED, UNMEASURED
    notes, good = [], 0
    for r in runs:
        h0, h1 = r.metric("top_centre_height_m.initial"), r.metric("top_centre_height_m.final")
        standing = h0 is not None and h1 is not None and h1 >= STANDING_FRACTION * h0
        tunnelling, jitter, ratio = r.metric("tunneling"), r.metric("jitter"), jitter_ratio(r, ctx)
        ok = r.status == "ok" and tunnelling == 0 and standing and ratio is not None and ratio <= JITTER_FACTOR
        good += ok
        height = f"top centre {h0:.3f} -> {h1:.3f} m" if h0 is not None and h1 is not None else "height not measured"
        jit = "jitter not measured" if jitter is None else f"jitter {jitter:.3g} m/s" + (
            f" = {ratio:.1f}x the reference's" if ratio is not None else " (no reference to compare)")
        notes.append(f"{r.name}: status {r.status}, {height}, tunnelling {tunnelling}, {jit}")
    return "; ".join(notes), share(good, len(runs))


def jitters(runs, ctx):
    """The naive alternative's jitter exceeds JITTER_FACTOR times the reference's."""
    rows = [(r, jitter_ratio(r, ctx)) for r in runs]
    rows = [(r, x) for r, x in rows if x is not None]
    if not rows:
        return UNMEASURED, UNMEASURED
    loud = [r for r, x in rows if x > JITTER_FACTOR]
    measured = "; ".join(f"{r.name}: jitter {x:.1f}x the reference's" for r, x in rows)
    return measured, share(len(loud), len(rows))


def latency_bound(runs, ctx):
    """Runs with latency <= LATENCY_STEPS never tunnel; some with more do."""
    if not runs:
        return UNMEASURED, UNMEASURED
    low = [r for r in runs if r.metric("latency_steps.max") <= LATENCY_STEPS]
    high = [r for r in runs if r.metric("latency_steps.max") > LATENCY_STEPS]
    low_tunnel = [r for r in low if r.metric("tunneling")]
    high_tunnel = [r for r in high if r.metric("tunneling")]
    measured = (f"latency <= {LATENCY_STEPS}: {len(low_tunnel)} of {plural(len(low), 'run')} tunnel; "
                f"latency > {LATENCY_STEPS}: {len(high_tunnel)} of {plural(len(high), 'run')} tunnel")
    safe = [r.metric("latency_steps.max") for r in runs if not r.metric("tunneling")]
    if high_tunnel:
        measured += (f"; no pass-through up to {max(safe, default=0):.0f} steps, pass-through from "
                     f"{min(r.metric('latency_steps.max') for r in high_tunnel):.0f} steps")
    if low_tunnel:
        verdict = FAILS
    elif low and high_tunnel:
        verdict = HOLDS if max(safe, default=0) <= LATENCY_STEPS else "partly: the objects resist longer latencies here"
    elif high:
        verdict = f"partly: no run above {LATENCY_STEPS} steps tunnelled here"
    else:
        verdict = f"partly: not measured above {LATENCY_STEPS} steps"
    return measured, verdict


# ---------------------------------------------------------------- the table

CLAIMS = [
    Claim(id="granularity",
          text="Time constraints are met with a granularity below 5 % of the budget",
          paper=f"< {OVERSHOOT_PCT:g} %",
          figure="overshoot", select=Select(methods=("interruptible",), budget_kinds=("wall_ms",),
                                          measured=("overshoot_pct.p99",)),
          metrics=("overshoot_pct.p99",), rule=worst_overshoot),
    Claim(id="speedup",
          text="Interruptible handling saves up to two thirds of the collision handling time",
          paper=f"up to {SPEEDUP:g}x (120 -> 40 ms)",
          figure="speedup", select=Select(methods=("interruptible",), budget_kinds=("wall_ms",),
                                        measured=("handling_ms.p50",)),
          metrics=("handling_ms.p50",), rule=best_speedup,
          ours=(f"SPEEDUP_MIN = {SPEEDUP_MIN:g}: counts as reproduced from {SPEEDUP_MIN:g}x",)),
    Claim(id="stack_rests",
          text="A stack rests plausibly under the budget (stable, still standing, no pass-through, "
               f"jitter within {JITTER_FACTOR:g}x of the reference's)",
          paper="plausible resting contact",
          figure="jitter", select=Select(methods=("interruptible",), budget_kinds=("wall_ms", "work"),
                                       measured=("jitter",)),
          metrics=("top_centre_height_m.initial", "top_centre_height_m.final", "tunneling", "jitter"),
          rule=rests_plausibly,
          ours=(f"JITTER_FACTOR = {JITTER_FACTOR:g}: plausible jitter is at most that times the reference's",
                f"STANDING_FRACTION = {STANDING_FRACTION:g}: standing while the top keeps that share of its height")),
    Claim(id="every_2nd_jitters",
          text=f"Handling collisions only every n-th step (n = {EVERY_NTH_N}) makes resting contact jitter",
          paper="resting contact jitters",
          figure="jitter", select=Select(methods=("every_nth",), settings={"n": EVERY_NTH_N}, measured=("jitter",)),
          metrics=("jitter",), rule=jitters,
          ours=(f"JITTER_FACTOR = {JITTER_FACTOR:g}: jitter is more than that times the reference's",)),
    Claim(id="latency",
          text=f"A fast heavy object: latency up to {LATENCY_STEPS} steps keeps it from passing through; "
               "more lets it pass",
          paper=f"<= {LATENCY_STEPS} steps holds",
          figure="latency", select=Select(measured=("latency_steps.max",)),
          metrics=("latency_steps.max", "tunneling"), rule=latency_bound),
]


def judge(ctx):
    """[Outcome] for every claim, judged on the runs its figure draws."""
    modules = dict(figures.discover())
    outcomes = []
    for claim in CLAIMS:
        module = modules.get(claim.figure)
        scope = figures.runs_in_scope(claim.figure, module, ctx.runs) if module else []
        runs = claim.select(scope)
        measured, verdict = claim.rule(runs, ctx)
        outcomes.append(Outcome(claim, measured, verdict, runs))
    return outcomes
