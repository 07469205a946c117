"""What a figure draws with: where to save, how to sign a figure, what a section is."""
import os
from dataclasses import dataclass, field

import matplotlib

matplotlib.use("Agg")  # files only: no display on a build machine
import matplotlib.pyplot as plt  # noqa: E402

from . import pairing, statistics  # noqa: E402

FOOTER_CHARS_PER_INCH = 22  # about that many 6 pt characters fit in an inch
FOOTER_LINE_INCHES = 0.1


@dataclass
class Section:
    """One figure's entry in the report, drawn or not."""
    title: str
    caption: str
    runs: list = field(default_factory=list)  # the runs it was drawn from
    image: str = None    # path relative to the report folder, or None when not drawn
    vector: str = None   # the SVG of the same figure, when there is one
    missing: str = None  # why it was not drawn

    @property
    def text(self):
        return f"Not drawn: {self.missing}" if self.missing else self.caption


def provenance(runs):
    """The builds and machines runs came from, in one line."""
    def build(r):
        b = r.record.get("build") or {}
        return f"{str(b.get('git_sha') or '?')[:10]}{'+dirty' if b.get('dirty') else ''}"

    def machine(r):
        m = r.record.get("machine") or {}
        return f"{m.get('cpu', '?')} x{m.get('cores', '?')}"

    if not runs:
        return "no runs"
    builds, machines = sorted({build(r) for r in runs}), sorted({machine(r) for r in runs})
    return f"build {', '.join(builds)}; machine {', '.join(machines)}"


def unique(runs):
    """runs without repeats, in first-seen order (a reference serves several budgeted runs)."""
    seen = set()
    return [r for r in runs if not (r.name in seen or seen.add(r.name))]


def wrap(text, width):
    lines, line = [], ""
    for word in text.split():
        if line and len(line) + len(word) + 1 > width:
            lines.append(line)
            line = word
        else:
            line = f"{line} {word}".strip()
    return lines + [line]


MAX_NAMED_RUNS = 24  # a figure's footer names its runs up to this many


class Context:
    """Shared by all figures of one report: the output folder and every loaded run."""

    def __init__(self, results, out_dir):
        self.results = results
        self.out = out_dir
        self.fig_dir = os.path.join(out_dir, "figures")
        os.makedirs(self.fig_dir, exist_ok=True)

    @property
    def runs(self):
        return self.results.runs

    def reference(self, run):
        # Searched among all runs: a reference may sit in another sweep than the run.
        return pairing.reference(run, self.runs)

    def sign(self, fig, title, runs):
        """Write the title, runs, build and machine under the plot, and lay out around it."""
        # Past a few dozen runs (seeds of a sweep) their names would bury the plot: count them instead;
        # the report's page lists every one under the figure.
        names = (", ".join(r.name for r in runs) if len(runs) <= MAX_NAMED_RUNS else
                 f"{len(runs)} runs in {len(statistics.repeats(runs))} configurations, listed in the report")
        text = f"{title}. Runs: {names}. {provenance(runs)}."
        width_in, height_in = fig.get_size_inches()
        lines = wrap(text, int(width_in * FOOTER_CHARS_PER_INCH))
        fig.text(0.01, 0.005, "\n".join(lines), fontsize=6, va="bottom", ha="left", color="0.35")
        reserved = min(0.5, (len(lines) * FOOTER_LINE_INCHES + 0.05) / height_in)
        fig.tight_layout(rect=(0, reserved, 1, 1))

    def write_figure(self, name, write):
        """Call write(path) with a temporary path beside figures/NAME (same extension, so matplotlib picks the
        format), then rename it into place: an interrupted report leaves no half-written figure."""
        final = os.path.join(self.fig_dir, name)
        stem, ext = os.path.splitext(name)
        tmp = os.path.join(self.fig_dir, f".{stem}.tmp{ext}")
        try:
            write(tmp)
            os.replace(tmp, final)
        finally:
            if os.path.exists(tmp):
                os.remove(tmp)
        return final

    def save(self, fig, stem, title, caption, runs, repeats=statistics.MEDIANS):
        """Sign fig, write it as PNG and SVG, and return its Section. The caption gains how many runs each
        configuration rests on, what the figure draws for repeats (`repeats`) and the jitter the seeds drew."""
        runs = unique(runs)
        note = statistics.runs_note(runs, repeats)
        caption = f"{caption} {note}".strip() if note else caption
        self.sign(fig, title, runs)
        for ext in ("png", "svg"):
            self.write_figure(f"{stem}.{ext}", lambda path: fig.savefig(path, dpi=110))
        plt.close(fig)
        return Section(title, caption, runs, image=f"figures/{stem}.png", vector=f"figures/{stem}.svg")

    def missing(self, title, why):
        return Section(title, "", [], missing=why)
