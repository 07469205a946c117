"""The report's figures: every module in this folder not starting with "_".

A figure module's file stem is its name (sweep files list it in `figures =
[...]`, and tcbench checks those names against this folder). Each module
defines:

  TITLE  the section title
  ORDER  where it goes in the report (ascending; ties by name)
  SCOPE  "all": drawn from every run (generic figures), or
         "declared": drawn from the runs of the sweeps that list the figure
  draw(ctx, runs) -> Section, or a list of Sections
         runs are the runs in scope; ctx is a context.Context (save, missing,
         reference, runs). Return ctx.missing(TITLE, why) when there is nothing
         to draw.

Adding a figure is adding one file here.
"""
import importlib
import pkgutil

SCOPES = ("all", "declared")


def discover():
    """[(name, module)] of every figure module, in report order."""
    found = []
    for info in pkgutil.iter_modules(__path__):
        if info.name.startswith("_"):
            continue
        module = importlib.import_module(f"{__name__}.{info.name}")
        if getattr(module, "SCOPE", None) not in SCOPES or not callable(getattr(module, "draw", None)):
            raise TypeError(f"figure module {info.name}: needs SCOPE in {SCOPES} and draw(ctx, runs)")
        found.append((info.name, module))
    found.sort(key=lambda item: (getattr(item[1], "ORDER", 1000), item[0]))
    return found


def runs_in_scope(name, module, runs):
    """The runs a figure draws from: all of them, or those whose sweeps declare it."""
    return list(runs) if module.SCOPE == "all" else [r for r in runs if name in r.figures]
