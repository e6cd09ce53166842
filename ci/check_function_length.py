#!/usr/bin/env python3
"""Fails when a function in lib/ is longer than 80 lines, from its first line to its last, as
universal-ctags counts them (its `end` field), in every preprocessor branch. Long functions hide
the steps a reader needs named.

ctags reads only the first branch of an #if/#else (the other could unbalance the braces), so a
function written in the #else of a build option (PETSc's, AVX2's) would go unseen. Each file with
conditionals is also read as the variant that keeps every group's last branch (its #else or
#elif, or nothing), with the dropped lines blanked so that line numbers stay the file's."""
import re
import subprocess
import sys
import tempfile
from pathlib import Path

LIMIT = 80
ROOT = Path(__file__).resolve().parent.parent
OPEN = re.compile(r"^\s*#\s*(if|ifdef|ifndef)\b")
ELSE = re.compile(r"^\s*#\s*(else|elif)\b")
END = re.compile(r"^\s*#\s*endif\b")


def last_branches(lines):
    """The file with every conditional group reduced to its last branch (its #else or last
    #elif; a group without one keeps nothing), the other lines blanked."""
    keep = [True] * len(lines)
    stack = []  # per open group: the first line of each of its branches so far
    for i, line in enumerate(lines):
        if OPEN.match(line):
            stack.append([i + 1])
        elif ELSE.match(line) and stack:
            stack[-1].append(i + 1)
        elif END.match(line) and stack:
            starts = stack.pop()
            # Every branch but the last; a group without #else: its one branch too.
            ends = [start - 1 for start in starts[1:]] if len(starts) > 1 else [i]
            for start, end in zip(starts, ends):
                keep[start:end] = [False] * (end - start)
        else:
            continue
        keep[i] = False  # the directive itself
    return [line if kept else "\n" for line, kept in zip(lines, keep)]


def functions(root):
    out = subprocess.run(
        ["ctags", "-R", "--languages=C++", "--kinds-C++=f", "--fields=+ne", "-x",
         "--_xformat=%{line} %{end} %N %F", "."],
        cwd=root, check=True, capture_output=True, text=True).stdout
    for line in out.splitlines():
        first, last, name, path = line.split(" ", 3)
        if first.isdigit() and last.isdigit():
            yield int(first), int(last), name, path.removeprefix("./")


def main():
    lengths = {}
    for first, last, name, path in functions(ROOT / "lib"):
        lengths[(path, first, name)] = last - first + 1
    with tempfile.TemporaryDirectory() as variants:
        for source in (ROOT / "lib").rglob("*"):
            if source.suffix not in (".cpp", ".hpp"):
                continue
            lines = source.read_text(encoding="utf-8").splitlines(keepends=True)
            if not any(OPEN.match(line) for line in lines):
                continue
            target = Path(variants) / source.relative_to(ROOT / "lib")
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_text("".join(last_branches(lines)), encoding="utf-8")
        for first, last, name, path in functions(variants):
            key = (path, first, name)
            lengths[key] = max(lengths.get(key, 0), last - first + 1)
    long = sorted(((length, name, f"lib/{path}", first)
                   for (path, first, name), length in lengths.items() if length > LIMIT),
                  reverse=True)
    for length, name, path, first in long:
        print(f"{path}:{first}: {name} is {length} lines (limit {LIMIT})", file=sys.stderr)
    if long:
        print(f"check_function_length: {len(long)} functions over {LIMIT} lines, in some "
              f"preprocessor branch", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
