#!/usr/bin/env python3
"""Fails when a page of the documentation (README.md, lib/README.md, lib/docs/*.md, the READMEs of
bench/ and reports/) is longer than 300 lines: a reader who needs more is served by two pages with
a link between them."""
import sys
from pathlib import Path

LIMIT = 300
ROOT = Path(__file__).resolve().parent.parent


def main():
    pages = [ROOT / "README.md", ROOT / "lib" / "README.md", *sorted((ROOT / "lib" / "docs").glob("*.md")),
             *sorted(ROOT.glob("bench/**/README.md")), ROOT / "reports" / "README.md"]
    long = [(len(p.read_text(encoding="utf-8").splitlines()), p.relative_to(ROOT))
            for p in pages if p.exists()]
    long = [(n, p) for n, p in long if n > LIMIT]
    for n, p in long:
        print(f"{p}: {n} lines (limit {LIMIT})", file=sys.stderr)
    return 1 if long else 0


if __name__ == "__main__":
    sys.exit(main())
