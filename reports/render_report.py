#!/usr/bin/env python3
"""Draws REPORT.md and charts/*.png of a corofem report folder from its JSON records alone, and
for papers every table as LaTeX (tables/*.tex, booktabs; tables/all.tex compiles them) and every
chart as PDF and SVG (charts/vector/).

Usage: render_report.py DIR [--blank-times] [--age]
       render_report.py --units        (the units and the records each reads, as JSON)

Each part of REPORT.md is a unit: a module of reports/sections/ (and of every folder in
$COROFEM_REPORT_SECTIONS, separated by ':', for a user's own sections) that defines
  ORDER           where its part goes (the built-ins at 10, 20, ... 70),
  RECORDS         the record files it reads (absent ones are passed as None),
  REPORT_SECTION  True when its first record is written by a `corofem report` section,
  render(records, folder, md)  which appends its Markdown to md and saves its charts.
Modules whose names start with '_' are helpers, not units.
--blank-times prints every time, rate and date as "t" (the golden test of the report's format
compares text that does not depend on the machine's speed). --age adds how many commits the
records' commit is behind this checkout's HEAD (git's answer, not the records': off by default,
so that a report redrawn from its JSON is the same text).
"""
import importlib
import importlib.util
import json
import os
import pkgutil
import subprocess
import sys
import tempfile

import latex_tables
import render_common
import sections
from render_common import HAVE_MPL, load


def _own_units(folder):
    """A user's units: every public module of `folder`, loaded by path."""
    out = []
    for name in sorted(os.listdir(folder)):
        if name.endswith(".py") and not name.startswith("_"):
            spec = importlib.util.spec_from_file_location(f"user_section_{name[:-3]}",
                                                          os.path.join(folder, name))
            module = importlib.util.module_from_spec(spec)
            spec.loader.exec_module(module)
            out.append(module)
    return out


def units():
    """Every unit, in the order of REPORT.md."""
    found = [importlib.import_module(f"sections.{m.name}")
             for m in pkgutil.iter_modules(sections.__path__) if not m.name.startswith("_")]
    for folder in filter(None, os.environ.get("COROFEM_REPORT_SECTIONS", "").split(":")):
        found += _own_units(folder)
    for unit in found:
        if not (isinstance(getattr(unit, "ORDER", None), int) and getattr(unit, "RECORDS", None)
                and callable(getattr(unit, "render", None))):
            raise SystemExit(f"render: {unit.__file__} is not a unit (it needs ORDER, RECORDS and "
                             "render(records, folder, md))")
    return sorted(found, key=lambda u: (u.ORDER, u.__name__))


def age_line(records):
    """Where the records' commit is behind this checkout's: a snapshot drawn again later says how
    old it is ("" where the records are of this commit, or git cannot tell)."""
    commit = next((r["context"].get("commit") for r in records.values()
                   if isinstance(r, dict) and isinstance(r.get("context"), dict)
                   and r["context"].get("commit")), None)
    if not commit or render_common.blanked():
        return ""
    commit = commit.removesuffix("-dirty")
    here = os.path.dirname(os.path.abspath(__file__))
    try:
        behind = subprocess.run(["git", "rev-list", "--count", f"{commit}..HEAD"], cwd=here,
                                capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return ""
    if behind in ("", "0"):
        return ""
    return (f"**These records are of commit `{commit[:9]}`, {behind} commits behind this "
            "checkout's HEAD**: the code has moved since they were made.\n\n")


def record_files(all_units):
    return list(dict.fromkeys(name for u in all_units for name in u.RECORDS))


def write_atomically(folder, text):
    fd, tmp = tempfile.mkstemp(dir=folder, suffix=".md")
    with os.fdopen(fd, "w") as f:
        f.write(text)
    os.chmod(tmp, 0o644)
    os.replace(tmp, os.path.join(folder, "REPORT.md"))


def main(argv):
    all_units = units()
    if argv[1:] == ["--units"]:
        print(json.dumps([{"unit": u.__name__.removeprefix("sections."), "order": u.ORDER,
                           "records": list(u.RECORDS), "report_section": getattr(u, "REPORT_SECTION", False)}
                          for u in all_units], indent=1))
        return 0
    args = [a for a in argv[1:] if a not in ("--blank-times", "--age")]
    render_common.set_blank("--blank-times" in argv)
    if len(args) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    folder = args[0]
    records = {name: load(folder, name) for name in record_files(all_units)}
    primary = [u.RECORDS[0] for u in all_units if getattr(u, "REPORT_SECTION", False)]
    if not any(records[name] for name in primary):
        print(f"render: none of {', '.join(primary)} in {folder}", file=sys.stderr)
        return 2
    md = ["# corofem report\n\n",
          "Drawn by reports/render_report.py from the JSON records in this folder alone; every "
          "number below is in them, with the commit, flags and machine that produced it.\n\n"]
    if not HAVE_MPL:
        md.append("(matplotlib was not available: no charts drawn.)\n\n")
    if "--age" in argv:
        md.append(age_line(records))
    for unit in all_units:
        unit.render(records, folder, md)
    text = "".join(md)
    write_atomically(folder, text)
    tables = latex_tables.write_tables(text, folder)
    print(f"render: wrote {os.path.join(folder, 'REPORT.md')}, its {len(tables)} tables as LaTeX "
          f"in tables/ and its charts as PNG, PDF and SVG in charts/", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
