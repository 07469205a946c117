"""Results on disk -> Run objects, and which figures each run's sweeps declare.

A results directory holds run folders (run.json + steps.csv) at any depth and,
for every sweep written into it, a sweep.json naming its runs and the
scene-specific figures they feed. Nothing here interprets scenes or methods:
figures and claims select runs by what the run summaries contain.
"""
import csv
import json
import os
import re
from dataclasses import dataclass, field

SKIP_DIRS = ("report", "frames")  # our own output and ParaView frames: never results

RESPONSE_KEY = "collision.response"  # the scene key choosing implicit or explicit penalty contact
RESPONSE_BEFORE_FIELD = "explicit"   # runs recorded before run.json had "response" integrated explicitly
RESPONSE_ORDER = ("implicit", "explicit")  # the default first, wherever modes are listed
BUDGET_KIND_ORDER = {"none": 0, "wall_ms": 1, "work": 2}


def response_override(override):
    """The mode a `collision.response=...` override sets, or None for any other override."""
    key, _, value = override.partition("=")
    return value.strip().strip("'\"") if key.strip() == RESPONSE_KEY else None


MESH_ORDER_KEY = "scene.mesh_order"  # the scene key renumbering vertices; run.json records its effect


def mesh_order_override(override):
    """True for a `scene.mesh_order=...` override: the run's recorded world.mesh_order already says it."""
    return override.partition("=")[0].strip() == MESH_ORDER_KEY


def response_order(mode):
    return (RESPONSE_ORDER.index(mode) if mode in RESPONSE_ORDER else len(RESPONSE_ORDER), mode)


def relative_divisor(label):
    """K of a relative budget label "full/K" or "full-work/K", else None."""
    match = re.fullmatch(r"full(?:-work)?/([0-9.]+)", label or "")
    try:
        return float(match.group(1)) if match else None
    except ValueError:
        return None


class Run:
    """One complete run: run.json eagerly, steps.csv only when a figure asks."""

    def __init__(self, directory, record, name):
        self.dir = directory
        self.name = name  # path relative to the results directory: unique across sweeps
        self.record = record
        self.summary = record.get("summary") or {}
        self.figures = set()  # scene-specific figures declared by this run's sweeps
        self.sweeps = set()   # names of the sweeps that list this run
        self._steps = None

    scene = property(lambda self: self.record.get("scene", ""))
    method = property(lambda self: self.record.get("method", ""))
    status = property(lambda self: self.record.get("status", ""))
    seed = property(lambda self: self.record.get("seed"))
    # tcbench.run/1 lacked settings and method_label: fall back to the bare method.
    settings = property(lambda self: self.record.get("settings") or {})
    method_label = property(lambda self: self.record.get("method_label") or self.method)
    overrides = property(lambda self: tuple(self.record.get("overrides") or ()))
    budget = property(lambda self: self.record.get("budget") or {})
    budget_kind = property(lambda self: self.budget.get("kind") or "none")
    budget_value = property(lambda self: self.budget.get("value"))
    budget_label = property(lambda self: self.budget.get("label") or "none")
    # How the simulation numbered the meshes' vertices (world.mesh_order): "curve" renumbers them, which
    # changes results in rounding and tie-breaks; runs recorded before the field were in the file's order.
    mesh_order = property(lambda self: (self.record.get("world") or {}).get("mesh_order") or "file")

    @property
    def response(self):
        """"implicit" or "explicit": how the run integrated penalty contact. run.json records it since
        the option exists; an older run has no field and was explicit."""
        mode = self.record.get("response")
        if isinstance(mode, str) and mode:
            return mode
        for o in self.overrides:
            if response_override(o):
                return response_override(o)
        return RESPONSE_BEFORE_FIELD

    @property
    def response_recorded(self):
        return isinstance(self.record.get("response"), str)

    @property
    def timing(self):
        """"quiet" or "noisy": the run's timing verdict (summary.timing.verdict); None for runs older
        than the verdict. A noisy run's wall-clock numbers are partly the scheduler's."""
        verdict = ((self.summary or {}).get("timing") or {}).get("verdict")
        return verdict if verdict in ("quiet", "noisy") else None

    def budget_order(self):
        """Sort key: no budget, then wall, then work; relative budgets from the largest (full/2 before
        full/10), then absolute ones from the largest."""
        k = relative_divisor(self.budget_label)
        value = self.budget_value if isinstance(self.budget_value, (int, float)) else 0
        return (BUDGET_KIND_ORDER.get(self.budget_kind, 3), k is None, k if k is not None else -value,
                self.budget_label)

    def label(self):
        """Legend text: the method with its non-default settings, and the budget."""
        return self.method_label if self.budget_kind == "none" else f"{self.method_label} @ {self.budget_label}"

    def metric(self, dotted):
        """A number from the summary ("handling_ms.p50"), or None when absent or null."""
        node = self.summary
        for key in dotted.split("."):
            if not isinstance(node, dict) or key not in node:
                return None
            node = node[key]
        return node if isinstance(node, (int, float)) and not isinstance(node, bool) else None

    def dynamic_tets(self):
        """Tetrahedra of the objects that change shape (integrated, or driven through a latent path): the size a
        scaling figure plots against."""
        objects = (self.record.get("world") or {}).get("objects") or []
        return sum(o.get("tets", 0) for o in objects if not o.get("passive") or o.get("latent"))

    def has_frames(self):
        return os.path.exists(os.path.join(self.dir, "frames.pvd"))

    def steps(self):
        """steps.csv as {column: [float or None]}; {} when the file is missing or unreadable."""
        if self._steps is None:
            self._steps = read_steps(os.path.join(self.dir, "steps.csv"))
        return self._steps


def read_steps(path):
    cols = {}
    try:
        with open(path, newline="") as f:
            reader = csv.reader(f)
            names = next(reader, [])
            cols = {n: [] for n in names}
            for row in reader:
                if len(row) != len(names):
                    break  # a truncated last line: keep what is whole
                for n, v in zip(names, row):
                    cols[n].append(to_float(v))
    except (OSError, UnicodeDecodeError):
        return {}
    return cols


def to_float(text):
    try:
        return float(text) if text != "" else None
    except ValueError:
        return None


@dataclass
class Sweep:
    name: str
    dir: str
    description: str
    figures: list
    runs: list  # absolute run directories


@dataclass
class Results:
    root: str
    runs: list = field(default_factory=list)
    sweeps: list = field(default_factory=list)
    skipped: list = field(default_factory=list)  # (path, why): shown in the report, never drawn


def load(root):
    """Every complete run and every sweep.json beneath root, runs sorted by name."""
    results = Results(root)
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = sorted(d for d in dirnames if d not in SKIP_DIRS)
        if "run.json" in filenames:
            run, why = read_run(root, dirpath)
            if run:
                results.runs.append(run)
            else:
                results.skipped.append((os.path.relpath(os.path.join(dirpath, "run.json"), root), why))
        if "sweep.json" in filenames:
            sweep, why = read_sweep(dirpath)
            if sweep:
                results.sweeps.append(sweep)
            else:
                results.skipped.append((os.path.relpath(os.path.join(dirpath, "sweep.json"), root), why))
    results.runs.sort(key=lambda r: r.name)
    attach_sweeps(results)
    return results


def load_json(path):
    """The parsed file, or None when it cannot be read or is not JSON."""
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, UnicodeDecodeError, ValueError):
        return None


def read_run(root, directory):
    record = load_json(os.path.join(directory, "run.json"))
    if record is None:
        return None, "not valid JSON (still being written, or cut short)"
    if not isinstance(record, dict) or not isinstance(record.get("summary"), dict):
        return None, "no summary (the run did not finish)"
    return Run(directory, record, os.path.relpath(directory, root)), None


def read_sweep(directory):
    record = load_json(os.path.join(directory, "sweep.json"))
    if record is None:
        return None, "not valid JSON"
    if not isinstance(record, dict) or not isinstance(record.get("runs"), list):
        return None, "no list of runs"
    # The sweep's name is its file's stem (experiments/sweeps/paper/1_stack.toml -> 1_stack);
    # a hand-written sweep.json without a file is named after its folder.
    source = record.get("file") or os.path.abspath(directory)
    name = os.path.splitext(os.path.basename(source.rstrip("/")))[0]
    runs = [os.path.normpath(os.path.join(directory, p)) for p in record["runs"] if isinstance(p, str)]
    figures = [f for f in record.get("figures") or [] if isinstance(f, str)]
    return Sweep(name, directory, record.get("description") or "", figures, runs), None


def attach_sweeps(results):
    """Give each run the figures and names of every sweep that lists it."""
    by_dir = {os.path.realpath(r.dir): r for r in results.runs}
    for sweep in results.sweeps:
        for path in sweep.runs:
            run = by_dir.get(os.path.realpath(path))
            if run:  # a listed run that failed or is still running is simply absent
                run.figures.update(sweep.figures)
                run.sweeps.add(sweep.name)
