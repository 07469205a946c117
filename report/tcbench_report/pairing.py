"""A budgeted run's reference: the same experiment handled fully, without a budget.

Written once here because the speed-up figure, the claims and the jitter
comparison all need it and must agree on it.
"""

REFERENCE_METHOD = "full"  # the registry's exhaustive baseline


def setup(run):
    """What makes two runs the same experiment: scene, RNG seed and scene overrides.

    Overrides are scene-only in tcbench.run/2 (method settings moved to
    "settings"), so their order is the only thing to normalise.
    """
    return run.scene, run.seed, tuple(sorted(run.overrides))


def is_reference(run):
    return run.method == REFERENCE_METHOD and run.budget_kind == "none"


def reference(run, runs):
    """The reference run for run among runs, or None. Prefers one from the same sweep."""
    if is_reference(run):
        return None
    key = setup(run)
    candidates = [r for r in runs if is_reference(r) and setup(r) == key]
    candidates.sort(key=lambda r: (not (r.sweeps & run.sweeps), r.name))
    return candidates[0] if candidates else None


def speedup(run, ref):
    """Median handling time of the reference over the run's, or None when either is missing."""
    if ref is None:
        return None
    full, mine = ref.metric("handling_ms.p50"), run.metric("handling_ms.p50")
    return full / mine if full and mine else None


def budgeted_with_reference(runs, all_runs):
    """[(run, reference, speed-up)] for every budgeted run in runs that has a reference."""
    rows = []
    for run in runs:
        if run.budget_kind == "none":
            continue
        ref = reference(run, all_runs)
        ratio = speedup(run, ref)
        if ratio is not None:
            rows.append((run, ref, ratio))
    return rows
