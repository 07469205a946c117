#!/usr/bin/python3
"""tcbench report DIR: the entry point `tcbench report` runs (the package is tcbench_report/).

Run with Debian's Python (its matplotlib): /usr/bin/python3 report/make_report.py DIR
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))  # the package sits beside this file

from tcbench_report.main import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main(sys.argv))
