#!/usr/bin/env python3
"""The gate's false-alarm or detection rate, from one long ci/bench-gate run.

Usage: bench/gate/calibrate.py OUT --trials 20 --runs 10 [--phase solve] [--seed 1]
                               [--bin build/release/bin/corofem] [--json FILE]
                               [-- COMPARE_OPTIONS...]

OUT is a ci/bench-gate folder whose base/ and new/ hold a pool of repetitions of the suite
(`ci/bench-gate REF REF --runs 60` for A against A, `... --patch plant.patch --runs 30` for a
planted fault). Each trial draws --runs repetition indices from the pool at random and compares
those repetitions of both sides, as a gate of --runs runs would: the same indices on both sides,
so each pair stays the one alternated run it was. A trial alarms when compare exits 1. With
--phase, it also counts the trials in which that phase was found slower across the cases (compare's
stratified row "all cases"). Trials drawn from one pool share runs, so the rates are estimates of the gate's,
not independent draws: the pool's size is printed beside them.
Writes a summary to stdout (and --json FILE); progress to stderr.
"""
import argparse
import json
import os
import random
import re
import subprocess
import sys
import tempfile

REPETITION = re.compile(r"^(?P<case>.+)-r(?P<rep>\d+)\.json$")


def pool(folder):
    """{rep: [file names]} of one side."""
    reps = {}
    for name in os.listdir(folder):
        m = REPETITION.match(name)
        if m:
            reps.setdefault(int(m["rep"]), []).append(name)
    return reps


def main():
    argv = sys.argv[1:]
    compare_options = []
    if "--" in argv:
        compare_options = argv[argv.index("--") + 1:]
        argv = argv[:argv.index("--")]
    root = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--trials", type=int, default=20)
    parser.add_argument("--runs", type=int, default=10)
    parser.add_argument("--phase")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--bin", default=os.path.join(root, "build", "release", "bin", "corofem"))
    parser.add_argument("--json")
    args = parser.parse_args(argv)
    base, new = pool(os.path.join(args.out, "base")), pool(os.path.join(args.out, "new"))
    common = sorted(set(base) & set(new))
    if len(common) < args.runs:
        sys.exit(f"calibrate: {len(common)} repetitions in {args.out}, fewer than --runs {args.runs}")
    rng = random.Random(args.seed)
    alarms, detected, rows_flagged = 0, 0, {}
    for trial in range(args.trials):
        reps = rng.sample(common, args.runs)
        with tempfile.TemporaryDirectory() as work:
            for side, reps_of in (("base", base), ("new", new)):
                os.makedirs(os.path.join(work, side))
                for rep in reps:
                    for name in reps_of[rep]:
                        os.symlink(os.path.join(os.path.abspath(args.out), side, name),
                                   os.path.join(work, side, name))
            done = subprocess.run([args.bin, "compare", os.path.join(work, "base"),
                                   os.path.join(work, "new"), "--out", os.path.join(work, "c"),
                                   *compare_options], stdout=subprocess.DEVNULL,
                                  stderr=subprocess.PIPE, text=True)
            if done.returncode not in (0, 1):
                sys.exit(f"calibrate: compare exited {done.returncode}: {done.stderr}")
            with open(os.path.join(work, "c", "compare.json")) as f:
                verdict = json.load(f)
        alarms += done.returncode == 1
        for r in verdict["rows"]:
            if r["regression"]:
                key = f"{r['case']} | {r['threads']} | {r['quantity']} ({r['verdict']})"
                rows_flagged[key] = rows_flagged.get(key, 0) + 1
        if args.phase:
            detected += any(r["case"] == "all cases" and r["quantity"] == args.phase and
                            r["verdict"] == "slower" for r in verdict["rows"])
        print(f"calibrate: trial {trial + 1}/{args.trials}: "
              f"{'alarm' if done.returncode == 1 else 'quiet'}", file=sys.stderr)
    summary = {"producer": "bench/gate/calibrate.py", "folder": args.out, "pool": len(common),
               "trials": args.trials, "runs_per_trial": args.runs, "seed": args.seed,
               "compare_options": compare_options, "alarms": alarms,
               "rows_flagged": dict(sorted(rows_flagged.items(), key=lambda kv: -kv[1]))}
    if args.phase:
        summary["phase"] = args.phase
        summary["phase_found_slower_across_cases"] = detected
    text = json.dumps(summary, indent=1)
    print(text)
    if args.json:
        with open(args.json, "w") as f:
            f.write(text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
