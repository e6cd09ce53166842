#!/usr/bin/env bash
# The gate's calibration as lib/docs/comparing.md reports it: pools of alternated runs of one
# commit against itself (built twice) and against planted faults (bench/gate/plant.py patches,
# applied in bench-gate's worktree only), then 20 trials of a 10-run gate drawn from each pool,
# and of 15 (bench/gate/calibrate.py). About 50 minutes on 2 cores, builds included.
# Usage: bench/gate/calibration.sh [REF] [OUT]   (default HEAD, out/calibration)
set -euo pipefail
cd "$(dirname "$0")/../.."
ref=$(git rev-parse --verify "${1:-HEAD}^{commit}")
out=${2:-out/calibration}
mkdir -p "$out"
ci/build release corofem >/dev/null  # the comparing binary
pool() {  # NAME RUNS [PATCH]
  local name=$1 runs=$2 patch=${3:-}
  echo "calibration: $name ($runs runs a side)" >&2
  ci/bench-gate "$ref" "$ref" --runs "$runs" --no-counts --out "$out/$name" ${patch:+--patch "$patch"} \
    >"$out/$name.md" 2>"$out/$name.log" || (($? == 1))
}
trials() {  # NAME [PHASE]: gates of 10 runs and of 15 (bench-gate's default)
  for runs in 10 15; do
    python3 bench/gate/calibrate.py "$out/$1" --trials 20 --runs "$runs" ${2:+--phase "$2"} \
      --json "$out/$1-trials-$runs.json" >/dev/null 2>>"$out/$1.log"
  done
}
pool aa 40 && trials aa
for plant in "solve 10" "update 10" "assemble 10" "solve 3"; do
  set -- $plant
  python3 bench/gate/plant.py slowdown "$1" "$2" --ref "$ref" >"$out/$1-$2.patch"
  pool "$1-$2" 20 "$out/$1-$2.patch" && trials "$1-$2" "$1"
done
python3 bench/gate/plant.py rotation-offset 1e-6 --ref "$ref" >"$out/rotation.patch"
pool rotation 3 "$out/rotation.patch"
echo "calibration: done; $out/*-trials.json and $out/rotation.md" >&2
