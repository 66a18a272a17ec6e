#!/bin/bash
# The runs of issue 55, part 2, with 2 local workers and in one process: a sparse 1024x1024x16 cube
# and a sparse 512x512x16 one (a few small blobs, mostly empty: nearly every leaf's surface is
# empty) with leaves of 8, and a 256^3 analytic cube (geotandem synth) with leaves of 8. Prints
# per run the wall time, the manager's CPU (from the run's task log) and its share of the wall time,
# and the tasks by kind. Then the resume: the 2-worker run of the analytic and the sparse 1024 cube
# killed (SIGKILL of the manager) after KILL_AFTER seconds (the sparse one after a third of it) and run again; prints the rerun's wall time
# against the clean run's for the leaves left, its tasks, and whether its components are those of the
# in-process run (same keys, volumes within 0.5 %).
#   bench/manager_runs.sh GEOTANDEM [DIR=/tmp/geotandem-manager-runs] [WORKERS=2] [KILL_AFTER=3]
# Cubes are made in DIR once (the sparse ones by numpy, seeded) and reused: give the same DIR to
# compare two builds on the same cubes.
set -euo pipefail
bin=$(realpath "$1")
dir=${2:-/tmp/geotandem-manager-runs}
workers=${3:-2}
kill_after=${4:-3}
mkdir -p "$dir"
cd "$dir"
python=${PYTHON:-python3}
for n in 512 1024; do
  [ -f sparse$n.raw ] && continue
  "$python" - "$n" <<'PY'
import json, sys
import numpy as np
n = int(sys.argv[1])
shape = (n + 1, n + 1, 17)
rng = np.random.default_rng(55)
a = np.zeros(shape, dtype="<f4")
for _ in range(n // 32):  # a few small blobs, radius 1.5 to 3 samples
    c = rng.uniform([4, 4, 4], [shape[0] - 5, shape[1] - 5, 12])
    r = rng.uniform(1.5, 3.0)
    lo = np.maximum(np.floor(c - r - 1).astype(int), 0)
    hi = np.minimum(np.ceil(c + r + 2).astype(int), shape)
    i, j, k = np.meshgrid(*(np.arange(l, h) for l, h in zip(lo, hi)), indexing="ij")
    d2 = ((i - c[0]) ** 2 + (j - c[1]) ** 2 + (k - c[2]) ** 2) / r**2
    a[lo[0]:hi[0], lo[1]:hi[1], lo[2]:hi[2]] = np.maximum(a[lo[0]:hi[0], lo[1]:hi[1], lo[2]:hi[2]], np.exp(-d2))
a.tofile(f"sparse{n}.raw")
geometry = {"inline0": 0, "inline_step": 1, "crossline0": 0, "crossline_step": 1, "z0": 0, "dz": 4, "z_unit": "ms",
            "affine": {"x0": 0.0, "xi": 12.5, "xj": 0.0, "y0": 0.0, "yi": 0.0, "yj": 12.5}}
json.dump({"format": "geotandem-raw", "version": 1, "dtype": "float32", "byte_order": "little", "order": "C",
           "axes": ["inline", "crossline", "sample"], "shape": list(shape), "geometry": geometry},
          open(f"sparse{n}.raw.json", "w"))
PY
done
[ -f a257.raw ] || "$bin" -q synth --kind analytic --shape 257 257 257 --seed 1 --out a257.raw
declare -A clean_wall
run() { # cube workers
  local out=store-$(basename "$1" .raw)-w$2
  rm -rf "$out" "$out.keys" "$out.relay"
  local start end
  start=$(date +%s.%N)
  "$bin" -q extract "$1" --out "$out" --iso 0.5 --block-size 8 --workers "$2" --fresh > /dev/null
  end=$(date +%s.%N)
  local wall
  wall=$(echo "$end - $start" | bc)
  clean_wall[$1-$2]=$wall
  if [ "$2" = 0 ]; then
    printf '%-14s in one process: %6.2f s wall\n' "$1" "$wall"
    return
  fi
  awk -F'\t' -v cube="$1" -v w="$2" -v wall="$wall" '
    /^# manager/ { split($0, f, " "); cpu = f[4] }
    $1 !~ /^#/ && $1 != "worker" { n[$2]++; l[$2] += $4 }
    END {
      printf "%-14s %d workers: %6.2f s wall, manager CPU %.2f s (%.1f %% of the wall time); tasks:", cube, w, wall, cpu, 100 * cpu / wall
      for (k in n) printf " %s %d (%d leaves)", k, n[k], l[k]
      printf "\n"
    }' "$out/task-log.tsv"
}
# Same keys as the in-process store, volumes within 0.5 %.
same_components() { # store reference
  "$python" - "$bin" "$1" "$2" <<'PY'
import json, subprocess, sys
def volumes(store):
    out = subprocess.run([sys.argv[1], "-q", "store", "ls", store, "--json"], check=True, capture_output=True, text=True).stdout
    rows = json.loads(out)
    rows = rows["components"] if isinstance(rows, dict) else rows
    return {r["key"]: r["volume"] for r in rows}
got, ref = volumes(sys.argv[2]), volumes(sys.argv[3])
off = [k for k in ref if k in got and abs(got[k] - ref[k]) > 0.005 * abs(ref[k]) + 1e-9]
same = set(got) == set(ref) and not off
print(f"components: {len(got)} against {len(ref)} in one process, " +
      ("the same keys and volumes" if same else f"DIFFERENT: {len(set(ref) - set(got))} missing, "
       f"{len(set(got) - set(ref))} extra, {len(off)} volumes off"))
PY
}
resume() { # cube workers seconds
  local out=store-$(basename "$1" .raw)-resume
  rm -rf "$out" "$out.keys" "$out.relay"
  "$bin" -q extract "$1" --out "$out" --iso 0.5 --block-size 8 --workers "$2" --fresh > /dev/null 2>&1 &
  local pid=$!
  sleep "$3"
  kill -9 "$pid" 2> /dev/null || true
  wait "$pid" 2> /dev/null || true
  sleep 1 # its workers end with it
  local start end wall
  start=$(date +%s.%N)
  "$bin" -q extract "$1" --out "$out" --iso 0.5 --block-size 8 --workers "$2" > /dev/null
  end=$(date +%s.%N)
  wall=$(echo "$end - $start" | bc)
  # The rerun's block of the task log (a resumed run appends its own).
  awk -F'\t' -v cube="$1" -v w="$2" -v wall="$wall" -v clean="${clean_wall[$1-$2]:-0}" -v after="$3" '
    FNR == NR { if ($1 !~ /^#/ && $1 != "worker" && $2 == "EXTRACT") all += $4; next } # the clean run: every leaf
    /^# cube/ { delete n; delete l; cpu = 0 }
    /^# manager/ { split($0, f, " "); cpu = f[4] }
    $1 !~ /^#/ && $1 != "worker" { n[$2]++; l[$2] += $4 }
    END {
      left = l["EXTRACT"]
      share = all > 0 ? clean * left / all : 0
      ratio = share > 0 ? wall / share : 0
      printf "%-14s resumed, %d workers, killed after %s s: %d of %d leaves left, %6.2f s wall (a clean run: %.2f s, %.2f s for the leaves left: %.2fx), manager CPU %.2f s; tasks:", cube, w, after, left, all, wall, clean, share, ratio, cpu
      for (k in n) printf " %s %d (%d leaves)", k, n[k], l[k]
      printf "\n"
    }' "store-$(basename "$1" .raw)-w$2/task-log.tsv" "$out/task-log.tsv"
  same_components "$out" "store-$(basename "$1" .raw)-w0"
}
echo "# $(date -u +%FT%TZ), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), $bin"
for cube in sparse1024.raw sparse512.raw a257.raw; do
  run "$cube" "$workers"
  run "$cube" 0
done
resume a257.raw "$workers" "$kill_after"
resume sparse1024.raw "$workers" "$(echo "$kill_after / 3" | bc -l)" # a clean run takes 2-3 s
