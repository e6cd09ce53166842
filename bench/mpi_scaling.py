#!/usr/bin/env python3
"""Strong and weak scaling of the distributed solvers over MPI ranks on this machine.

Usage: bench/mpi_scaling.py [--out mpi_scaling.json] [--bin build/release/bin] [--ranks 1,2,4]
                            [--repeats 3] [--steps 5] [--cells 120,24,24] [--smoke]

Runs `mpirun -np R corofem run SCENE.json` for R in --ranks on procedural cantilever bars
(dynamic, gravity, energy-newton rotations, MG-PCG's default accuracy 1e-4):
  strong: one bar (--cells; by default 414,720 tets, --smoke a small one) at every rank count;
  weak:   a bar per rank count with R times the base bar's elements (longer along x), for the
          rank counts this machine has cores for;
for each solver that distributes (petsc-gamg, hypre-boomeramg, petsc-mg), and, for the same bars,
corofem's own MG-PCG at R OpenMP threads on one rank (the route within one machine), again only
up to the machine's cores. Rank counts above the cores are oversubscribed: they are recorded
for correctness and memory, and marked so; their times say nothing.
These scenes run on a distributed mesh (issue 37): each rank holds its part of the mesh, rotates
and assembles it, and solves its rows; the record gives per run the largest rank's peak RSS,
element visits (held tets) and halo. Each configuration runs --repeats times; the record keeps
the median of the per-step times (phases from RESULT.json's timings_ms, rank 0's; setup
excluded). Progress goes to stderr; the JSON (with the runs' own context) to --out, written
atomically.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

from json_output import write_json_atomically
from run_record import displacement_norm, ms_per_step

SOLVERS = ["petsc-gamg", "hypre-boomeramg", "petsc-mg"]
ELEMENT_PHASES = ("rotate", "assemble", "forces")
SOLVE_PHASES = ("update", "solve")


def bar_scene(cells, solver, steps):
    length = cells[0] / cells[1] * 0.2  # cells of equal size: the bar grows with its cell count
    return {"mesh": {"box": [length, 0.2, 0.2], "cells": cells},
            "material": {"young": 5e6, "poisson": 0.3, "density": 1000},
            "fixed": [{"box": [[0, 0, 0], [0, 0.2, 0.2]]}],
            "gravity": [0, 0, -9.81],
            "analysis": {"type": "dynamic", "rotation": "energy-newton", "solver": solver, "levels": 3,
                         "dt": 0.01, "steps": steps, "tolerance": 1e-4}}


def run_once(corofem, scene, ranks, threads, work):
    scene_file = os.path.join(work, "scene.json")
    out_file = os.path.join(work, "result.json")
    with open(scene_file, "w") as f:
        json.dump(scene, f)
    if os.path.exists(out_file):
        os.remove(out_file)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1", OMP_NUM_THREADS=str(threads))
    command = [corofem, "run", scene_file, "--out", out_file, "--threads", str(threads)]
    if ranks > 1 or scene["analysis"]["solver"] in SOLVERS:
        command = ["mpirun", "-np", str(ranks)] + command
    done = subprocess.run(command, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} exited {done.returncode}: {done.stderr[-800:]}")
    with open(out_file) as f:
        return json.load(f)


def measure(corofem, cells, solver, ranks, threads, steps, repeats, work):
    per_step = {}
    record = None
    for _ in range(repeats):
        record = run_once(corofem, bar_scene(cells, solver, steps), ranks, threads, work)
        phases = ms_per_step(record)
        phases["element"] = sum(phases.get(p, 0.0) for p in ELEMENT_PHASES)
        phases["solver"] = sum(phases.get(p, 0.0) for p in SOLVE_PHASES)
        for k, v in phases.items():
            per_step.setdefault(k, []).append(v)
    tets = record["mesh"]["tets"]
    per_rank = record.get("ranks") or {}
    largest = per_rank.get("max", {})
    return {"solver": solver, "ranks": ranks, "threads": threads, "cells": cells,
            "tets": tets, "vertices": record["mesh"]["vertices"],
            "distributed": record["mpi"]["distributed"],
            "oversubscribed": ranks * threads > (os.cpu_count() or 1),
            "linear_iterations_per_step": record["linear_iterations"] / record["steps"],
            "displacement_norm": displacement_norm(record),
            "converged": record["converged"],
            # The largest rank's: peak RSS, tets held (its element visits per pass) and halo.
            "peak_rss_kb_per_rank": largest.get("peak_rss_kb", record["peak_rss_kb"]),
            "held_tets_per_rank": largest.get("held_tets", tets),
            "element_visits_fraction": largest.get("held_tets", tets) / tets,
            "halo_vertices_per_rank": largest.get("halo_vertices", 0),
            "ms_per_step": {k: statistics.median(v) for k, v in per_step.items()},
            "ms_per_step_runs": per_step["step"]}, record["context"]


def summary(runs, ranks):
    """Per solver: strong speed-up and memory per rank against the first rank count, weak
    efficiency, element visits per rank."""
    out = {}
    for solver in sorted({r["solver"] for r in runs}):
        def find(study, count):
            for r in runs:
                workers = r["threads"] if solver == "mgpcg" else r["ranks"]
                if r["solver"] == solver and workers == count and (r["study"] == study or count == ranks[0]):
                    return r
            return None
        base = find("strong", ranks[0])
        if base is None:
            continue
        rows = {}
        for count in ranks[1:]:
            strong, weak = find("strong", count), find("weak", count)
            row = {}
            if strong:
                row["oversubscribed"] = strong["oversubscribed"]
                row["step_speedup"] = base["ms_per_step"]["step"] / strong["ms_per_step"]["step"]
                row["peak_rss_ratio"] = strong["peak_rss_kb_per_rank"] / base["peak_rss_kb_per_rank"]
                row["element_visits_fraction"] = strong["element_visits_fraction"]
            if weak:
                row["weak_efficiency"] = base["ms_per_step"]["step"] / weak["ms_per_step"]["step"]
            rows[str(count)] = row
        out[solver] = rows
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="mpi_scaling.json")
    parser.add_argument("--bin", default="build/release/bin")
    parser.add_argument("--ranks", default="1,2,4")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--steps", type=int, default=5)
    parser.add_argument("--cells", default="120,24,24", help="the strong study's bar (x,y,z cells)")
    parser.add_argument("--smoke", action="store_true", help="a seconds-long run for the tests")
    args = parser.parse_args()
    ranks = [int(r) for r in args.ranks.split(",")]
    cores = os.cpu_count() or 1
    if args.smoke:
        base, repeats, steps, ranks = [8, 4, 4], 1, 2, [1, 2]
    else:
        base, repeats, steps = [int(c) for c in args.cells.split(",")], args.repeats, args.steps
    corofem = os.path.join(args.bin, "corofem")
    if not os.access(corofem, os.X_OK):
        print(f"mpi_scaling: {corofem} is not built (ci/build)", file=sys.stderr)
        return 2
    runs, context = [], None
    with tempfile.TemporaryDirectory() as work:
        for solver in SOLVERS + ["mgpcg"]:
            for r in ranks:
                # mgpcg: one rank, R threads; the others: R ranks of one thread each.
                procs, threads = (1, r) if solver == "mgpcg" else (r, 1)
                for study, cells in (("strong", base), ("weak", [base[0] * r] + base[1:])):
                    if study == "weak" and r == ranks[0]:
                        continue  # the weak study's first point is the strong study's
                    if r > cores and (study == "weak" or solver == "mgpcg"):
                        continue  # oversubscribed: correctness and memory only, on the one bar
                    print(f"mpi_scaling: {solver}, {study}, {procs} rank(s) x {threads} thread(s), "
                          f"cells {cells}", file=sys.stderr)
                    row, context = measure(corofem, cells, solver, procs, threads, steps, repeats, work)
                    row["study"] = study
                    runs.append(row)
    result = {"producer": "bench/mpi_scaling.py", "context": context,
              "parameters": {"ranks": ranks, "repeats": repeats, "steps": steps, "base_cells": base,
                             "tolerance": 1e-4, "smoke": args.smoke, "cores": cores},
              "element_phases": list(ELEMENT_PHASES), "solver_phases": list(SOLVE_PHASES),
              "note": "Each rank holds its part of the mesh and does its element work (a dynamic, "
                      "linearly implicit scene on a PETSc solver); mgpcg runs on one rank with as "
                      "many OpenMP threads as the others have ranks; rank counts above the cores are "
                      "oversubscribed (memory and element visits only)",
              "summary": summary(runs, ranks),
              "runs": runs}
    write_json_atomically(args.out, result, sort_keys=True)
    print(f"mpi_scaling: wrote {args.out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
