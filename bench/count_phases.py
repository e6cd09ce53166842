#!/usr/bin/env python3
"""Counts each phase's work in scenes: instructions, D1 and last-level misses under callgrind.

Usage: bench/count_phases.py [SCENE.json ...] (--out DIR | --bundle FILE) [--bin DIR] [--jobs N]
                             [--keep-fields] [--layout-shift SEED]

Runs every scene (default: the gate suite, bench/gate/*.json) once with `corofem run --threads 1
--count-phases callgrind` under valgrind's callgrind, on fixed simulated caches (the paper's Core 2
Duo: I1 and D1 32 KiB 8-way, LL 4 MiB 16-way, 64-byte lines), and writes DIR/<scene>.json: the run
record with its `phase_counts` (each phase and solver part, inclusive of its parts) and without
its fields (rest, displacement, rotations); or, with --bundle, one file of them all (producer
"bench/count_phases.py", its "records"): small enough to commit as a baseline (ci/count-gate's
bench/gate/baseline/counts.json), and what the report keeps (phase_counts.json). Either is what
`corofem compare` reads. The records' timings are valgrind's, 50-150x the machine's: compare reads none of
a callgrind-counted record's times.

Counts are exact, and the same from run to run and from host to host, when what the process sees
is the same:
- valgrind gives the code a synthetic CPU (CPUID says "Intel Core i7-4910MQ" on any AVX2 host), by
  which the C library, BLAS and the block kernels choose their code; the record says which it saw
  (phase_counts.processor_seen);
- the heap's layout, and so the addresses that decide misses and alignment peeling, follows the
  lengths of the paths and the environment the process starts with: each run gets a fresh working
  folder of a fixed-length name (/tmp/corofem-count-XXXXXXXX), the scene copied in as scene.json,
  the binary linked as ./corofem, and an environment of PATH and OMP_NUM_THREADS=1 alone.
The same binary counted in two folders of different name lengths moved the small scenes' D1
misses by up to 0.2% (and a phase of 2,000 misses by 2%); in equal-length folders, not at all.

Scenes run side by side, one a core, the longest first. Progress goes to stderr.
Exit status: 0 counted; 2 bad arguments or no binary; 3 a run failed (its stderr is printed).
"""
import argparse
import glob
import json
import os
import random
import shutil
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
# The paper's Core 2 Duo 6600 (as bench/cache_profile.sh): counts compare with its machine and are
# the same on every host.
CACHES = ["--I1=32768,8,64", "--D1=32768,8,64", "--LL=4194304,16,64"]
FIELDS = ("node_tags", "rest", "displacement", "element_tags", "rotations", "reflected_elements",
          "step_samples_ms")


def say(text):
    print(f"count_phases: {text}", file=sys.stderr, flush=True)


def valgrind_command():
    return ["valgrind", "--tool=callgrind", "--instr-atstart=no", "--combine-dumps=yes",
            "--dump-instr=no", "--dump-line=no", "--cache-sim=yes", *CACHES,
            "--callgrind-out-file=callgrind.out"]


def layout_shift(seed):
    """Calibration only: a working folder's name longer by 0-47 characters and 0-4095 bytes more
    environment, drawn from `seed`; each moves the heap's or the stack's layout as a change to
    unrelated code would. None: no shift."""
    if seed is None:
        return "", {}
    rng = random.Random(seed)
    return "x" * rng.randrange(48), {"COROFEM_COUNT_PAD": "p" * rng.randrange(4096)}


def count_one(binary, scene, seed=None):
    """Runs `scene` counted; returns (record, seconds). Raises RuntimeError with its stderr."""
    start = time.monotonic()
    longer, pad = layout_shift(seed)
    work = tempfile.mkdtemp(prefix="corofem-count-" + longer, dir="/tmp")  # a fixed-length path
    try:
        shutil.copyfile(scene, os.path.join(work, "scene.json"))
        os.symlink(os.path.abspath(binary), os.path.join(work, "corofem"))
        command = valgrind_command() + [
            "./corofem", "run", "scene.json", "--out", "record.json", "--threads", "1",
            "--count-phases", "callgrind:callgrind.out"]
        env = {"PATH": "/usr/bin:/bin", "OMP_NUM_THREADS": "1", **pad}
        done = subprocess.run(command, cwd=work, env=env, stdout=subprocess.DEVNULL,
                              stderr=subprocess.PIPE, text=True)
        if done.returncode != 0:
            raise RuntimeError(f"{scene}: exited {done.returncode}:\n{done.stderr[-3000:]}")
        with open(os.path.join(work, "record.json")) as f:
            record = json.load(f)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    counts = record.get("phase_counts") or {}
    if counts.get("source") != "callgrind":
        raise RuntimeError(f"{scene}: not counted: {counts.get('unavailable', 'no phase_counts')}")
    return record, time.monotonic() - start


def slim(record, scene):
    """The record without its fields; named by the scene's own file, as compare pairs it."""
    for key in FIELDS:
        record.pop(key, None)
    record["scene_file"] = os.path.basename(scene)
    record["timings_ms_note"] = "valgrind's times (50-150x the machine's): not a measurement"
    return record


def counting_note(records):
    """What made the bundle's counts, once (each record also says it)."""
    counts = records[0]["phase_counts"]
    return {"tool": counts.get("tool"), "simulated_caches": counts.get("simulated_caches"),
            "processor_seen": counts.get("processor_seen"), "threads": counts.get("threads"),
            "environment": "PATH and OMP_NUM_THREADS=1 alone, in a fresh /tmp/corofem-count-XXXXXXXX",
            "commit": records[0]["context"].get("commit")}


def write_atomically(path, record):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        json.dump(record, f, indent=1, sort_keys=True)
        f.write("\n")
    os.replace(tmp, path)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenes", nargs="*")
    where = parser.add_mutually_exclusive_group(required=True)
    where.add_argument("--out", help="a folder: one record per scene")
    where.add_argument("--bundle", help="one file of every scene's record")
    parser.add_argument("--bin", default=os.path.join(ROOT, "build", "release", "bin"))
    parser.add_argument("--jobs", type=int, default=len(os.sched_getaffinity(0)))
    parser.add_argument("--keep-fields", action="store_true",
                        help="keep the displacements and the other fields in the records")
    parser.add_argument("--layout-shift", type=int, metavar="SEED",
                        help="calibration: move the heap's and the stack's layout (a longer "
                             "working folder, more environment) as unrelated code would")
    args = parser.parse_args(argv)
    binary = os.path.join(args.bin, "corofem")
    if not os.access(binary, os.X_OK):
        say(f"no {binary}: build it first (ci/build release corofem)")
        return 2
    if not shutil.which("valgrind"):
        say("valgrind is not installed (ci/setup installs it)")
        return 2
    scenes = args.scenes or sorted(glob.glob(os.path.join(ROOT, "bench", "gate", "*.json")))
    for scene in scenes:
        if not os.path.isfile(scene):
            say(f"{scene}: no such scene file")
            return 2
    if args.out:
        os.makedirs(args.out, exist_ok=True)
    bundle = []
    # The longest first, so that the short ones fill the cores at the end: the quadrupeds, the
    # larger size first (quadruped_34k before quadruped_11k), then the others.
    order = sorted(scenes, key=os.path.basename, reverse=True)
    order.sort(key=lambda s: "quadruped" not in os.path.basename(s))
    say(f"{len(order)} scene(s) under callgrind, {args.jobs} at a time")
    start = time.monotonic()
    failed = []

    def one(scene):
        try:
            record, seconds = count_one(binary, scene, args.layout_shift)
        except RuntimeError as e:
            failed.append(str(e))
            say(f"FAILED {e}")
            return
        if not args.keep_fields:
            record = slim(record, scene)
        if args.bundle:
            bundle.append(record)
        else:
            name = os.path.splitext(os.path.basename(scene))[0] + ".json"
            write_atomically(os.path.join(args.out, name), record)
        say(f"{os.path.basename(scene)}: {record['phase_counts']['marks']} marks, {seconds:.0f} s")

    with ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        list(pool.map(one, order))
    if args.bundle and not failed:
        bundle.sort(key=lambda r: r["scene_file"])
        write_atomically(args.bundle, {"producer": "bench/count_phases.py",
                                       "counting": counting_note(bundle),
                                       "records": bundle})
    say(f"done in {time.monotonic() - start:.0f} s")
    return 3 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
