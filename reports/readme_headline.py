#!/usr/bin/env python3
"""Draws the README's headline (the paper's Table 1 beside ours) from the published snapshot.

Usage: readme_headline.py [--check] README REPORT_DIR

Replaces the text between the README's `<!-- headline:begin -->` and `<!-- headline:end -->`
lines with the headline drawn from REPORT_DIR/tables.json alone, so the numbers on the front page
are the snapshot's, with its commit, machine and date. --check changes nothing and exits 1 when
the README's headline differs from the snapshot's (the gate that keeps them one).
"""
import json
import os
import sys
import tempfile

BEGIN, END = "<!-- headline:begin -->", "<!-- headline:end -->"


def rate(value, paper):
    """'199 (11.7x)': steps per second and ours / the paper's."""
    return f"{value:.0f} ({value / paper:.1f}x)"


def headline(tables):
    c, s = tables["context"], tables["settings"]
    rows = [r for r in tables.get("table1", [])
            if r.get("completed") and r.get("paper") and r.get("one_thread")]
    if not rows:
        raise ValueError("tables.json has no completed Table 1 row of the paper's sizes")
    threads = tables.get("threads", c.get("threads_used", 1))
    flags = c["flags"].split()[0]  # the optimization level; REPORT.md has every flag
    tolerance = f"{s['tolerance']:.0e}".replace("e-0", "e-")  # 1e-4
    levels = "/".join(str(n) for n in sorted({r["levels"] for r in rows}))
    text = [
        "Time steps per second on the paper's dynamic scenes (energy-newton rotations, MG-PCG to "
        f"{tolerance} on\n{levels} non-nested levels, implicit Euler at dt = {s['dt']:g} s; medians "
        f"of {s['measured_steps']} steps), against the paper's\n"
        "Table 1 (Core 2 Duo 6600, 2.4 GHz), from the published snapshot "
        "([reports/REPORT.md](reports/REPORT.md):\n"
        f"commit `{c['commit'][:7]}`, {c['cpu']}, {c['hardware_threads']} cores, {c['compiler']} "
        f"`{flags}`, {c['date'][:10]}):",
        "",
        f"| model | tets | paper | ours, 1 thread (x paper) | ours, {threads} threads (x paper) |",
        "|---|---|---|---|---|",
    ]
    for r in rows:
        paper = r["paper"]["tps"]
        text.append(f"| {r['paper_model']} | {r['tets']:,} | {paper:g} | "
                    f"{rate(r['one_thread']['tps'], paper)} | {rate(r['tps'], paper)} |")
    return "\n".join(text) + "\n"


def main(argv):
    check = "--check" in argv
    args = [a for a in argv[1:] if a != "--check"]
    if len(args) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    readme, folder = args
    try:
        with open(os.path.join(folder, "tables.json")) as f:
            drawn = headline(json.load(f))
    except (OSError, ValueError, KeyError) as e:
        print(f"readme_headline: {folder}/tables.json: {e!r}", file=sys.stderr)
        return 2
    with open(readme) as f:
        text = f.read()
    begin, end = text.find(BEGIN), text.find(END)
    if begin < 0 or end < begin:
        print(f"readme_headline: {readme} has no {BEGIN} ... {END} block", file=sys.stderr)
        return 2
    begin += len(BEGIN) + 1
    if text[begin:end] == drawn:
        return 0
    if check:
        print(f"readme_headline: {readme}'s headline is not the snapshot's in {folder}; run "
              f"reports/readme_headline.py {readme} {folder}\n--- README has:\n{text[begin:end]}"
              f"--- the snapshot gives:\n{drawn}", file=sys.stderr)
        return 1
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(readme)), suffix=".md")
    with os.fdopen(fd, "w") as f:
        f.write(text[:begin] + drawn + text[end:])
    os.chmod(tmp, 0o644)
    os.replace(tmp, readme)
    print(f"readme_headline: {readme}'s headline drawn from {folder}/tables.json", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
