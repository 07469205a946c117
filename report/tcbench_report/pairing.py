"""A budgeted run's reference: the same experiment handled fully, without a budget.

Written once here because the speed-up figure, the claims and the jitter
comparison all need it and must agree on it.
"""
from .loader import response_override

REFERENCE_METHOD = "full"  # the registry's exhaustive baseline


def setup(run):
    """What makes two runs the same experiment: scene, RNG seed, contact response and scene overrides.

    Overrides are scene-only in tcbench.run/2 (method settings moved to
    "settings"), so their order is the only thing to normalise. The response
    mode (implicit or explicit penalty contact) is the run's recorded one
    (explicit for runs older than the field); the `collision.response=...`
    override that chose it is folded into it, so a run that sets it explicitly
    and an older run that was explicit without saying so are one experiment.
    """
    overrides = tuple(sorted(o for o in run.overrides if response_override(o) is None))
    return run.scene, run.seed, run.response, overrides


def is_reference(run):
    return run.method == REFERENCE_METHOD and run.budget_kind == "none"


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


def speedup(run, ref, stat="p50"):
    """The reference's handling time over the run's, both as the statistic `stat` of summary.handling_ms
    (p50: the median, what a budget "full/K" divides; p99: what a deadline sees), or None when either
    is missing or 0."""
    if ref is None:
        return None
    full, mine = ref.metric(f"handling_ms.{stat}"), run.metric(f"handling_ms.{stat}")
    return full / mine if full and mine else None


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
