#!/usr/bin/env python3
"""The counted gate's calibration: its false alarms, and the planted faults of real work it finds.

Usage: bench/gate/count_calibration.py [REF] [--trials 20] [--out out/count-calibration]
                                       [--assembly-work 6] [--scenes SCENE.json ...]
                                       [--first-trial N]

Builds REF twice (two builds of one commit, in two folders: gate_builds) and once with each
planted fault (bench/gate/plant.py: assembly-work ITERATIONS, extra-pass, scattered-order), then
counts the gate suite (bench/count_phases.py) with the first build as the baseline, and in each
trial with the second build and with every planted one, each time with the heap's and the
stack's layout moved as a change to unrelated code would move them (--layout-shift: a longer
working folder, more environment; trial t uses seed t). Each trial is `corofem compare`d with the
baseline at compare's default thresholds (--first-trial N: a stopped calibration goes on at trial
N, adding to OUT/summary.json; the baseline is counted again, the same counts):
- A against A: a trial that alarms (compare exits 1, or a count fell beyond its threshold) is a
  false alarm;
- a planted fault is found when the trial alarms with its phase among the moved rows (assemble,
  update, rotate).
Writes OUT/summary.json: per condition the trials' alarms and the phases they named, and for A
against A every count row's largest relative move over the trials (what the thresholds must
clear); a summary to stdout, progress to stderr.
"""
import argparse
import json
import os
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "ci"))
from gate_builds import PREFIX, build_ref, build_work_tree, git, say  # noqa: E402

PREFIX[0] = "count_calibration"
# Each planted fault, the plant.py arguments and the phase it must be found in.
PLANTS = {
    "assembly-work": (["assembly-work"], "assemble"),
    "extra-pass": (["extra-pass"], "update"),
    "scattered-order": (["scattered-order"], "rotate"),
}


def count_command(binary, out, scenes, seed, jobs):
    command = [sys.executable, os.path.join(ROOT, "bench", "count_phases.py"), "--out", out,
               "--bin", os.path.dirname(binary), "--jobs", str(jobs), *scenes]
    if seed is not None:
        command += ["--layout-shift", str(seed)]
    return command


def count(binary, out, scenes, seed, jobs=2):
    if subprocess.run(count_command(binary, out, scenes, seed, jobs),
                      stderr=subprocess.DEVNULL).returncode != 0:
        raise SystemExit(f"count_calibration: counting with {binary} failed ({out})")


def count_pairwise(runs, scenes, seed):
    """Counts each (binary, folder) of `runs`, two at a time, each on one core: the suite's
    longest scene then never leaves the other core idle."""
    for i in range(0, len(runs), 2):
        started = [(out, subprocess.Popen(count_command(binary, out, scenes, seed, 1),
                                          stderr=subprocess.DEVNULL))
                   for binary, out in runs[i:i + 2]]
        for out, process in started:
            if process.wait() != 0:
                raise SystemExit(f"count_calibration: counting failed ({out})")


def compare(corofem, base, new, out):
    """(alarmed, the moved rows) of compare's verdict on NEW's counts against BASE's."""
    done = subprocess.run([corofem, "compare", base, new, "--out", out],
                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    if done.returncode == 2:
        raise SystemExit(f"count_calibration: compare {base} {new} refused (see {out})")
    with open(os.path.join(out, "compare.json")) as f:
        result = json.load(f)
    moved = [r for r in result["rows"] if r["kind"] == "count" and
             r["verdict"] in ("more", "fewer") and "not gated" not in r.get("note", "")]
    return done.returncode == 1 or result.get("counts_fell", False), moved, result["rows"]


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("ref", nargs="?", default="HEAD")
    parser.add_argument("--trials", type=int, default=20)
    parser.add_argument("--out", default=os.path.join(ROOT, "out", "count-calibration"))
    parser.add_argument("--assembly-work", type=int, default=6)
    parser.add_argument("--scenes", nargs="*", default=[])
    parser.add_argument("--first-trial", type=int, default=1)
    args = parser.parse_args(argv)
    sha = git("rev-parse", "--verify", f"{args.ref}^{{commit}}")
    os.makedirs(args.out, exist_ok=True)
    builds = {"base": build_ref(sha, "base", True, None)[0],
              "aa": build_ref(sha, "new", True, None)[0]}
    PLANTS["assembly-work"] = (["assembly-work", str(args.assembly_work)], "assemble")
    for name, (plant, _) in PLANTS.items():
        patch = os.path.join(args.out, f"{name}.patch")
        with open(patch, "w") as f:
            subprocess.run([sys.executable, os.path.join(ROOT, "bench", "gate", "plant.py"),
                            *plant, "--ref", sha], stdout=f, check=True)
        builds[name] = build_ref(sha, "new", False, patch)[0]
    corofem = build_work_tree()  # the comparing binary
    base = os.path.join(args.out, "base")
    count(builds["base"], base, args.scenes, None)
    summary = {"ref": sha, "trials": args.trials, "assembly_work": args.assembly_work,
               "conditions": {}, "aa_largest_moves": {}}
    summary_file = os.path.join(args.out, "summary.json")
    if args.first_trial > 1:
        with open(summary_file) as f:
            summary = json.load(f)
        for name in summary["conditions"]:
            summary["conditions"][name] = [t for t in summary["conditions"][name]
                                           if t["trial"] < args.first_trial]
    for trial in range(args.first_trial, args.trials + 1):
        names = ["aa", *PLANTS]
        count_pairwise([(builds[name], os.path.join(args.out, f"{name}-{trial}")) for name in names],
                       args.scenes, trial)
        for name in names:
            folder = os.path.join(args.out, f"{name}-{trial}")
            alarmed, moved, rows = compare(corofem, base, folder, folder + "-compare")
            phases = sorted({r["quantity"].rsplit(" ", 2 if r["quantity"].endswith("misses")
                                                  else 1)[0] for r in moved})
            expected = None if name == "aa" else PLANTS[name][1]
            found = alarmed and expected in phases if expected else None
            summary["conditions"].setdefault(name, []).append(
                {"trial": trial, "alarmed": alarmed, "found": found, "phases": phases,
                 "moved": [{k: r[k] for k in ("case", "quantity", "base", "new")} for r in moved]})
            if name == "aa":
                for r in rows:
                    if r["kind"] == "count" and r["base"]:
                        key = f"{r['case']} | {r['quantity']}"
                        move = abs(r["new"] / r["base"] - 1)
                        largest = summary["aa_largest_moves"].get(key, [0, r["base"]])
                        summary["aa_largest_moves"][key] = [max(largest[0], move), r["base"]]
            say(f"trial {trial}/{args.trials} {name}: "
                f"{'alarm' if alarmed else 'quiet'}{' ' + ','.join(phases) if phases else ''}")
        with open(summary_file, "w") as f:
            json.dump(summary, f, indent=1)
    for name, trials in summary["conditions"].items():
        if name == "aa":
            print(f"A against A: {sum(t['alarmed'] for t in trials)} false alarms in {len(trials)}")
        else:
            print(f"{name}: found {sum(bool(t['found']) for t in trials)} of {len(trials)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
