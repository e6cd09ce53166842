#!/usr/bin/env bash
# Cache misses of the Galerkin update (naive, reuse, stream, stream-full) and of one whole time
# step (rotate, assemble, stream update, MG-PCG) on one model: D1 and last-level misses per
# update (or step) and per block of K. Uses perf where the machine has hardware
# counters, valgrind's cachegrind (simulated caches: exact and repeatable) otherwise; the JSON
# says which. Each count is the difference of a run with N updates and one with none, divided by N.
# cachegrind simulates the paper's Core 2 Duo 6600 caches (32 KiB 8-way D1, 4 MiB 16-way L2) so that
# the counts compare with the paper's machine; --host-caches simulates this machine's instead.
# Usage: bench/cache_profile.sh [--model bunny] [--updates 5] [--out cache_profile.json]
#        [--bin build/release/bin] [--models DIR] [--host-caches]
set -euo pipefail
cd "$(dirname "$0")/.."
model=bunny updates=5 out=cache_profile.json bin=build/release/bin models=()
caches=(--D1=32768,8,64 --LL=4194304,16,64) cache_note="paper's Core 2 Duo: D1 32 KiB 8-way, LL 4 MiB 16-way"
while (($#)); do
  case $1 in
    --model) model=$2; shift 2 ;;
    --updates) updates=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --bin) bin=$2; shift 2 ;;
    --models) models=(--models "$2"); shift 2 ;;
    --host-caches) caches=() cache_note="this machine's caches"; shift ;;
    *) echo "cache_profile: unknown option $1" >&2; exit 2 ;;
  esac
done
profile="$bin/corofem_profile"
[[ -x $profile ]] || { echo "cache_profile: $profile not built (ci/build)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# perf exits 0 even where it prints "<not supported>": require a numeric count.
if command -v perf >/dev/null && perf stat -x, -e instructions true 2>&1 >/dev/null | grep -q '^[0-9]'; then
  tool=perf
else
  tool=cachegrind
fi
echo "cache_profile: using $tool on $model, $updates updates per method" >&2

# Prints "d1_misses ll_misses instructions" of one run of the driver.
measure() {
  local method=$1 n=$2 run="$tmp/$1.$2"
  if [[ $tool == perf ]]; then
    perf stat -x, -e L1-dcache-load-misses,LLC-load-misses,instructions -o "$run.perf" \
      "$profile" "$method" "$model" "$n" "${models[@]}" > /dev/null
    awk -F, '/L1-dcache-load-misses/{d=$1} /LLC-load-misses/{l=$1} /instructions/{i=$1} END{print d, l, i}' "$run.perf"
  else
    # One thread: valgrind runs a process's threads one at a time, and a second thread's
    # spin-waits made the counts differ from run to run (step: 6.4e7 to 8.4e7 instructions).
    OMP_NUM_THREADS=1 valgrind --tool=cachegrind --cache-sim=yes "${caches[@]}" --cachegrind-out-file="$run.cg" \
      "$profile" "$method" "$model" "$n" "${models[@]}" > /dev/null 2> "$run.err"
    # events: Ir I1mr ILmr Dr D1mr DLmr Dw D1mw DLmw
    awk '/^events:/{for(i=2;i<=NF;i++) idx[$i]=i-1} /^summary:/{print $(idx["D1mr"]+1)+$(idx["D1mw"]+1), $(idx["DLmr"]+1)+$(idx["DLmw"]+1), $(idx["Ir"]+1)}' "$run.cg"
  fi
}

blocks=$("$profile" stream "$model" 0 "${models[@]}" | awk '/^fine_blocks/{print $2}')
methods=(naive reuse stream stream-full step)  # the record's order, the shortest run first
# cachegrind's simulated caches are each run's own: its runs go side by side, one a core (the
# main job's profile 53 -> about 30 s on 2 cores). perf counts the real caches, which runs side by
# side would share: one at a time.
side_by_side=$(nproc)
[[ $tool == perf ]] && side_by_side=1
pids=()
for ((m = ${#methods[@]} - 1; m >= 0; m--)); do  # the longest first
  method=${methods[m]}
  for n in 0 "$updates"; do
    while (($(jobs -rp | wc -l) >= side_by_side)); do wait -n || true; done
    echo "cache_profile: $method, $n updates" >&2
    (measure "$method" "$n" > "$tmp/$method.$n.counts") &
    pids+=($!)
  done
done
for pid in "${pids[@]}"; do
  wait "$pid" || { echo "cache_profile: a $tool run failed" >&2; exit 1; }
done
results=()
for method in "${methods[@]}"; do
  read -r d0 l0 i0 < "$tmp/$method.0.counts"
  read -r d1 l1 i1 < "$tmp/$method.$updates.counts"
  results+=("$method $d0 $l0 $i0 $d1 $l1 $i1")
done

threads=$(nproc)
[[ $tool == cachegrind ]] && threads=1
python3 - "$out" "$tool" "$model" "$updates" "$blocks" "$cache_note" "$threads" "${results[@]}" <<'PY'
import json, os, platform, subprocess, sys, tempfile, datetime
out, tool, model, updates, blocks = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
cache_note, threads = sys.argv[6], int(sys.argv[7])
rows = []
for line in sys.argv[8:]:
    m, d0, l0, i0, d1, l1, i1 = line.split()
    d = (float(d1) - float(d0)) / updates
    l = (float(l1) - float(l0)) / updates
    i = (float(i1) - float(i0)) / updates
    rows.append({"method": m, "unit": "time step" if m == "step" else "Galerkin update",
                 "d1_misses_per_update": d, "ll_misses_per_update": l,
                 "instructions_per_update": i, "d1_misses_per_k_block": d / blocks,
                 "ll_misses_per_k_block": l / blocks})
try:
    commit = subprocess.check_output(["git", "rev-parse", "HEAD"], text=True).strip()
except Exception:
    commit = "unknown"
cpu = "unknown"  # the model name, as the run records say it (platform.processor() is empty on Linux)
try:
    with open("/proc/cpuinfo") as f:
        cpu = next((line.split(":", 1)[1].strip() for line in f if line.startswith("model name")),
                   cpu)
except OSError:
    pass
record = {"producer": "bench/cache_profile.sh", "tool": tool,
          "tool_note": "perf hardware counters" if tool == "perf" else
                       "valgrind cachegrind: simulated D1 and last-level caches (exact, repeatable), " + cache_note,
          "model": model, "updates": updates, "fine_blocks": blocks, "threads": threads,
          "context": {"commit": commit, "machine": platform.node(), "cpu": cpu,
                      "date": datetime.datetime.utcnow().strftime("%Y-%m-%dT%H:%M:%SZ")},
          "results": rows}
fd, tmp = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(out)))
with os.fdopen(fd, "w") as f:
    json.dump(record, f, indent=1)
os.chmod(tmp, 0o644)
os.replace(tmp, out)
for r in rows:
    print(f"{r['method']:12s} D1 {r['d1_misses_per_k_block']:8.2f}/block  LL {r['ll_misses_per_k_block']:8.3f}/block  "
          f"instr {r['instructions_per_update']:.3e}/update", file=sys.stderr)
PY
echo "cache_profile: wrote $out" >&2
