#!/usr/bin/env python3
"""Two configurations of `corofem run` timed against each other, alternated in one session.

Usage: bench/alternate_runs.py --baseline BIN[:SCENE] --candidate BIN[:SCENE] [--runs 5]
                               [--threads 2] [--target solve=0.6] [--target step=0.75]
                               [--out FILE] SCENE [SCENE ...]

A configuration is a corofem binary, and optionally a scene file of its own that replaces each
SCENE (one scene with other settings: `--baseline bin/corofem:a.json --candidate
bin/corofem:b.json`). For each SCENE the two configurations run one after the other, --runs
times (baseline, candidate, baseline, ...), so that both see the same hours of a noisy shared
machine; each run's per-step times come from its record's timings_ms (setup excluded). The
report gives per configuration the median over the runs of the ms a step of solve, update and
step, the linear iterations, and the ratios candidate / baseline of the medians; each --target
PHASE=R says whether candidate / baseline <= R. A faster build of the same numerics gives the
same results: `same_result` says whether the two configurations' displacements agree to 1e-12 of
their norm and their iterations are equal (the comparison is about time only when they do).
Progress goes to stderr; the JSON (with each configuration's record context: commit, flags,
machine) to stdout or --out, written atomically. Exit 1 when a run fails.
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile

from json_output import write_json_atomically
from run_record import displacement_norm, ms_per_step

PHASES = ("solve", "update", "step")


def configuration(text):
    binary, _, scene = text.partition(":")
    return {"binary": binary, "scene": scene or None}


def target(text):
    phase, _, ratio = text.partition("=")
    if phase not in PHASES or not ratio:
        raise argparse.ArgumentTypeError(f"--target {text!r}: expected PHASE=RATIO, PHASE one of {PHASES}")
    return phase, float(ratio)


def run_once(config, scene, threads, out_file):
    command = [config["binary"], "run", config["scene"] or scene, "--out", out_file,
               "--threads", str(threads)]
    done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        sys.exit(f"alternate_runs: {' '.join(command)} exited {done.returncode}:\n{done.stderr}")
    with open(out_file) as f:
        record = json.load(f)
    per_step = ms_per_step(record)
    return record, {phase: per_step.get(phase, 0.0) for phase in PHASES}


def same_result(a, b):
    if a.get("linear_iterations") != b.get("linear_iterations"):
        return False
    ua, ub = a["displacement"], b["displacement"]
    if len(ua) != len(ub):
        return False
    difference = math.sqrt(sum((x - y) ** 2 for u, v in zip(ua, ub) for x, y in zip(u, v)))
    return difference <= 1e-12 * max(displacement_norm(a), 1e-300)


def compare(scene, configs, runs, threads, targets, work):
    times = {name: {phase: [] for phase in PHASES} for name in configs}
    records = {}
    for k in range(runs):
        for name, config in configs.items():
            print(f"alternate_runs: {scene}: {name} run {k + 1} of {runs}", file=sys.stderr)
            record, per_step = run_once(config, scene, threads, os.path.join(work, name + ".json"))
            for phase in PHASES:
                times[name][phase].append(per_step[phase])
            records.setdefault(name, record)
    result = {"scene": scene, "runs": runs, "threads": threads,
              "same_result": same_result(records["baseline"], records["candidate"])}
    for name in configs:
        medians = {phase: statistics.median(times[name][phase]) for phase in PHASES}
        result[name] = {"binary": configs[name]["binary"],
                        "scene": configs[name]["scene"] or scene,
                        "context": records[name].get("context", {}),
                        "linear_iterations": records[name].get("linear_iterations"),
                        "ms_per_step": medians, "ms_per_step_runs": times[name]}
    ratio = {}
    for phase in PHASES:
        base = result["baseline"]["ms_per_step"][phase]
        ratio[phase] = result["candidate"]["ms_per_step"][phase] / base if base > 0 else None
    result["candidate_over_baseline"] = ratio
    result["targets"] = [{"phase": phase, "at_most": bound,
                          "met": ratio[phase] is not None and ratio[phase] <= bound}
                         for phase, bound in targets]
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("scenes", nargs="+", metavar="SCENE")
    parser.add_argument("--baseline", type=configuration, required=True, metavar="BIN[:SCENE]")
    parser.add_argument("--candidate", type=configuration, required=True, metavar="BIN[:SCENE]")
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--target", type=target, action="append", default=[], metavar="PHASE=R")
    parser.add_argument("--out")
    args = parser.parse_args()
    if args.runs < 1 or args.threads < 1:
        parser.error("--runs and --threads must be at least 1")
    configs = {"baseline": args.baseline, "candidate": args.candidate}
    for name, config in configs.items():
        if not os.access(config["binary"], os.X_OK):
            parser.error(f"--{name}: {config['binary']} is not an executable")
    with tempfile.TemporaryDirectory() as work:
        report = {"producer": "bench/alternate_runs.py",
                  "comparisons": [compare(scene, configs, args.runs, args.threads, args.target,
                                          work) for scene in args.scenes]}
    if args.out:
        write_json_atomically(args.out, report)
    else:
        sys.stdout.write(json.dumps(report, indent=1) + "\n")


if __name__ == "__main__":
    main()
