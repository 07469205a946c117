"""The neural experiment's results (`tcbench neural experiment`): learning.csv, alm.csv and neural.json in one
directory, found anywhere beneath the report's root. Reading only; the figure (figures/neural.py) and the
claims (claims.py) share it."""
import csv
import json
import math
import os
from dataclasses import dataclass, field


@dataclass
class NeuralResults:
    directory: str
    meta: dict
    learning: list = field(default_factory=list)  # rows of learning.csv, numbers parsed
    alm: list = field(default_factory=list)


def number(text):
    if text in ("", None):
        return math.nan
    try:
        return float(text)
    except ValueError:
        return text


def read_rows(path):
    with open(path, newline="") as f:
        return [{k: (v if k in ("preset", "strategy") else number(v)) for k, v in row.items()} for row in csv.DictReader(f)]


def find(root):
    """[NeuralResults] of every directory beneath root holding neural.json and learning.csv, by path."""
    found = []
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames.sort()
        if "neural.json" in filenames and "learning.csv" in filenames and "report" not in os.path.relpath(dirpath, root).split(os.sep):
            with open(os.path.join(dirpath, "neural.json")) as f:
                meta = json.load(f)
            alm = read_rows(os.path.join(dirpath, "alm.csv")) if "alm.csv" in filenames else []
            found.append(NeuralResults(dirpath, meta, read_rows(os.path.join(dirpath, "learning.csv")), alm))
    return found


def final_rows(results, preset):
    """{strategy: [the last round's row of each seed]} for one preset."""
    last = {}
    for row in results.learning:
        if row["preset"] != preset:
            continue
        key = (row["strategy"], row["seed"])
        if key not in last or row["labels"] > last[key]["labels"]:
            last[key] = row
    out = {}
    for (strategy, _), row in sorted(last.items(), key=lambda kv: (kv[0][0], kv[0][1])):
        out.setdefault(strategy, []).append(row)
    return out


def presets(results):
    return sorted({row["preset"] for row in results.learning})


def mean(values):
    values = [v for v in values if isinstance(v, float) and not math.isnan(v)]
    return sum(values) / len(values) if values else math.nan


def compare_final(results, key, better):
    """[(preset, active mean, supervised mean, seeds where active is better, seeds)]: the last round's
    `key` (better: "higher" or "lower"), seed against seed (both strategies share each seed's bootstrap)."""
    out = []
    for preset in presets(results):
        rows = final_rows(results, preset)
        active = {r["seed"]: r[key] for r in rows.get("active", [])}
        supervised = {r["seed"]: r[key] for r in rows.get("supervised", [])}
        seeds = sorted(set(active) & set(supervised))
        wins = sum(1 for s in seeds if (active[s] > supervised[s] if better == "higher" else active[s] < supervised[s]))
        out.append((preset, mean(active[s] for s in seeds), mean(supervised[s] for s in seeds), wins, len(seeds)))
    return out
