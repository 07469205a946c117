"""The paper's claims, as a table of records, each judged from run summaries.

A claim judges the runs its figure draws (all runs for a generic figure, the
runs of the sweeps declaring it otherwise), narrowed to a method, its settings
and budget kinds. Every number a rule uses is a run.json summary value (or the
run's status), never recomputed from steps.csv, so `tcbench check` can gate
the same numbers. Where the paper is qualitative, a rule uses a threshold of
ours; the record names it in `ours` and the report flags it. A record's `per`
judges its runs in parts, one table row each: per contact response (implicit or
explicit penalty contact), so the reader sees which verdicts are the
integrator's, and per method variant. A record's `evidence` appends what other figures' runs show (force
error, divergence over its noise floor) to the measured text, split alike and from the scenes of the runs the
claim judges only, and never changes the verdict. `every_2nd_inferior` is judged on force error and divergence
themselves (every_nth n = 2 against interruptible at the same work), the jitter shown beside them.
"""
import math
from dataclasses import dataclass, field

from . import figures, neural, pairing, statistics
from .loader import relative_divisor, response_order
from .paper import (EVERY_NTH_N, FLOOR_FACTOR, JITTER_FACTOR, LATENCY_STEPS, OVERSHOOT_PCT, SPEEDUP, SPEEDUP_MIN,
                    STANDING_FRACTION)

HOLDS, FAILS, UNMEASURED = "holds", "does not hold", "not measured"
# The paper's schedule: runs with our settings fine_tasks, reserve_apply, apply_first, widen_stale, rehash_stale or predict_tasks
# are not the paper's method
# (they are drawn beside it in the figures, never judged as it). A run recorded before the settings existed
# had the paper's granularity.
PAPER_TASKS = {"fine_tasks": False, "reserve_apply": False, "apply_first": False, "widen_stale": False,
               "rehash_stale": False, "predict_tasks": False}


@dataclass(frozen=True)
class Select:
    """Which of a figure's runs a claim is about."""
    methods: tuple = ()                           # registry names; () for any
    settings: dict = field(default_factory=dict)  # must match these of the run's settings (absent: the default)
    budget_kinds: tuple = ()                      # "none", "wall_ms", "work"; () for any
    measured: tuple = ()                          # summary keys that must not be null: what the claim is about

    def __call__(self, runs):
        return [r for r in runs
                if (not self.methods or r.method in self.methods)
                and all(r.metric(key) is not None for key in self.measured)
                and all(r.settings.get(k, v) == v for k, v in self.settings.items())
                and (not self.budget_kinds or r.budget_kind in self.budget_kinds)]


@dataclass(frozen=True)
class Evidence:
    """Further evidence a claim shows beside its verdict, from another figure's runs: text only, it never
    changes the verdict (a secondary verdict it finds is stated in the text)."""
    figure: str      # the figure whose runs it reads
    select: Select
    rule: object     # rule(runs, ctx) -> text


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
    # Judged separately for each value of these: "response" (implicit or explicit penalty
    # contact: which verdicts are the integrator's), "method" (each method variant selected).
    per: tuple = ()
    evidence: tuple = ()  # Evidence shown after what the rule measured, split by `per` alike


@dataclass
class Outcome:
    claim: Claim
    measured: str
    verdict: str
    runs: list
    part: str = ""  # which part of the runs this row judges ("interruptible, implicit response"); "" for all

    @property
    def text(self):
        return f"{self.claim.text} — {self.part}" if self.part else self.claim.text


# ---------------------------------------------------------------- rules

def plural(count, noun):
    return f"{count} {noun}{'' if count == 1 else 's'}"


def share(good, total):
    """The verdict of a claim judged run by run."""
    if good == total or good == 0:
        verdict = HOLDS if good == total else FAILS
        return verdict + (f" ({statistics.rate_text(good, total)} runs)" if total > 1 else "")
    return f"partly: {statistics.rate_text(good, total)} runs"


def setting(run):
    """statistics.configuration without the scene: what tells runs of one budget apart besides their seed
    (the evidence reads several scenes' runs and names the scene per run)."""
    return statistics.configuration(run)[1:]


def by_budget(runs):
    """[(label, [runs])] from the largest budget to the smallest (full-work/2 before full-work/10), and within
    a budget one group per configuration (its repeats, by seed: a jittered sweep's seeds are not pooled with
    another sweep's unjittered run). The label is the budget, and where several configurations share it,
    what sets them apart (the jitter their seeds drew, else their overrides, else their length)."""
    groups = {}
    for r in sorted(runs, key=lambda r: (r.budget_order(), r.seed if r.seed is not None else -1, r.name)):
        groups.setdefault((r.budget_label, setting(r)), []).append(r)
    labels = {}
    for label, _ in groups:
        labels[label] = labels.get(label, 0) + 1
    out = []
    for (label, _), group in sorted(groups.items(), key=lambda item: (item[1][0].budget_order(),
                                                                       min(statistics.seed_order(r) for r in item[1]))):
        if labels[label] > 1:
            siblings = [g for (other, _), g in groups.items() if other == label]
            label = f"{label} ({apart(group[0], [g[0] for g in siblings])})"
        out.append((label, group))
    return out


def apart(run, others):
    """What sets run's configuration apart from the others of its budget, in words."""
    jitters = {statistics.jitter_text(o) for o in others}
    if len(jitters) > 1:
        jitter = statistics.jitter_text(run)
        return f"jittered: {jitter}" if jitter else "not jittered"
    overrides = {tuple(sorted(o.overrides)) for o in others}
    if len(overrides) > 1:
        return " ".join(sorted(run.overrides)) or "no overrides"
    steps = {o.record.get("steps") for o in others}
    if len(steps) > 1:
        return f"{run.record.get('steps')} steps"
    return run.method_label + (f", {run.response} response" if len({o.response for o in others}) > 1 else "")


def where(run, group, label=None):
    """How the evidence names a run within its budget's group: the budget (or the group's label from
    by_budget), and the seed when it repeats, with the jitter its seed drew (a jittered seed 0 is not the
    unperturbed seed 0 of another sweep)."""
    jitter = statistics.jitter_text(run)
    return (label or run.budget_label) + (f" (seed {run.seed}{', jittered: ' + jitter if jitter else ''})"
                                          if len(group) > 1 else "")


def per_budget_verdict(results):
    """results: [(budget label, good, total)] -> one verdict naming the budgets it holds at."""
    if not results:
        return UNMEASURED
    # With repeats, each budget's count carries its Wilson 95 % interval (statistics.py): 5 of 5 runs is
    # not a certainty, only a rate above 57 %.
    def rate(good, total):
        return f" ({statistics.rate_text(good, total)} runs)" if total > 1 else ""
    held = [label + rate(good, total) for label, good, total in results if good == total]
    failed = [label + rate(good, total) for label, good, total in results if not good]
    partial = [f"{label} in {statistics.rate_text(good, total)} runs" for label, good, total in results
               if 0 < good < total]
    if len(held) == len(results):
        return f"{HOLDS} at {'every budget' if len(results) > 1 else 'its budget'} ({', '.join(held)})"
    if len(failed) == len(results):
        return f"{FAILS} at {'any budget' if len(results) > 1 else 'its budget'} ({', '.join(failed)})"
    return "partly: " + "; ".join(part for part in (
        f"holds at {', '.join(held)}" if held else "",
        f"not at {', '.join(failed)}" if failed else "",
        f"holds at {', '.join(partial)}" if partial and not held else ", ".join(partial)) if part)


def num(value, unit="", digits=3):
    return "n/a" if value is None else f"{value:.{digits}g}{' ' + unit if unit else ''}"


def vs_reference(run, ref, key, unit):
    """"0.196 J (full 0.150 J)": a summary value beside its reference's."""
    mine = num(run.metric(key), unit)
    return mine if ref is None or ref.metric(key) is None else f"{mine} (full {num(ref.metric(key), unit)})"


INCONCLUSIVE = "inconclusive"


FLOOR_P99 = "timing.floor.overshoot_pct.p99"


def overshoot_outcome(run):
    """HOLDS, FAILS or INCONCLUSIVE for one quiet run against OVERSHOOT_PCT, given the machine's own floor
    beside it (summary.timing.floor: a null handler's overshoot p99 over as many windows, 0 where the run
    has none): it holds below the threshold whatever the floor; it fails when even its p99 less the whole
    floor p99 reaches the threshold (the method's own part does, however much of the floor's p99 was the
    machine's); in between, its excess over the threshold is within what the machine alone overshot, and it
    decides nothing. p99s of different samples do not add exactly, so floor + threshold is the harness's
    line, not a bound."""
    p99 = run.metric("overshoot_pct.p99")
    if p99 < OVERSHOOT_PCT:
        return HOLDS
    return FAILS if p99 - (run.metric(FLOOR_P99) or 0.0) >= OVERSHOOT_PCT else INCONCLUSIVE


def worst_overshoot(runs, ctx):
    """Judged on wall time where the runs were measured on a quiet machine; a noisy run's wall overshoot
    is partly the scheduler's, so it is shown (with its CPU-time overshoot) but decides nothing. A quiet run
    over the threshold by no more than its machine floor decides nothing either (overshoot_outcome)."""
    if not runs:
        return UNMEASURED, UNMEASURED

    def worst(group, key):
        known = [r for r in group if r.metric(key) is not None]
        return max(known, key=lambda r: r.metric(key)) if known else None

    def text(group, what):
        wall, cpu = worst(group, "overshoot_pct.p99"), worst(group, "overshoot_cpu_pct.p99")
        out = f"{what}: overshoot p99 up to {wall.metric('overshoot_pct.p99'):.1f} %"
        if wall.metric("overshoot_us.p99") is not None:
            out += f" = {wall.metric('overshoot_us.p99'):.0f} us"
        out += f" ({wall.name}; {plural(len(group), 'run')})"
        if cpu is not None:
            out += f", CPU-time overshoot p99 up to {cpu.metric('overshoot_cpu_pct.p99'):.1f} % ({cpu.name})"
        floor = worst(group, FLOOR_P99)
        if floor is not None:
            out += f", machine floor p99 up to {floor.metric(FLOOR_P99):.1f} % ({floor.name})"
        return out

    quiet = [r for r in runs if r.timing != "noisy"]
    noisy = [r for r in runs if r.timing == "noisy"]
    parts = []
    if quiet:
        parts.append(text(quiet, "quiet machine" if noisy or any(r.timing for r in quiet) else "all runs"))
    if noisy:
        parts.append(text(noisy, "noisy machine"))
    measured = "; ".join(parts)
    if not quiet:
        cpu = worst(noisy, "overshoot_cpu_pct.p99")
        cpu_text = f"CPU-time overshoot {cpu.metric('overshoot_cpu_pct.p99'):.1f} %" if cpu else "no CPU time"
        return measured, f"{INCONCLUSIVE}: measured on a noisy machine ({cpu_text})"
    outcomes = [overshoot_outcome(r) for r in quiet]
    bound = outcomes.count(INCONCLUSIVE)
    if bound == len(quiet):
        floor = worst(quiet, FLOOR_P99)
        return measured, (f"{INCONCLUSIVE}: each quiet run is over {OVERSHOOT_PCT:g} % by no more than the machine's "
                          f"own floor (null handler p99 up to {floor.metric(FLOOR_P99):.1f} %, {floor.name})")
    verdict = FAILS if FAILS in outcomes else HOLDS
    caveats = []
    if bound:
        caveats.append(f"{plural(bound, 'run')} {INCONCLUSIVE} (over by no more than the machine floor)")
    if noisy:
        caveats.append(f"{plural(len(noisy), 'run')} {INCONCLUSIVE} (noisy machine)")
    if caveats:
        verdict += " on the quiet runs the machine could judge; " + "; ".join(caveats)
    return measured, verdict


def speedup_range(rows, what):
    """"median (p50) handling time: up to 3.10x (run a), down to 1.20x (run b), 2 runs": the range of
    (run, speed-up) rows, `what` naming the statistic; "" when there are none."""
    if not rows:
        return ""
    best, low = max(rows, key=lambda row: row[1]), min(rows, key=lambda row: row[1])
    text = f"{what}: up to {best[1]:.2f}x ({best[0].name})"
    if len(rows) > 1:
        text += f", down to {low[1]:.2f}x ({low[0].name}), {plural(len(rows), 'run')}"
    return text


STEP_WHAT = "whole step (step_ms: handling + dynamics)"


def step_speedups(rows):
    """The whole step's speed-up for (run, reference, ...) rows, as text: its median (p50) and p99 ranges,
    shown beside the handling one and deciding nothing; "n/a" for runs (or references) recorded before
    summary.step_ms."""
    medians = [(run, pairing.step_speedup(run, ref)) for run, ref, *_ in rows]
    tails = [(run, pairing.step_speedup(run, ref, "p99")) for run, ref, *_ in rows]
    known = [(run, ratio) for run, ratio in medians if ratio is not None]
    if not known:
        return f"{STEP_WHAT}: n/a (no step_ms in these runs or their references)"
    parts = [speedup_range(known, f"median (p50) {STEP_WHAT} (shown, not judged)"),
             speedup_range([(run, tail) for run, tail in tails if tail is not None],
                           "p99 whole step (shown, not judged)")]
    if len(known) < len(medians):
        parts.append(f"whole step n/a for {plural(len(medians) - len(known), 'run')} without step_ms "
                     "(or whose reference has none)")
    return "; ".join(part for part in parts if part)


def best_speedup(runs, ctx):
    """Judged on the median (p50) per-step handling time, the statistic a budget full/K divides; the p99
    speed-up (what a deadline sees) and the whole step's (handling + dynamics: what the application sees,
    median and p99) are shown beside it and decide nothing."""
    rows = pairing.budgeted_with_reference(runs, ctx.runs)
    if not rows:
        return UNMEASURED, UNMEASURED
    best = max(rows, key=lambda row: row[2])
    tails = [(run, pairing.speedup(run, ref, "p99")) for run, ref, _ in rows]
    measured = "; ".join(part for part in (
        speedup_range([(run, ratio) for run, _, ratio in rows], "median (p50) handling time"),
        speedup_range([(run, tail) for run, tail in tails if tail is not None],
                      "p99 handling time (shown, not judged)"),
        step_speedups(rows)) if part)
    verdict = HOLDS if best[2] >= SPEEDUP_MIN else FAILS
    return measured, f"{verdict} (the budget sets it; what it costs is in the speed-up figure)"


def jitter_ratio(run, ctx):
    """The run's summary jitter over its reference's, or None when either is missing."""
    ref = ctx.reference(run)
    mine, theirs = run.metric("jitter"), ref.metric("jitter") if ref else None
    return mine / theirs if mine is not None and theirs else None


SETTLED = (("kinetic energy mean", "settled_kinetic_energy.mean", "J"),
           ("max speed median", "settled_max_speed_median", "m/s"))  # over the run's second half


def resting_outcomes(run, ctx):
    """{outcome: True/False/None (not measured)} of one run of the resting stack."""
    h0, h1 = run.metric("top_centre_height_m.initial"), run.metric("top_centre_height_m.final")
    ratio = jitter_ratio(run, ctx)
    tunnelling = run.metric("tunneling")
    standing = None if h0 is None or h1 is None else h1 >= STANDING_FRACTION * h0
    plausible = None if ratio is None else ratio <= JITTER_FACTOR
    out = {"stable": run.status == "ok", "standing": standing,
           "without pass-through": None if tunnelling is None else tunnelling == 0,
           "with plausible jitter": plausible}
    out["resting plausibly"] = all(v is True for v in out.values())
    return out


def repeated_rest(label, group, ctx):
    """(text, good) for a configuration's repeats: each outcome as a rate with its Wilson 95 % interval
    ("standing in 4/5 runs (80 %, 95 % CI 38-96 %)"), the median jitter and its multiple of full's, and the
    seeds that missed an outcome."""
    outcomes = [resting_outcomes(r, ctx) for r in group]
    n = len(group)
    parts = []
    for what in ("stable", "standing", "without pass-through", "with plausible jitter"):
        measured = [o[what] for o in outcomes if o[what] is not None]
        text = statistics.outcome_text(what, sum(measured), len(measured))
        parts.append(text + (f" ({n - len(measured)} not measured)" if len(measured) < n else ""))
    good = sum(o["resting plausibly"] for o in outcomes)
    jitter, lo, hi, known = statistics.summarise(r.metric("jitter") for r in group)
    ratio, r_lo, r_hi, _ = statistics.summarise(jitter_ratio(r, ctx) for r in group)
    if jitter is not None:
        text = f"median jitter (RMS) {jitter:.3g} m/s" + (f" [{lo:.3g}, {hi:.3g}]" if lo is not None else "")
        if ratio is not None:
            text += f", {ratio:.3g}x full's" + (f" [{r_lo:.3g}, {r_hi:.3g}]" if r_lo is not None else "")
        parts.append(text + f" (n={known}; bootstrap 95 % intervals; full: the same seed's)")
    missed = [f"seed {r.seed}: " + ", ".join(MISSED[what](r, v) for what, v in o.items()
                                             if what in MISSED and v is not True)
              for r, o in zip(group, outcomes) if not o["resting plausibly"]]
    jitter_drawn = statistics.jitter_text(group[0])
    head = f"{label}, {n} seeds" + (f" (jittered: {jitter_drawn})" if jitter_drawn and "jittered" not in label else "")
    text = f"{head}: " + ", ".join(parts) + "; " + statistics.outcome_text("resting plausibly (all four)", good, n)
    if missed:
        text += " (" + "; ".join(missed) + ")"
    return text, good


MISSED = {  # how a repeat that missed an outcome is named (v: False, or None when not measured)
    "stable": lambda r, v: f"status {r.status}",
    "standing": lambda r, v: "fallen" if v is False else "height not measured",
    "without pass-through": lambda r, v: "passed through" if v is False else "tunnelling not measured",
    "with plausible jitter": lambda r, v: "implausible jitter" if v is False else "jitter not compared",
}


def rests_plausibly(runs, ctx):
    """Per budget (and configuration): stable, still standing, nothing passed through, jitter within
    JITTER_FACTOR of the reference's. A configuration with repeats gives each outcome as a rate with its
    Wilson 95 % interval, and holds at its budget only when every repeat rests plausibly. The evidence adds
    how settled the stack is (kinetic energy and fastest vertex over the second half), beside the
    reference's."""
    if not runs:
        return UNMEASURED, UNMEASURED
    notes, results = [], []
    for label, group in by_budget(runs):
        if len(group) > 1:
            text, good = repeated_rest(label, group, ctx)
            notes.append(text)
            results.append((label, good, len(group)))
            continue
        good = 0
        for r in group:
            ref = ctx.reference(r)
            h0, h1 = r.metric("top_centre_height_m.initial"), r.metric("top_centre_height_m.final")
            standing = h0 is not None and h1 is not None and h1 >= STANDING_FRACTION * h0
            tunnelling, jitter, ratio = r.metric("tunneling"), r.metric("jitter"), jitter_ratio(r, ctx)
            plausible = ratio is not None and ratio <= JITTER_FACTOR
            ok = r.status == "ok" and tunnelling == 0 and standing and plausible
            good += ok
            height = (f"top centre {h0:.3f} -> {h1:.3f} m: {'standing' if standing else 'fallen'} (ours)"
                      if h0 is not None and h1 is not None else "height not measured")
            jit = "jitter not measured" if jitter is None else f"jitter (RMS) {jitter:.3g} m/s" + (
                f" = {ratio:.3g}x full's: {'plausible' if plausible else 'implausible'} (ours)"
                if ratio is not None else " (no reference to compare)")
            settled = [f"{name} {vs_reference(r, ref, key, unit)}" for name, key, unit in SETTLED
                       if r.metric(key) is not None]
            notes.append(f"{where(r, group, label)}: {'ok' if r.status == 'ok' else 'status ' + r.status}, {height}, "
                         f"tunnelling {tunnelling}, {jit}" + (", settled: " + ", ".join(settled) if settled else ""))
        results.append((label, good, len(group)))
    return "; ".join(notes), per_budget_verdict(results)


def jitters(runs, ctx):
    """The naive alternative's jitter exceeds JITTER_FACTOR times the reference's."""
    rows = [(r, jitter_ratio(r, ctx)) for r in runs]
    rows = [(r, x) for r, x in rows if x is not None]
    if not rows:
        return UNMEASURED, UNMEASURED
    loud = [r for r, x in rows if x > JITTER_FACTOR]
    ratios = dict((r.name, x) for r, x in rows)
    notes = []
    for group in statistics.repeats([r for r, _ in rows]):
        if len(group) == 1:
            r = group[0]
            notes.append(f"{r.name}: jitter (RMS) {r.metric('jitter'):.3g} m/s = {ratios[r.name]:.3g}x full's")
            continue
        # Repeats: the outcome as a rate with its Wilson interval, the ratio as a median with its bootstrap one.
        k = sum(1 for r in group if ratios[r.name] > JITTER_FACTOR)
        ratio, lo, hi, n = statistics.summarise(ratios[r.name] for r in group)
        jitter = statistics.jitter_text(group[0])
        notes.append(f"{group[0].label()}, {n} seeds{' (jittered: ' + jitter + ')' if jitter else ''}: "
                     + statistics.outcome_text(f"jitter above {JITTER_FACTOR:g}x full's", k, n)
                     + f", median {ratio:.3g}x full's [{lo:.3g}, {hi:.3g}] (bootstrap 95 %; full: the same seed's)")
    return "; ".join(notes), share(len(loud), len(rows))


ABLATION = "interruptible_no_extrapolation"  # the paper's method without force extrapolation


def extrapolation_steadies(runs, ctx):
    """Per budget: the run with extrapolation jitters less than the ablation without it (same experiment,
    same budget)."""
    notes, results = [], []
    for label, group in by_budget(runs):
        good = compared = 0
        for r in group:
            other = pairing.counterpart(r, ctx.runs, ABLATION)
            mine, theirs = r.metric("jitter"), other.metric("jitter") if other else None
            if mine is None or theirs is None:
                continue
            compared += 1
            good += mine < theirs
            ratio = f" ({mine / theirs:.2f}x)" if theirs else ""
            notes.append(f"{where(r, group, label)}: jitter (RMS) {mine:.3g} m/s with extrapolation, {theirs:.3g} m/s "
                         "without"
                         + ratio)
        if compared:
            results.append((label, good, compared))
    if not results:
        return (f"no {ABLATION} run with jitter in the same setup at the same budget" if runs else UNMEASURED,
                UNMEASURED)
    return "; ".join(notes), per_budget_verdict(results)


def repeated_pass_through(runs):
    """'; pass-through per configuration (12 with 10 seeds each): interruptible @ full-work/64 in 3/10 runs
    (30 %, 95 % CI 11-60 %), max latency median 7 [6, 9] (n=10) steps; none in the other 11 (0/10 runs each:
    95 % CI 0-28 %)'; '' when no configuration has repeats."""
    groups = [g for g in statistics.repeats(runs) if len(g) > 1]
    if not groups:
        return ""
    scenes = len({r.scene for r in runs}) > 1
    tunnelled, clean = [], []
    for g in groups:
        k = sum(1 for r in g if r.metric("tunneling"))
        if not k:
            clean.append(len(g))
            continue
        latency = statistics.estimate_text(*statistics.summarise(r.metric("latency_steps.max") for r in g),
                                           fmt="{:.0f}")
        name = g[0].label() + (f" ({g[0].scene})" if scenes else "")
        tunnelled.append(f"{statistics.outcome_text(name, k, len(g))}, max latency {latency} steps")
    sizes = sorted({len(g) for g in groups})
    text = (f"; pass-through per configuration ({len(groups)} with "
            f"{sizes[0] if len(sizes) == 1 else f'{sizes[0]} to {sizes[-1]}'} seeds each): " + "; ".join(tunnelled))
    if clean:
        each = (f" (0/{clean[0]} runs each: 95 % CI 0-{100 * statistics.wilson_interval(0, clean[0])[1]:.0f} %)"
                if len(set(clean)) == 1 else "")
        text += ("; " if tunnelled else "") + f"none in {'the other ' if tunnelled else ''}{len(clean)}{each}"
    return text


def latency_bound(runs, ctx):
    """Runs whose longest latency (latency_steps.max, over penetration episodes) is <= LATENCY_STEPS never
    tunnel; some with more do."""
    if not runs:
        return UNMEASURED, UNMEASURED
    low = [r for r in runs if r.metric("latency_steps.max") <= LATENCY_STEPS]
    high = [r for r in runs if r.metric("latency_steps.max") > LATENCY_STEPS]
    low_tunnel = [r for r in low if r.metric("tunneling")]
    high_tunnel = [r for r in high if r.metric("tunneling")]
    measured = (f"max latency <= {LATENCY_STEPS} steps: {statistics.rate_text(len(low_tunnel), len(low))} runs "
                f"tunnel; max latency > {LATENCY_STEPS} steps: {statistics.rate_text(len(high_tunnel), len(high))} "
                "runs tunnel")
    safe = [r.metric("latency_steps.max") for r in runs if not r.metric("tunneling")]
    if high_tunnel:
        measured += (f"; no pass-through up to a max latency of {max(safe, default=0):.0f} steps, pass-through "
                     f"from {min(r.metric('latency_steps.max') for r in high_tunnel):.0f} steps")
    measured += repeated_pass_through(runs)
    if low_tunnel:
        verdict = FAILS
    elif low and high_tunnel:
        verdict = HOLDS if max(safe, default=0) <= LATENCY_STEPS else "partly: the objects resist longer latencies here"
    elif high:
        verdict = f"partly: no run above {LATENCY_STEPS} steps tunnelled here"
    else:
        verdict = f"partly: not measured above {LATENCY_STEPS} steps"
    return measured, verdict


# ---------------------------------------------------------------- further evidence: force error, divergence

FORCE_KEY = "force_error.relative_l2.p50"
FORCE_WHAT = "force error (relative L2 against full's forces from the same state, p50 over sampled steps)"
DIVERGENCE_WHAT = (f"divergence (RMS vertex distance to full at the last compared step, {pairing.DIVERGENCE}, "
                   "as a multiple of the noise floor)")


def has_force_error(run):
    return run.metric(FORCE_KEY) is not None


def has_divergence(run):
    return run.metric(pairing.DIVERGENCE) is not None and not pairing.is_noise_floor(run)


def divergence_text(run, ctx):
    """(multiple of the floor or None, "357x floor" | "1.71e-04 m (no noise-floor run)")."""
    floor = pairing.noise_floor(run, ctx.runs)
    multiple = pairing.floor_multiple(run, floor)
    if multiple is not None:
        return multiple, f"{multiple:.3g}x floor"
    value = run.metric(pairing.DIVERGENCE)
    why = "no noise-floor run" if floor is None else "floor 0"
    return None, f"{num(value, 'm')} ({why})"


def above_noise(mine, theirs):
    """Whether two multiples of the same floor differ by FLOOR_FACTOR floors or more (ours): only then does
    the difference between two divergences decide anything."""
    return mine is not None and theirs is not None and abs(mine - theirs) >= FLOOR_FACTOR


def every_nth_n(run):
    n = run.settings.get("n", EVERY_NTH_N)
    return n if isinstance(n, (int, float)) and n > 0 else None


def papers_interruptible(run):
    """The paper's method: interruptible with the paper's schedule (PAPER_TASKS; absent settings count as
    the default)."""
    return run.method == "interruptible" and all(run.settings.get(name, value) == value
                                                 for name, value in PAPER_TASKS.items())


def comparable_interruptible(run, ctx, has):
    """The paper's method (interruptible with PAPER_TASKS) in run's experiment at the relative budget (full/K
    or full-work/K) nearest every_nth's share of full's work (1/n), work budgets first; with `has(run)` true.
    Returns (that run, K) or (None, None)."""
    n, key = every_nth_n(run), pairing.setup(run)
    candidates = []
    for r in ctx.runs:
        k = relative_divisor(r.budget_label)
        if papers_interruptible(r) and k and has(r) and pairing.setup(r) == key:
            candidates.append((abs(math.log(k / n)) if n else 0.0, r.budget_kind != "work", k < (n or 0), r.name, r, k))
    if not candidates:
        return None, None
    *_, best, k = min(candidates)
    return best, k


def inferior(mine, theirs, n, k, decided=True):
    """every_nth (n) against interruptible at full/K: inferior when it erred more with no less work; not when it
    erred no more with no more work; otherwise the work differs the wrong way to tell."""
    if not decided:
        return "inferior: undecided, they differ by less than the noise"
    if mine > theirs and k >= n:
        return "inferior: yes" + ("" if k == n else f", though interruptible had less work (1/{k:g} of full's)")
    if mine <= theirs and k <= n:
        return "inferior: no" + ("" if k == n else f", though interruptible had more work (1/{k:g} of full's)")
    more = "every_nth" if k > n else "interruptible"
    return f"inferior: undecided, {more} had more work: every_nth 1/{n:g} of full's, interruptible 1/{k:g}"


def named(run, runs):
    """" (plates20, seed 0)" when the evidence has several runs, else ""."""
    return f" ({run.scene}, seed {run.seed})" if len(runs) > 1 else ""


def every_nth_force(runs, ctx):
    """every_nth (n = 2) against the paper's method at the budget nearest its work: force error p50."""
    runs = [r for r in runs if has_force_error(r)]
    if not runs:
        return f"{FORCE_WHAT}: n/a (no every_nth n={EVERY_NTH_N} run with summary.force_error)"
    notes = []
    for r in runs:
        n, mine = every_nth_n(r), r.metric(FORCE_KEY)
        other, k = comparable_interruptible(r, ctx, has_force_error)
        text = f"every_nth n={n:g} {mine:.3g}{named(r, runs)}"
        if other is None:
            notes.append(f"{text} vs no interruptible run (paper's settings, relative budget, same setup) with "
                         "force error: n/a")
            continue
        theirs = other.metric(FORCE_KEY)
        notes.append(f"{text} vs interruptible at {other.budget_label} {theirs:.3g} ({inferior(mine, theirs, n, k)})")
    return f"{FORCE_WHAT}: " + "; ".join(notes)


def every_nth_divergence(runs, ctx):
    """every_nth (n = 2) against the paper's method at the budget nearest its work: divergence over the floor."""
    runs = [r for r in runs if has_divergence(r)]
    if not runs:
        return f"{DIVERGENCE_WHAT}: n/a (no every_nth n={EVERY_NTH_N} run with summary.divergence)"
    notes = []
    for r in runs:
        n = every_nth_n(r)
        mine, mine_text = divergence_text(r, ctx)
        other, k = comparable_interruptible(r, ctx, has_divergence)
        text = f"every_nth n={n:g} {mine_text}{named(r, runs)}"
        if other is None:
            notes.append(f"{text} vs no interruptible run (paper's settings, relative budget, same setup) with "
                         "divergence: n/a")
            continue
        theirs, theirs_text = divergence_text(other, ctx)
        verdict = (inferior(mine, theirs, n, k, above_noise(mine, theirs)) if mine is not None and theirs is not None
                   else "inferior: undecided without a noise floor")
        notes.append(f"{text} vs interruptible at {other.budget_label} {theirs_text} ({verdict})")
    return f"{DIVERGENCE_WHAT}: " + "; ".join(notes)


def where_scene(run, group):
    """where(run, group), the scene first when the group spans several (the evidence reads every scene's runs)."""
    return (f"{run.scene} " if len({r.scene for r in group}) > 1 else "") + where(run, group)


def lower_with(mine, theirs, decided=True):
    if not decided:
        return "lower with: undecided, they differ by less than the noise"
    return "lower with: yes" if mine < theirs else "lower with: no"


def extrapolation_force(runs, ctx):
    """The paper's method against the ablation without extrapolation at the same budget: force error p50."""
    runs = [r for r in runs if has_force_error(r)]
    if not runs:
        return f"{FORCE_WHAT}: n/a (no interruptible run with summary.force_error)"
    notes = []
    for label, group in by_budget(runs):
        for r in group:
            other = pairing.counterpart(r, ctx.runs, ABLATION)
            mine = r.metric(FORCE_KEY)
            theirs = other.metric(FORCE_KEY) if other else None
            if theirs is None:
                notes.append(f"{where_scene(r, group)}: {mine:.3g} with extrapolation, no {ABLATION} run with "
                             "force error at this budget: n/a")
            else:
                notes.append(f"{where_scene(r, group)}: {mine:.3g} with extrapolation, {theirs:.3g} without "
                             f"({lower_with(mine, theirs)})")
    return f"{FORCE_WHAT}: " + "; ".join(notes)


def extrapolation_divergence(runs, ctx):
    """The paper's method against the ablation without extrapolation at the same budget: divergence over the
    floor."""
    runs = [r for r in runs if has_divergence(r)]
    if not runs:
        return f"{DIVERGENCE_WHAT}: n/a (no interruptible run with summary.divergence)"
    notes = []
    for label, group in by_budget(runs):
        for r in group:
            other = pairing.counterpart(r, ctx.runs, ABLATION)
            mine, mine_text = divergence_text(r, ctx)
            if other is None or not has_divergence(other):
                notes.append(f"{where_scene(r, group)}: {mine_text} with extrapolation, no {ABLATION} run with "
                             "divergence at this budget: n/a")
                continue
            theirs, theirs_text = divergence_text(other, ctx)
            verdict = (lower_with(mine, theirs, above_noise(mine, theirs)) if mine is not None and theirs is not None
                       else "lower with: undecided without a noise floor")
            notes.append(f"{where_scene(r, group)}: {mine_text} with extrapolation, {theirs_text} without ({verdict})")
    return f"{DIVERGENCE_WHAT}: " + "; ".join(notes)


EVERY_NTH_EVIDENCE = (
    Evidence("force_error", Select(methods=("every_nth",), settings={"n": EVERY_NTH_N}, measured=(FORCE_KEY,)),
             every_nth_force),
    Evidence("divergence", Select(methods=("every_nth",), settings={"n": EVERY_NTH_N},
                                  measured=(pairing.DIVERGENCE,)), every_nth_divergence))
EXTRAPOLATION_EVIDENCE = (
    Evidence("force_error", Select(methods=("interruptible",), settings=PAPER_TASKS,
                                   budget_kinds=("wall_ms", "work"), measured=(FORCE_KEY,)), extrapolation_force),
    Evidence("divergence", Select(methods=("interruptible",), settings=PAPER_TASKS,
                                  budget_kinds=("wall_ms", "work"), measured=(pairing.DIVERGENCE,)),
             extrapolation_divergence))
EVIDENCE_KEYS = (FORCE_KEY, pairing.DIVERGENCE)
FLOOR_OURS = (f"FLOOR_FACTOR = {FLOOR_FACTOR:g}: two divergences (as multiples of the noise floor, same setup) "
              "differ only when they are that many floors apart; the force-error and divergence evidence is shown "
              "with its own verdict in the text and does not decide the row's")


# ---------------------------------------------------------------- every second step against interruptible, same work

EVERY_NTH_DEFAULTS = {"n": EVERY_NTH_N, "hold": True}  # method_label "every_nth": n = 2, forces held between cycles
MIXED = "mixed"
UNDECIDED = "undecided: within the noise floor"
INFERIOR_TEXT = {HOLDS: "inferior", FAILS: "not inferior: interruptible is worse on both",
                 MIXED: "mixed: force error and divergence disagree", UNDECIDED: UNDECIDED}
INFERIOR_PARTS = {HOLDS: "holds", FAILS: "does not hold", MIXED: "mixed",
                  UNDECIDED: "undecided (within the noise floor)"}
FLOOR_RUN = "a noise-floor run (full, no budget, a perturb.* override, same setup)"


def same_work_interruptible(run, ctx):
    """The paper's method (interruptible, PAPER_TASKS) in run's experiment (same scene, seed, response and
    overrides) with every_nth's share of full's work: a relative budget full-work/K, else full/K, with K = n.
    Among several, one with both keys the claim reads first, then one from the same sweep and of the same
    length. None when there is none."""
    n, key = every_nth_n(run), pairing.setup(run)
    candidates = [r for r in ctx.runs if papers_interruptible(r) and n and relative_divisor(r.budget_label) == n
                  and pairing.setup(r) == key]
    if not candidates:
        return None
    return min(candidates, key=lambda r: (
        (not has_force_error(r)) + (not has_divergence(r)), r.budget_kind != "work", not (r.sweeps & run.sweeps),
        r.record.get("steps") != run.record.get("steps"), r.name))


def floor_multiple_or_why(run, ctx):
    """(the run's divergence as a multiple of its noise floor, None) or (None, why not)."""
    if not has_divergence(run):
        return None, f"no {pairing.DIVERGENCE}"
    floor = pairing.noise_floor(run, ctx.runs)
    if floor is None:
        return None, f"no noise floor: {FLOOR_RUN}"
    multiple = pairing.floor_multiple(run, floor)
    return (multiple, None) if multiple is not None else (None, f"its noise floor ({floor.name}) is 0 or unmeasured")


def inferior_at_same_work(force_mine, force_theirs, multiple_mine, multiple_theirs):
    """every_nth (mine) against interruptible at the same work (theirs), from the force error p50 and the
    divergence as a multiple of the noise floor. Undecided when the divergences are fewer than FLOOR_FACTOR
    floors apart; holds (inferior) when every_nth errs more and diverges more; does not hold when interruptible
    does both; mixed when the two disagree (or the force errors are equal)."""
    if not above_noise(multiple_mine, multiple_theirs):
        return UNDECIDED
    diverges_more = multiple_mine > multiple_theirs
    if force_mine > force_theirs and diverges_more:
        return HOLDS
    if force_mine < force_theirs and not diverges_more:
        return FAILS
    return MIXED


def jitter_text(run, ctx):
    if run is None or run.metric("jitter") is None:
        return "n/a"
    ratio = jitter_ratio(run, ctx)
    return f"{run.metric('jitter'):.3g} m/s" + (f" = {ratio:.3g}x full's" if ratio is not None else "")


def inferior_pair(run, other, ctx, runs):
    """(the text of one every_nth run against its interruptible run, verdict or None when not measured)."""
    n = every_nth_n(run)
    label = f"every_nth n={n:g}{named(run, runs)}"
    if other is None:
        budgets = f"full-work/{n:g} or full/{n:g}" if n else "the same share of full's work"
        return (f"{label}: {UNMEASURED}: no interruptible run (paper's settings) at {budgets} in the same setup; "
                f"jitter (RMS, shown, not judged) {jitter_text(run, ctx)}"), None
    pair = (("every_nth", run), ("interruptible", other))
    missing = {}  # why -> who: what keeps the pair from being judged, each reason once
    for who, r in pair:
        if not has_force_error(r):
            missing.setdefault(f"no {FORCE_KEY}", []).append(who)
    multiples = {}
    for who, r in pair:
        multiples[who], why = floor_multiple_or_why(r, ctx)
        if why:
            missing.setdefault(why, []).append(who)

    def force(r):
        return num(r.metric(FORCE_KEY))

    def div(who):
        return "n/a" if multiples[who] is None else f"{multiples[who]:.3g}x floor"

    numbers = (f"force error p50 {force(run)} vs {force(other)}, divergence {div('every_nth')} vs "
               f"{div('interruptible')}"
               + (f" ({abs(multiples['every_nth'] - multiples['interruptible']):.3g} floors apart)"
                  if None not in multiples.values() else "")
               + f", jitter (RMS, shown, not judged) {jitter_text(run, ctx)} vs {jitter_text(other, ctx)}")
    text = f"{label} vs interruptible at {other.budget_label}: {numbers}"
    if missing:
        reasons = "; ".join(" and ".join(who) + f": {why}" for why, who in missing.items())
        return f"{text}: {UNMEASURED} ({reasons})", None
    verdict = inferior_at_same_work(run.metric(FORCE_KEY), other.metric(FORCE_KEY), multiples["every_nth"],
                                    multiples["interruptible"])
    return f"{text}: {INFERIOR_TEXT[verdict]}", verdict


def every_2nd_inferior(runs, ctx):
    """Each every_nth (n = 2, its defaults) run against the paper's method at the same share of full's work,
    judged on the force error p50 and the divergence over the noise floor (inferior_at_same_work); the
    jitter is shown beside them. One verdict for the runs: theirs when they agree, else what share each has."""
    if not runs:
        return (f"no every_nth n={EVERY_NTH_N} run (its default settings) in the sweeps declaring the jitter figure",
                UNMEASURED)
    ordered = sorted(runs, key=lambda r: (r.scene, r.seed if r.seed is not None else -1, r.name))
    notes, verdicts = [], []
    for r in ordered:
        text, verdict = inferior_pair(r, same_work_interruptible(r, ctx), ctx, runs)
        notes.append(text)
        if verdict is not None:
            verdicts.append(verdict)
    unmeasured = len(runs) - len(verdicts)
    if not verdicts:
        return "; ".join(notes), UNMEASURED
    if len(set(verdicts)) == 1:
        verdict = verdicts[0]
    else:
        shares = [f"{INFERIOR_PARTS[v]} in {verdicts.count(v)}" for v in INFERIOR_PARTS if v in verdicts]
        verdict = f"partly: {', '.join(shares)} of {plural(len(verdicts), 'run')}"
    if unmeasured:
        verdict += f" ({plural(unmeasured, 'run')} {UNMEASURED})"
    return "; ".join(notes), verdict


INFERIOR_OURS = (
    f"the rule: every_nth n={EVERY_NTH_N} (its defaults) against interruptible (the paper's settings) at the "
    f"same share of full's work (full-work/{EVERY_NTH_N}, else full/{EVERY_NTH_N}), same scene, seed, response "
    "and overrides; inferior (holds) when every_nth's force error p50 is higher AND its divergence "
    f"({pairing.DIVERGENCE} over the noise floor) is at least FLOOR_FACTOR = {FLOOR_FACTOR:g} floors higher; "
    "does not hold when interruptible is worse on both; undecided when the divergences are fewer than "
    f"{FLOOR_FACTOR:g} floors apart; mixed otherwise; not measured without either run, a key or the noise floor",
    "jitter is shown beside it, not judged (every_2nd_jitters judges it)",
    "judged on the every_nth runs of the sweeps declaring the jitter figure (resting contact)")


# ---------------------------------------------------------------- the table

# ---------------------------------------------------------------- the neural detector (seed 002)

NEURAL_MIN_SEEDS = 3


def neural_compare(key, better, what):
    """A rule comparing the last round's `key` of active and supervised learning, seed against seed, from
    the neural experiment's files beneath the report's root (runs play no part)."""
    def rule(runs, ctx):
        found = neural.find(ctx.results.root)
        rows = [row for results in found for row in neural.compare_final(results, key, better)]
        if not rows:
            return UNMEASURED, UNMEASURED
        texts, verdicts = [], []
        for preset, active, supervised, wins, seeds in rows:
            texts.append(f"{preset}: {what} active {active:.3f} vs supervised {supervised:.3f} (mean of the last "
                         f"round over {seeds} seeds; active {better} in {wins}/{seeds})")
            # Paired by seed (both strategies share each seed's bootstrap). It holds when active is better on
            # every seed, fails when it is better on none, of at least 3 seeds (unanimity by chance: 1/8 or
            # less); anything else, or fewer seeds, is inconclusive.
            verdicts.append(INCONCLUSIVE if seeds < NEURAL_MIN_SEEDS else
                            HOLDS if wins == seeds else FAILS if wins == 0 else INCONCLUSIVE)
        verdict = verdicts[0] if len(set(verdicts)) == 1 else "partly: " + ", ".join(
            f"{r[0]} {v}" for r, v in zip(rows, verdicts))
        return "; ".join(texts), verdict
    return rule


def alm_interval(group):
    """95 % Wilson interval of a strategy's resolved share, over its distinct codes (attempts / seeds)."""
    resolved, attempted, _, seeds = group
    codes = max(1, round(attempted / max(1, seeds)))
    return statistics.wilson_interval(round(codes * resolved / max(1, attempted)), codes)


def neural_alm(runs, ctx):
    """Collisions the ALM resolves (the oracle's verdict at its answer) with active against supervised
    networks, per preset and margin, with the distance moved: resolving more by moving further is shown."""
    groups = {}
    for results in neural.find(ctx.results.root):
        for r in results.alm:
            g = groups.setdefault((r["preset"], r["margin"]), {}).setdefault(r["strategy"], [0, 0, [], 0])
            g[0] += r["resolved"]
            g[1] += r["attempted"]
            g[2].append(r["median_distance_ratio"])
            g[3] += 1  # seeds
    if not groups:
        return UNMEASURED, UNMEASURED
    texts, verdicts = [], []
    for (preset, margin), by in sorted(groups.items()):
        if "active" not in by or "supervised" not in by:
            continue
        a, s = by["active"], by["supervised"]
        ra, rs = a[0] / max(1, a[1]), s[0] / max(1, s[1])
        texts.append(f"{preset} margin {margin:g}: active {int(a[0])}/{int(a[1])} ({ra:.0%}, distance "
                     f"{neural.mean(a[2]):.2f}x the reference) vs supervised {int(s[0])}/{int(s[1])} ({rs:.0%}, "
                     f"{neural.mean(s[2]):.2f}x)")
        # A difference counts when the 95 % Wilson intervals of the two shares do not overlap. Every seed
        # resolves the same codes, so the seeds' attempts are not independent: the interval is taken over the
        # distinct codes (attempts / seeds), with the pooled share.
        (alo, ahi), (slo, shi) = alm_interval(a), alm_interval(s)
        verdicts.append(HOLDS if alo > shi else FAILS if ahi < slo else INCONCLUSIVE)
    if not verdicts:
        return UNMEASURED, UNMEASURED
    if len(set(verdicts)) == 1:
        verdict = verdicts[0]
    else:
        counts = ", ".join(f"{v} at {verdicts.count(v)}" for v in (HOLDS, FAILS, INCONCLUSIVE) if verdicts.count(v))
        verdict = f"partly: {counts} of {len(verdicts)} margins"
    return "; ".join(texts), verdict


NEURAL_OURS = ("the verdict, paired by seed (both strategies share each seed's bootstrap, labels and gradient "
               "steps): holds when the last round favours active learning on every one of at least 3 seeds, fails "
               "when it favours it on none; mixed, or fewer seeds: inconclusive",)


CLAIMS = [
    Claim(id="granularity",
          text="Time constraints are met with a granularity below 5 % of the budget",
          paper=f"< {OVERSHOOT_PCT:g} %",
          figure="overshoot", select=Select(methods=("interruptible",), settings=PAPER_TASKS, budget_kinds=("wall_ms",),
                                          measured=("overshoot_pct.p99",)),
          metrics=("overshoot_pct.p99", "overshoot_cpu_pct.p99", "timing.verdict", FLOOR_P99), rule=worst_overshoot,
          ours=("the statistic: each run's p99 of per-step overshoot, the worst run deciding (the paper names "
                "none)",
                "judged on wall time on quiet runs only (summary.timing): a noisy run's is inconclusive",
                "a quiet run over the threshold by no more than its machine floor (summary.timing.floor: a null "
                "handler spun beside it) is inconclusive; one over it by more fails")),
    Claim(id="speedup",
          text="Interruptible handling saves up to two thirds of the collision handling time",
          paper=f"up to {SPEEDUP:g}x (120 -> 40 ms)",
          figure="speedup", select=Select(methods=("interruptible",), settings=PAPER_TASKS, budget_kinds=("wall_ms",),
                                        measured=("handling_ms.p50",)),
          metrics=("handling_ms.p50", "handling_ms.p99", "step_ms.p50", "step_ms.p99"), rule=best_speedup,
          ours=(f"SPEEDUP_MIN = {SPEEDUP_MIN:g}: counts as reproduced from {SPEEDUP_MIN:g}x",
                "the statistic: full's median (p50) per-step handling time over the run's (the paper names none); "
                "the p99 ratio is shown beside it, not judged",
                "the whole step's ratio (step_ms: handling + dynamics, median and p99) is shown beside it, "
                "not judged")),
    Claim(id="stack_rests",
          text="A stack rests plausibly under the budget: stable, standing, no pass-through, plausible jitter",
          paper="plausible resting contact",
          figure="jitter",
          select=Select(methods=("interruptible", "interruptible_no_extrapolation", "interruptible_tracked"),
                        settings=PAPER_TASKS,
                        budget_kinds=("wall_ms", "work"), measured=("jitter",)),
          metrics=("top_centre_height_m.initial", "top_centre_height_m.final", "tunneling", "jitter",
                   "settled_kinetic_energy.mean", "settled_max_speed_median"),
          rule=rests_plausibly, per=("method", "response"),
          ours=(f"STANDING_FRACTION = {STANDING_FRACTION:g}: standing while the top centre keeps that share of "
                "its height",
                f"JITTER_FACTOR = {JITTER_FACTOR:g}: plausible jitter (RMS) is at most that times full's (same setup)",
                "interruptible_no_extrapolation and interruptible_tracked are our variants, judged alike")),
    Claim(id="every_2nd_jitters",
          text=f"Handling collisions only every n-th step (n = {EVERY_NTH_N}) makes resting contact jitter",
          paper="resting contact jitters",
          figure="jitter", select=Select(methods=("every_nth",), settings={"n": EVERY_NTH_N}, measured=("jitter",)),
          metrics=("jitter",) + EVIDENCE_KEYS, rule=jitters, per=("response",), evidence=EVERY_NTH_EVIDENCE,
          ours=(f"JITTER_FACTOR = {JITTER_FACTOR:g}: jitter (RMS) is more than that times full's (same setup)",
                "the force-error and divergence comparison: every_nth n against interruptible (the paper's "
                "settings) at the relative budget nearest 1/n of full's work; inferior when it errs more with no "
                "less work, not inferior when it errs no more with no more work",
                FLOOR_OURS)),
    Claim(id="every_2nd_inferior",
          text="Handling every second step is inferior to the interruptible method at the same work",
          paper="every second step is inferior: resting contact jitters (no number)",
          figure="jitter", select=Select(methods=("every_nth",), settings=EVERY_NTH_DEFAULTS),
          metrics=EVIDENCE_KEYS + ("jitter",), rule=every_2nd_inferior, per=("response",), ours=INFERIOR_OURS),
    Claim(id="extrapolation_steadies",
          text="Force extrapolation avoids jitter: interruptible jitters less than interruptible_no_extrapolation "
               "at the same budget",
          paper="extrapolated forces while a cycle is incomplete (no number)",
          figure="jitter", select=Select(methods=("interruptible",), settings=PAPER_TASKS,
                                       budget_kinds=("wall_ms", "work"),
                                       measured=("jitter",)),
          metrics=("jitter",) + EVIDENCE_KEYS, rule=extrapolation_steadies, per=("response",),
          evidence=EXTRAPOLATION_EVIDENCE,
          ours=("the comparison: the paper gives no ablation; lower jitter (RMS) than the same run without "
                "extrapolation counts",
                FLOOR_OURS)),
    Claim(id="latency",
          text=f"A fast heavy object: latency up to {LATENCY_STEPS} steps keeps it from passing through; "
               "more lets it pass",
          paper=f"<= {LATENCY_STEPS} steps holds",
          figure="latency", select=Select(measured=("latency_steps.max",)),
          metrics=("latency_steps.max", "tunneling"), rule=latency_bound),
    Claim(id="neural_active_accuracy",
          text="Active learning gives a more accurate self-collision detector than supervised learning with the "
               "same labels",
          paper="93.8-98.1 % accuracy; higher than supervised",
          figure="neural", select=Select(), metrics=("accuracy",),
          rule=neural_compare("accuracy", "higher", "accuracy"), ours=NEURAL_OURS),
    Claim(id="neural_active_fnr",
          text="Active learning has a lower false-negative rate than supervised learning with the same labels",
          paper="5.2-25.5 % lower false-negative rate",
          figure="neural", select=Select(), metrics=("fnr",),
          rule=neural_compare("fnr", "lower", "false-negative rate"), ours=NEURAL_OURS),
    Claim(id="neural_alm_resolves",
          text="The ALM resolves more collisions with the actively trained network",
          paper="9.7-58.9 % more collisions resolved",
          figure="neural", select=Select(), metrics=("resolved",), rule=neural_alm,
          ours=("resolved: the oracle finds no penetration at the ALM's code; the distance moved is shown beside "
                "it, as a solver that moves further resolves more",
                "the verdict per margin: the 95 % Wilson intervals of the resolved shares (pooled over seeds, the "
                "interval over the distinct codes, since every seed resolves the same ones) do not overlap; "
                "otherwise inconclusive")),
]


PARTS = {  # claim.per name -> (the run's value, its sort key, how a row names it)
    "method": (lambda r: r.method_label, lambda v: (v != "interruptible", v), lambda v: v),
    "response": (lambda r: r.response, response_order, lambda v: f"{v} response"),
}


def part_key(claim, run):
    """The values of the claim's `per` keys for run: which row judges it."""
    return tuple(PARTS[p][0](run) for p in claim.per)


def parts(claim, runs):
    """[(part text, runs)]: runs split by the claim's `per` keys; one part of all runs when it has none
    (or no runs)."""
    return [(text, [r for r in runs if part_key(claim, r) == key]) for text, key in part_keys(claim, runs)]


def part_keys(claim, runs):
    """[(part text, key)] of the parts runs fall in, in order; [("", None)] when the claim has no `per` or
    there are no runs."""
    if not claim.per or not runs:
        return [("", None)]
    keys = sorted({part_key(claim, r) for r in runs},
                  key=lambda key: tuple(PARTS[p][1](v) for p, v in zip(claim.per, key)))
    return [(", ".join(PARTS[p][2](v) for p, v in zip(claim.per, key)), key) for key in keys]


def judge(ctx):
    """[Outcome] for every claim, judged on the runs its figure draws: one per part of them (response
    mode, method variant) where the claim says so. A claim's further evidence (force error, divergence)
    comes from its own figures' runs, is split alike and appended to what was measured; a part that only
    the evidence has still gets a row (its verdict: not measured)."""
    modules = dict(figures.discover())

    def scope(name):
        module = modules.get(name)
        return figures.runs_in_scope(name, module, ctx.runs) if module else []

    outcomes = []
    for claim in CLAIMS:
        judged = claim.select(scope(claim.figure))
        # The evidence comes from the scenes of the runs the claim judges only: a resting-contact claim is
        # not backed by another scene's runs (a self-collision scene's, say) that the other figures draw.
        scenes = {r.scene for r in judged}
        drawn = [(e, e.select(scope(e.figure))) for e in claim.evidence]
        evidence = [(e, [r for r in runs if r.scene in scenes]) for e, runs in drawn]
        everything = judged + [r for _, runs in evidence for r in runs]
        for part, key in part_keys(claim, everything):
            runs = in_part(claim, key, judged)
            measured, verdict = claim.rule(runs, ctx)
            if evidence:
                if measured == UNMEASURED:
                    measured = f"{claim.metrics[0]} (what the verdict judges): {UNMEASURED}" + (
                        f" in the runs of sweeps declaring the {claim.figure} figure"
                        if getattr(modules.get(claim.figure), "SCOPE", "") == "declared" else "")
                measured = "; ".join([measured] + [e.rule(in_part(claim, key, ev_runs), ctx)
                                                   for e, ev_runs in evidence])
                left_out = sorted({r.scene for _, runs in drawn for r in in_part(claim, key, runs)} - scenes)
                if left_out:
                    measured += (f"; evidence from the scenes judged only ({', '.join(sorted(scenes)) or 'none'}): "
                                 f"{', '.join(left_out)} left out")
            extra = [r for _, ev_runs in evidence for r in in_part(claim, key, ev_runs) if r not in runs]
            outcomes.append(Outcome(claim, measured, verdict, runs + extra, part))
    return outcomes


def in_part(claim, key, runs):
    """The runs in the part `key` (from part_keys) of a claim: all of them when the claim has no parts."""
    return list(runs) if key is None else [r for r in runs if part_key(claim, r) == key]
