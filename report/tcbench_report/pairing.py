"""A budgeted run's reference: the same experiment handled fully, without a budget.

Written once here because the speed-up figure, the claims and the jitter
comparison all need it and must agree on it. The speed-up is the handling
time's (what the paper claims) or the whole step's (handling + dynamics).
"""
from .loader import mesh_order_override, response_override

REFERENCE_METHOD = "full"  # the registry's exhaustive baseline


PERTURB_PREFIX = "perturb."  # a noise-floor run's overrides: perturb.position=1e-09


def perturbation_override(override):
    """True for an override that perturbs the initial state (`perturb.position=...`): what makes a noise-floor
    run, not a different experiment."""
    return override.partition("=")[0].strip().startswith(PERTURB_PREFIX)


def setup(run):
    """What makes two runs the same experiment: scene, RNG seed, contact response, mesh order and scene
    overrides.

    Overrides are scene-only in tcbench.run/2 (method settings moved to
    "settings"), so their order is the only thing to normalise. The response
    mode (implicit or explicit penalty contact) is the run's recorded one
    (explicit for runs older than the field); the `collision.response=...`
    override that chose it is folded into it, so a run that sets it explicitly
    and an older run that was explicit without saying so are one experiment. The same for the mesh order: a
    `scene.mesh_order=...` override is folded into the recorded one (legends would otherwise name it twice).
    """
    overrides = tuple(sorted(o for o in run.overrides if response_override(o) is None and not mesh_order_override(o)))
    return run.scene, run.seed, run.response, run.mesh_order, overrides


def is_reference(run):
    """full with every setting at its default (method_label "full": keep_table is ours) and no budget."""
    return run.method_label == REFERENCE_METHOD and run.budget_kind == "none"


def closest(run, candidates):
    """The candidate best matching run: one from the same sweep first, then one of the same length."""
    candidates = sorted(candidates, key=lambda r: (not (r.sweeps & run.sweeps), r.record.get("steps") !=
                                                   run.record.get("steps"), r.name))
    return candidates[0] if candidates else None


def reference(run, runs):
    """The reference run for run among runs, or None. Prefers one from the same sweep."""
    if is_reference(run):
        return None
    key = setup(run)
    return closest(run, [r for r in runs if is_reference(r) and setup(r) == key])


def counterpart(run, runs, method):
    """The run of `method` (registry name) in the same experiment under the same budget, or None:
    what an ablation is compared with."""
    key = setup(run)
    return closest(run, [r for r in runs if r.method == method and setup(r) == key
                         and r.budget_kind == run.budget_kind and r.budget_label == run.budget_label])


HANDLING = "handling_ms"  # collision handling per step: what the paper's speed-up is about
STEP = "step_ms"          # the whole step a user pays: handling + dynamics (the implicit contact solve included)


def speedup(run, ref, stat="p50", key=HANDLING):
    """The reference's time per step over the run's, both as the statistic `stat` of summary.<key>
    (p50: the median, what a budget "full/K" divides; p99: what a deadline sees); key is handling_ms
    (collision handling) or step_ms (the whole step). None when either is missing or 0, as for runs
    recorded before the summary had the key."""
    if ref is None:
        return None
    full, mine = ref.metric(f"{key}.{stat}"), run.metric(f"{key}.{stat}")
    return full / mine if full and mine else None


def step_speedup(run, ref, stat="p50"):
    """The same ratio for the whole step (summary.step_ms): what the handling speed-up is worth to the
    application; None for runs without step_ms."""
    return speedup(run, ref, stat, STEP)


def budgeted_with_reference(runs, all_runs):
    """[(run, reference, median speed-up)] for every budgeted run in runs that has a reference."""
    rows = []
    for run in runs:
        if run.budget_kind == "none":
            continue
        ref = reference(run, all_runs)
        ratio = speedup(run, ref)
        if ratio is not None:
            rows.append((run, ref, ratio))
    return rows


# ---------------------------------------------------------------- the divergence noise floor

DIVERGENCE = "divergence.rms_m.final"  # the divergence a figure and the claims compare with the floor


def is_noise_floor(run):
    """A noise-floor run: full, no budget, its initial positions nudged (an override `perturb.position=...`)
    and compared with the full run (it has a summary divergence: full's own under that nudge). A full run
    whose repeats are jittered (`perturb.*` in a sweep's sets, no divergence) is a reference, not a floor."""
    return (is_reference(run) and run.metric("divergence.compared_steps") is not None
            and any(o.partition("=")[0].strip() == PERTURB_PREFIX + "position" for o in run.overrides))


def floor_setup(run):
    """setup(run) with the perturbation left out: the experiment a noise-floor run is the floor of. The
    floor run's other overrides (the scene's --set strings) stay and must match."""
    scene, seed, response, mesh_order, overrides = setup(run)
    return scene, seed, response, mesh_order, tuple(o for o in overrides if not perturbation_override(o))


def noise_floor(run, runs):
    """The noise-floor run of run's experiment (same scene, seed, response and other overrides) among runs,
    compared up to the same step (summary divergence.last_step, where both have one), or None. Prefers one
    from the same sweep. A floor run has no floor of its own."""
    if is_noise_floor(run):
        return None
    key, last = floor_setup(run), run.metric("divergence.last_step")
    return closest(run, [r for r in runs if is_noise_floor(r) and floor_setup(r) == key
                         and (last is None or r.metric("divergence.last_step") in (None, last))])


def floor_multiple(run, floor, key=DIVERGENCE):
    """The run's summary `key` over its noise floor's (how many floors it diverged), or None when either is
    missing or the floor is 0."""
    if floor is None:
        return None
    mine, theirs = run.metric(key), floor.metric(key)
    return mine / theirs if mine is not None and theirs else None
