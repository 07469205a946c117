"""Rates and medians over repeats, with the intervals tcbench's C++ side prints for the same runs.

The definitions are those of experiments/statistics/ (wilson_interval.hpp,
bootstrap_interval.hpp) and must stay identical, so `tcbench compare`,
configurations.csv and the report agree on every interval:

  counter_bits(seed, stream, index) = mix64(mix64(mix64(seed) ^ stream) ^ index), mix64 SplitMix64's
      finaliser; uniform01 = (counter_bits >> 11) * 2**-53, in [0, 1).
  wilson_interval(k, n): the Wilson score interval at z = 1.959963984540054 (95 %), clamped to [0, 1],
      exactly 0 at k = 0 and 1 at k = n; None for n = 0.
  median: the middle value, the mean of the two middle ones for even n.
  bootstrap_median(values): resample r in 0 .. 1999 takes values[floor(uniform01(SEED, r, j) * n)] for
      j in 0 .. n-1 (values in the caller's order: repeats sorted by seed); the interval is the sorted
      resample medians' entries 50 and 1949. SEED = 0x746362656E6368 ("tcbench"). Below 2 values: none.

A configuration is everything a run was told except its seed (scene, method and its settings, budget
label, response, steps, scene overrides): its runs are repeats, and n is how many there are.
"""
import math

M64 = (1 << 64) - 1
Z95 = 1.959963984540054
BOOTSTRAP_SEED = 0x746362656E6368
RESAMPLES = 2000


def mix64(x):
    x = (x + 0x9E3779B97F4A7C15) & M64
    x = ((x ^ (x >> 30)) * 0xBF58476D1CE4E5B9) & M64
    x = ((x ^ (x >> 27)) * 0x94D049BB133111EB) & M64
    return x ^ (x >> 31)


def counter_bits(seed, stream, index):
    return mix64(mix64(mix64(seed) ^ stream) ^ index)


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
    v = sorted(values)
    n = len(v)
    if not n:
        return None
    return v[n // 2] if n % 2 else 0.5 * (v[n // 2 - 1] + v[n // 2])


def bootstrap_median(values, resamples=RESAMPLES, seed=BOOTSTRAP_SEED):
    """(median, lo, hi); lo and hi None below 2 values."""
    values = list(values)
    n = len(values)
    if n < 2:
        return median(values), None, None
    medians = sorted(median([values[min(int(uniform01(seed, r, j) * n), n - 1)] for j in range(n)])
                     for r in range(resamples))
    return median(values), medians[math.floor(0.025 * resamples)], medians[math.ceil(0.975 * resamples) - 1]


def rate_text(k, n):
    """'4/5 (80 %, 95 % CI 38-96 %)', or '1/1' for a single run."""
    if n < 2:
        return f"{k}/{n}"
    lo, hi = wilson_interval(k, n)
    return f"{k}/{n} ({100 * k / n:.0f} %, 95 % CI {100 * lo:.0f}-{100 * hi:.0f} %)"


def configuration(run):
    """What makes runs repeats of each other: everything but the seed."""
    settings = tuple(sorted((k, str(v)) for k, v in (run.record.get("settings") or {}).items()))
    return (run.scene, run.method_label, settings, run.budget_label, run.response,
            run.record.get("steps_requested", run.record.get("steps")), tuple(sorted(run.overrides)))


def repeats(runs):
    """[[runs of one configuration, sorted by seed]] in order of first appearance."""
    groups = {}
    for r in runs:
        groups.setdefault(configuration(r), []).append(r)
    return [sorted(g, key=lambda r: (r.seed if r.seed is not None else -1, r.name)) for g in groups.values()]


def runs_note(runs):
    """How many runs each configuration rests on, and the jitter that makes the repeats differ."""
    sizes = sorted({len(g) for g in repeats(runs)})
    if not sizes:
        return ""
    if sizes == [1]:
        text = "One run per configuration (no repeats: single observations)."
    elif len(sizes) == 1:
        text = f"n = {sizes[0]} runs (seeds) per configuration; medians with bootstrap 95 % intervals."
    else:
        text = (f"{sizes[0]} to {sizes[-1]} runs (seeds) per configuration; where there are several, medians "
                "with bootstrap 95 % intervals.")
    jitters = sorted({jitter_text(r) for r in runs} - {""})
    if jitters:
        text += " Initial-state jitter drawn per seed: " + "; ".join(jitters) + "."
    return text


JITTER_KEYS = (("position_m", "position", "m"), ("velocity_m_per_s", "velocity", "m/s"),
               ("rotation_rad", "rotation", "rad"), ("material_rel", "Young's modulus", "relative"))


def jitter_text(run):
    """The run's global [perturb] jitter in words ('' when none or not recorded)."""
    perturbation = run.record.get("perturbation") or {}
    jitter = perturbation.get("jitter") or ({"position_m": perturbation.get("position_m")}
                                           if "position_m" in perturbation else {})
    parts = [f"{name} +-{jitter[key]:g} {unit}" for key, name, unit in JITTER_KEYS if jitter.get(key)]
    return ", ".join(parts)
