"""tcbench_report: figures, summary.md and index.html from a results directory.

Layout (each module small, each with one job):
  paper.py     the citation and every number the report compares against
  loader.py    Run objects (run.json, lazy steps.csv) and sweep membership
  pairing.py   a budgeted run's reference run, and the speed-up between them
  context.py   what figures draw with: saving, provenance footers, Sections
  figures/     one module per figure, discovered from the folder
  claims.py    the paper's claims as a table of records, judged from summaries
  render.py    one document model written as both summary.md and index.html
  main.py      the command line (report/make_report.py calls main)
"""
