#!/usr/bin/env python3
"""Fails when a function in lib/ is longer than 80 lines, from its first line to its last, as
universal-ctags counts them (its `end` field). Long functions hide the steps a reader needs named;
issue 71 brought every one under the limit and this keeps them there."""
import subprocess
import sys
from pathlib import Path

LIMIT = 80
ROOT = Path(__file__).resolve().parent.parent


def functions(root):
    out = subprocess.run(
        ["ctags", "-R", "--languages=C++", "--kinds-C++=f", "--fields=+ne", "-x",
         "--_xformat=%{line} %{end} %N %F", "lib"],
        cwd=root, check=True, capture_output=True, text=True).stdout
    for line in out.splitlines():
        first, last, name, path = line.split(" ", 3)
        if first.isdigit() and last.isdigit():
            yield int(first), int(last), name, path


def main():
    long = [(last - first + 1, name, path, first) for first, last, name, path in functions(ROOT)
            if last - first + 1 > LIMIT]
    for length, name, path, first in sorted(long, reverse=True):
        print(f"{path}:{first}: {name} is {length} lines (limit {LIMIT})", file=sys.stderr)
    if long:
        print(f"check_function_length: {len(long)} functions over {LIMIT} lines", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
