"""One document, two files: summary.md and index.html from the same list of blocks.

The report is built once as blocks (headings, paragraphs, tables, figure
sections); each writer only knows how to spell a block, so the two files
cannot drift apart.
"""
import html
import os
import tempfile
from dataclasses import dataclass

from .context import provenance
from .loader import response_order
from .claims import UNMEASURED as NOT_MEASURED
from .paper import PAPER_CITATION


@dataclass
class Heading:
    level: int
    text: str


@dataclass
class Para:
    text: str


@dataclass
class Table:
    header: list
    rows: list
    verdict_column: int = None  # coloured in HTML: held or not


@dataclass
class Figure:
    section: object  # context.Section


def count(items, noun):
    return f"{len(items)} {noun}{'' if len(items) == 1 else 's'}"


def fmt(value):
    return "" if value is None else f"{value:.4g}"


RUN_COLUMNS = (("handling p50 (ms)", "handling_ms.p50"), ("handling p99 (ms)", "handling_ms.p99"),
               ("recall mean", "recall_mean"), ("recall min", "recall_min"), ("max depth (m)", "max_depth"),
               ("depth error mean (m)", "depth_err.mean"), ("self-collision depth error mean (m)", "self_depth_err.mean"),
               ("jitter RMS (m/s)", "jitter"), ("settled max speed p50 (m/s)", "settled_max_speed_median"),
               ("settled kinetic energy mean (J)", "settled_kinetic_energy.mean"),
               ("probe force change RMS (N/step)", "probe_force_change_rms"), ("tunnelling", "tunneling"))


def document(results, sections, outcomes, notes):
    """The report as blocks."""
    runs = results.runs
    blocks = [Heading(1, "tcbench report"),
              Para(f"Results: {os.path.abspath(results.root)}, {count(runs, 'run')}, {count(results.sweeps, 'sweep')}; "
                   f"{provenance(runs)}.")]
    if results.skipped:
        blocks.append(Para("Skipped (incomplete or unreadable): "
                           + "; ".join(f"{path}: {why}" for path, why in results.skipped) + "."))
    blocks += [Heading(2, "Claims of the paper"), Para(f"[1] {PAPER_CITATION.rstrip('.')}."),
               Para("Claims about resting contact are judged once per contact response (implicit or explicit "
                    "penalty contact, the scene's collision.response; runs recorded before the option count as "
                    "explicit), so a verdict that differs between the two rows is the integrator's, not the "
                    "collision handling's. \"ours\" in a row marks a threshold of ours, listed in the last column."),
               Table(["claim", "the paper [1]", "here", "verdict", "thresholds of ours (not the paper's)"],
                     [[o.text, o.claim.paper, o.measured, o.verdict, "; ".join(o.claim.ours)]
                      for o in outcomes], verdict_column=3),
               Heading(2, "Figures")]
    blocks += [Figure(s) for s in sections]
    blocks += [Para(n) for n in notes]
    blocks += [Heading(2, "Runs"),
               Table(["run", "scene", "method", "budget", "response", "status"] + [name for name, _ in RUN_COLUMNS],
                     [[r.name, r.scene, r.method_label, r.budget_label, r.response, r.status]
                      + [fmt(r.metric(key)) for _, key in RUN_COLUMNS]
                      for r in sorted(runs, key=lambda r: (r.scene, r.method_label, r.budget_order(),
                                                           response_order(r.response), r.name))])]
    return blocks


def sources(section):
    return f"Runs: {', '.join(r.name for r in section.runs)}; {provenance(section.runs)}."


# ---------------------------------------------------------------- Markdown

def md_cell(text):
    return str(text).replace("|", "\\|").replace("\n", " ")


def markdown(blocks):
    out = []
    for b in blocks:
        if isinstance(b, Heading):
            out += ["#" * b.level + " " + b.text, ""]
        elif isinstance(b, Para):
            out += [b.text, ""]
        elif isinstance(b, Table):
            out.append("| " + " | ".join(md_cell(h) for h in b.header) + " |")
            out.append("|" + "---|" * len(b.header))
            out += ["| " + " | ".join(md_cell(c) for c in row) + " |" for row in b.rows]
            out.append("")
        elif isinstance(b, Figure):
            s = b.section
            out += [f"### {s.title}", ""]
            if s.image:
                out += [f"![{s.title}]({s.image})", ""]
            out += [s.text, ""]
            if s.runs:
                out += [sources(s), ""]
    return "\n".join(out)


# ---------------------------------------------------------------- HTML

STYLE = ("body{font-family:sans-serif;max-width:1100px;margin:auto}img{max-width:100%}"
         "table{border-collapse:collapse;font-size:13px}td,th{border:1px solid #ccc;padding:3px 6px}"
         ".no{color:#b00}.yes{color:#080}.part{color:#a60}.src{color:#666;font-size:12px}")


def page(blocks):
    e = html.escape
    out = ["<!doctype html><html><head><meta charset='utf-8'><title>tcbench report</title>",
           f"<style>{STYLE}</style></head><body>"]
    for b in blocks:
        if isinstance(b, Heading):
            out.append(f"<h{b.level}>{e(b.text)}</h{b.level}>")
            if b.level == 1:
                out.append("<p>Also: <a href='summary.md'>summary.md</a>.</p>")
        elif isinstance(b, Para):
            out.append(f"<p>{e(b.text)}</p>")
        elif isinstance(b, Table):
            out.append("<table><tr>" + "".join(f"<th>{e(h)}</th>" for h in b.header) + "</tr>")
            for row in b.rows:
                cells = []
                for k, c in enumerate(row):
                    cls = ""
                    if k == b.verdict_column and c != NOT_MEASURED:
                        cls = (" class='yes'" if str(c).startswith("holds") and "inconclusive" not in str(c) else
                               " class='part'" if str(c).startswith(("partly", "holds", "inconclusive", "mixed",
                                                                     "undecided"))
                               else " class='no'")
                    cells.append(f"<td{cls}>{e(str(c))}</td>")
                out.append("<tr>" + "".join(cells) + "</tr>")
            out.append("</table>")
        elif isinstance(b, Figure):
            s = b.section
            out.append(f"<h3>{e(s.title)}</h3>")
            if s.image:
                img = f"<img src='{e(s.image)}' alt='{e(s.title)}'>"
                out.append(f"<a href='{e(s.vector)}'>{img}</a>" if s.vector else img)
            out.append(f"<p>{e(s.text)}</p>")
            if s.runs:
                out.append(f"<p class='src'>{e(sources(s))}</p>")
    out.append("</body></html>")
    return "\n".join(out)


def write_atomically(path, text):
    """Readers never see half a file: write beside it, then rename."""
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(path), suffix=".tmp")
    with os.fdopen(fd, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def write(out_dir, blocks):
    write_atomically(os.path.join(out_dir, "summary.md"), markdown(blocks) + "\n")
    write_atomically(os.path.join(out_dir, "index.html"), page(blocks) + "\n")
