#!/usr/bin/env python3
"""Whether `"solver": "auto"` keeps the faster solver (lib/docs/solver-choice.md, issue 70).

Usage: bench/solver_choice.py --models DIR [--out solver_choice.json] [--bin build/release/bin]
                              [--rounds 3] [--threads 2] [--steps 20] [--stiffness 1,100]

For the bare bunny and horse surfaces of DIR (models/bunny_L0.stl, horse_L0.stl: no `levels`,
so the hierarchy is derived, as a user's STL gets it), dynamic and corotated (energy-newton,
tolerance 1e-6), at each factor of --stiffness times the default Young's modulus (1e5): runs
`corofem run` with solver auto, mgpcg and jacobi-pcg, alternated, --rounds times. The record
gives per case and solver the median over the rounds of the run's update + solve (ms, set-up
excluded) and its linear iterations, auto's choice in each round, and `kept_faster`: whether
auto kept, in every round, the solver whose median is the smaller. The issue's target: at the
default stiffness Jacobi-PCG on the bare bunny, at 100x MG-PCG. Progress goes to stderr; the
JSON (with the runs' context: commit, flags, machine) to --out, written atomically. Exit 1 when a
run fails, 2 when the models are missing.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

from json_output import write_json_atomically

SOLVERS = ("auto", "mgpcg", "jacobi-pcg")
MODELS = {  # the surface, its mesh size, supports and load: bench/scenes' bunny and horse
    "bunny": {"surface": "bunny_L0.stl", "size": 0.045098,
              "fixed": [[-1, -1, -1], [1, 1, -0.47]], "load": [[-1, -1, 0.25], [1, 1, 1]],
              "total": [400, 0, 0]},
    "horse": {"surface": "horse_L0.stl", "size": 0.018747,
              "fixed": [[-0.3, -0.55, -0.45], [0.3, -0.28, -0.36]],
              "load": [[-0.3, 0.02, 0.12], [0.3, 0.3, 0.3]], "total": [0, 0, 400]},
}


def scene(models, model, young, solver, steps):
    m = MODELS[model]
    return {"mesh": {"surface": os.path.join(os.path.abspath(models), m["surface"]),
                     "size": m["size"], "reorder": True},
            "material": {"young": young, "poisson": 0.3, "density": 1000},
            "fixed": [{"box": m["fixed"]}],
            "forces": [{"box": m["load"], "total": m["total"], "ramp_steps": 10}],
            "analysis": {"type": "dynamic", "formulation": "corotational",
                         "rotation": "energy-newton", "solver": solver, "tolerance": 1e-6,
                         "dt": 0.01, "steps": steps, "rayleigh": {"alpha": 1.0}}}


def run_once(corofem, scene_json, threads, work):
    scene_file, out_file = os.path.join(work, "scene.json"), os.path.join(work, "result.json")
    with open(scene_file, "w") as f:
        json.dump(scene_json, f)
    command = [corofem, "run", scene_file, "--out", out_file, "--threads", str(threads)]
    done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        sys.exit(f"solver_choice: {' '.join(command)} failed: {done.stderr.strip()[-400:]}")
    with open(out_file) as f:
        return json.load(f)


def measure(corofem, args, model, factor, work):
    young = 1e5 * factor
    runs = {s: [] for s in SOLVERS}
    for r in range(args.rounds):
        for solver in SOLVERS:
            print(f"solver_choice: {model}, E {young:g}, {solver}, round {r + 1}/{args.rounds}",
                  file=sys.stderr)
            runs[solver].append(run_once(corofem, scene(args.models, model, young, solver,
                                                        args.steps), args.threads, work))
    row = {"model": model, "young": young, "tets": runs["auto"][0]["mesh"]["tets"]}
    for solver, records in runs.items():
        row[solver] = {"update_solve_ms": statistics.median(
                           r["timings_ms"]["update"] + r["timings_ms"]["solve"] for r in records),
                       "linear_iterations": records[0]["linear_iterations"]}
    row["auto"]["kept"] = [r["solver_choice"]["chosen"] for r in runs["auto"]]
    row["auto"]["decided_after"] = [r["solver_choice"]["decided_after"] for r in runs["auto"]]
    faster = min(("mgpcg", "jacobi-pcg"), key=lambda s: row[s]["update_solve_ms"])
    row["faster"] = faster
    row["kept_faster"] = all(kept == faster for kept in row["auto"]["kept"])
    return row, runs["auto"][0]["context"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--models", required=True)
    parser.add_argument("--out", default="solver_choice.json")
    parser.add_argument("--bin", default="build/release/bin")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--steps", type=int, default=20)
    parser.add_argument("--stiffness", default="1,100")
    args = parser.parse_args()
    missing = [m["surface"] for m in MODELS.values()
               if not os.path.exists(os.path.join(args.models, m["surface"]))]
    if missing:
        print(f"solver_choice: {args.models} has no {', '.join(missing)}", file=sys.stderr)
        return 2
    corofem = os.path.join(args.bin, "corofem")
    cases, context = [], None
    with tempfile.TemporaryDirectory() as work:
        for model in MODELS:
            for factor in (float(f) for f in args.stiffness.split(",")):
                row, context = measure(corofem, args, model, factor, work)
                cases.append(row)
    write_json_atomically(args.out, {
        "producer": "bench/solver_choice.py", "context": context,
        "parameters": {"rounds": args.rounds, "threads": args.threads, "steps": args.steps,
                       "stiffness": args.stiffness},
        "cases": cases})
    for c in cases:
        print(f"{c['model']:6s} E {c['young']:8g}: mgpcg {c['mgpcg']['update_solve_ms']:8.1f} ms, "
              f"jacobi-pcg {c['jacobi-pcg']['update_solve_ms']:8.1f} ms, auto kept "
              f"{','.join(c['auto']['kept'])} ({'the faster' if c['kept_faster'] else 'NOT the faster'})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
