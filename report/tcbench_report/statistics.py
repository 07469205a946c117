"""Rates and medians over repeats, with the intervals tcbench's C++ side prints for the same runs.

The definitions are those of experiments/statistics/ (wilson_interval.hpp, bootstrap_interval.hpp) and
sim/random/counter_random.hpp, and must stay identical bit for bit, so `tcbench compare`,
configurations.csv and the report agree on every interval:

  mix64(x): SplitMix64's finaliser, all arithmetic mod 2^64:
      x = x + 0x9E3779B97F4A7C15; x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9;
      x = (x ^ (x >> 27)) * 0x94D049BB133111EB; return x ^ (x >> 31).   (mix64(0) = 0xE220A8397B1DCDAF)
  counter_bits(seed, stream, index) = mix64(mix64(mix64(seed) ^ stream) ^ index): a draw depends only on
      its three counters, not on any state or order.
  uniform01(seed, stream, index) = (counter_bits >> 11) * 2**-53, exact in a double, in [0, 1).
  wilson_interval(k, n, z = 1.959963984540054): the Wilson score interval of k outcomes in n runs,
      p = k/n, centre = (p + z^2/2n) / (1 + z^2/n), half = z sqrt(p(1-p)/n + z^2/4n^2) / (1 + z^2/n),
      (centre - half, centre + half) clamped to [0, 1], exactly 0 at k = 0 and 1 at k = n (rounding
      would leave 5.6e-17 there); None for n = 0 (no runs: no rate).
  median(values): the middle value of the sorted values, the mean of the two middle ones for even n.
  bootstrap_median_interval(values, resamples = 2000, seed = BOOTSTRAP_SEED) -> (median, lo, hi):
      resample r (0 .. resamples-1) draws n values, draw j (0 .. n-1) taking
      values[floor(uniform01(seed, r, j) * n)], values in the order given (callers pass repeats sorted by
      seed, so the interval does not depend on the order runs were found in); the resample's median as
      above. With the resample medians sorted, lo = sorted[floor(0.025 R)], hi = sorted[ceil(0.975 R) - 1]
      (R = 2000: entries 50 and 1949): a percentile-bootstrap 95 % interval. Below 2 values
      (median or None, None, None). BOOTSTRAP_SEED = 0x746362656E6368, "tcbench" in ASCII.

A configuration (`configuration`) is everything a run was told except its seed: scene, method label and
settings, budget label, contact response, length and scene overrides (as the C++ side's
configurations.csv groups them). Its runs are repeats (`repeats`, each group sorted by seed), and n is how
many there are: a seed changes a run only through the `[perturb]` jitter it draws, so n counts independent
draws of the initial state. A sweep's noise-floor run (full under perturb.position, pairing.is_noise_floor)
has its own overrides and is never a repeat of the full run.
"""
import math

M64 = (1 << 64) - 1
Z95 = 1.959963984540054
BOOTSTRAP_SEED = 0x746362656E6368  # "tcbench"
RESAMPLES = 2000


def mix64(x):
    x = (x + 0x9E3779B97F4A7C15) & M64
    x = ((x ^ (x >> 30)) * 0xBF58476D1CE4E5B9) & M64
    x = ((x ^ (x >> 27)) * 0x94D049BB133111EB) & M64
    return x ^ (x >> 31)


def counter_bits(seed, stream, index):
    return mix64(mix64(mix64(seed & M64) ^ (stream & M64)) ^ (index & M64))


def uniform01(seed, stream, index):
    return (counter_bits(seed, stream, index) >> 11) * 2.0 ** -53


def wilson_interval(k, n, z=Z95):
    """(lo, hi) of the rate k/n, or None without runs."""
    if n == 0:
        return None
    p, z2 = k / n, z * z
    denominator = 1 + z2 / n
    centre = (p + z2 / (2 * n)) / denominator
    half = z * math.sqrt(p * (1 - p) / n + z2 / (4 * n * n)) / denominator
    return (0.0 if k == 0 else max(0.0, centre - half), 1.0 if k == n else min(1.0, centre + half))


def median(values):
    """The middle value, the mean of the two middle ones for even n; None without values."""
    v = sorted(values)
    n = len(v)
    if not n:
        return None
    return v[n // 2] if n % 2 else 0.5 * (v[n // 2 - 1] + v[n // 2])


def bootstrap_median_interval(values, resamples=RESAMPLES, seed=BOOTSTRAP_SEED):
    """(median, lo, hi): the median and its percentile-bootstrap 95 % interval; lo and hi None below 2
    values (and the median None without any)."""
    values = list(values)
    n = len(values)
    if n < 2 or resamples <= 0:
        return median(values), None, None
    # min(..., n - 1) never bites (uniform01 < 1, and u * n rounds below n); the C++ side has it too.
    medians = sorted(median([values[min(math.floor(uniform01(seed, r, j) * n), n - 1)] for j in range(n)])
                     for r in range(resamples))
    return median(values), medians[math.floor(0.025 * resamples)], medians[math.ceil(0.975 * resamples) - 1]


bootstrap_median = bootstrap_median_interval  # the name the figures were first written with


def summarise(values):
    """(median, lo, hi, n) of the numbers among values (None left out): what a point drawn for a
    configuration's repeats shows."""
    known = [v for v in values if v is not None]
    if not known:
        return None, None, None, 0
    return (*bootstrap_median_interval(known), len(known))


def estimate_text(value, lo, hi, n, fmt="{:.3g}"):
    """'0.12' for one value, 'median 0.12 [0.1, 0.15] (n=5)' for several; 'n/a' without any."""
    if value is None:
        return "n/a"
    if n < 2:
        return fmt.format(value)
    interval = f" [{fmt.format(lo)}, {fmt.format(hi)}]" if lo is not None else ""
    return f"median {fmt.format(value)}{interval} (n={n})"


def rate_text(k, n):
    """'4/5 (80 %, 95 % CI 38-96 %)', or '1/1' for a single run."""
    if n < 2:
        return f"{k}/{n}"
    lo, hi = wilson_interval(k, n)
    return f"{k}/{n} ({100 * k / n:.0f} %, 95 % CI {100 * lo:.0f}-{100 * hi:.0f} %)"


def outcome_text(what, k, n):
    """'standing in 4/5 runs (80 %, 95 % CI 38-96 %)'; 'standing in 1/1 runs' for one run, 'standing in
    0/0 runs (not measured)' for none."""
    if n == 0:
        return f"{what} in 0/0 runs (not measured)"
    if n < 2:
        return f"{what} in {k}/{n} runs"
    lo, hi = wilson_interval(k, n)
    return f"{what} in {k}/{n} runs ({100 * k / n:.0f} %, 95 % CI {100 * lo:.0f}-{100 * hi:.0f} %)"


def configuration(run):
    """What makes runs repeats of each other: everything but the seed (the C++ side's configuration_of in
    experiments/results/run_collection.cpp: scene, method label, settings, budget label, response, mesh order,
    steps requested, overrides; the overrides sorted here, so their order does not split a configuration)."""
    settings = tuple(sorted((k, str(v)) for k, v in (run.record.get("settings") or {}).items()))
    return (run.scene, run.method_label, settings, run.budget_label, run.response, run.mesh_order,
            run.record.get("steps_requested", run.record.get("steps")), tuple(sorted(run.overrides)))


def seed_order(run):
    return (run.seed if run.seed is not None else -1, run.name)


def repeats(runs):
    """[[runs of one configuration, sorted by seed]] in order of first appearance."""
    groups = {}
    for r in runs:
        groups.setdefault(configuration(r), []).append(r)
    return [sorted(g, key=seed_order) for g in groups.values()]


MEDIANS = "each point or bar is their median with its bootstrap 95 % interval"


def runs_note(runs, how=MEDIANS):
    """How many runs each configuration (point, bar) rests on, what a figure draws for repeats (`how`), and
    the jitter that makes the repeats differ."""
    from .pairing import is_noise_floor
    sizes = sorted({len(g) for g in repeats(runs)})
    if not sizes:
        return ""
    if sizes == [1]:
        text = "One run per configuration: each point, bar or curve is a single run (no repeats, no interval)."
    elif len(sizes) == 1:
        text = f"n = {sizes[0]} runs (seeds) per configuration: {how}."
    else:
        text = f"{sizes[0]} to {sizes[-1]} runs (seeds) per configuration; where there are several, {how}."
    jitters = sorted({jitter_text(r) for r in runs if not is_noise_floor(r)} - {""})
    if jitters:
        text += " Initial-state jitter drawn per seed ([perturb], bounds): " + "; ".join(jitters) + "."
    return text


JITTER_KEYS = (("position_m", "position", "m"), ("velocity_m_per_s", "velocity", "m/s"),
               ("rotation_rad", "rotation", "rad"), ("material_rel", "Young's modulus", "relative"))


def jitter_of(run):
    """{key: bound} of the run's [perturb] jitter (run.json perturbation.jitter; where that is all zero, the
    largest effective bound over its bodies), only the non-zero ones; {} when none or not recorded. Older
    run.json files ({position_m, offsets_m}: a noise-floor nudge, or nothing at all) state no jitter."""
    perturbation = run.record.get("perturbation")
    if not isinstance(perturbation, dict) or not isinstance(perturbation.get("jitter"), dict):
        return {}

    def nonzero(jitter):
        return {key: jitter[key] for key, *_ in JITTER_KEYS
                if isinstance(jitter.get(key), (int, float)) and jitter[key]}

    found = nonzero(perturbation["jitter"])
    if not found:
        for body in perturbation.get("bodies") or []:
            for key, value in nonzero((body or {}).get("jitter") or {}).items():
                found[key] = max(found.get(key, 0), value)
    return found


def jitter_text(run):
    """The run's [perturb] jitter in words, 'position +-0.005 m, velocity +-0.1 m/s' ('' when none)."""
    jitter = jitter_of(run)
    return ", ".join(f"{name} +-{jitter[key]:g} {unit}" for key, name, unit in JITTER_KEYS if key in jitter)
