#!/usr/bin/env bash
# The python step against the built-in attribute it replaces: workflows/quickstart.yaml (the
# built-in envelope, a FIR Hilbert transformer) against workflows/python_attribute.yaml (the same
# recipe with the envelope computed with numpy in examples/python_attribute/seismic_attrs.py),
# end to end with run-workflow, with 1 worker (the extraction in this process) and 2 local workers.
# Prints each run's wall and CPU time, the ratio python / built-in (issue 53's target: at most 1.5
# in wall time) and the components extracted (the same Hilbert transformer as the built-in's, its
# sums in another order: the counts may differ by a speck or two).
#
#   bench/python_attribute.sh [GEOTANDEM] [SHAPE] [RUNS]
#
# GEOTANDEM defaults to build/release/bin/geotandem, SHAPE to 256,256,192, RUNS (alternated; the
# fastest and the median of each are compared) to 3. Every run starts from an empty output
# directory (--fresh). Needs /usr/bin/time (Debian package `time`).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bin="${1:-$here/build/release/bin/geotandem}"
shape="${2:-256,256,192}"
runs="${3:-3}"
[[ -x "$bin" ]] || { echo "bench/python_attribute.sh: no geotandem executable at $bin (build it, or pass its path)" >&2; exit 2; }
out="$(mktemp -d /tmp/geotandem-python-bench.XXXXXX)"
trap 'rm -rf "$out"' EXIT

echo "binary:  $bin"
echo "cube:    [$shape] (synthetic seismic, seed 1)"
echo "machine: $(nproc) cores, $(uname -sr), $(/usr/bin/python3 -c 'import numpy, sys; print("python", sys.version.split()[0], "numpy", numpy.__version__)')"

# One run: prints "WALL CPU COMPONENTS" (CPU: user + system of the run and its workers).
run() {
  local recipe="$1" workers="$2" dir="$out/run"
  rm -rf "$dir"
  /usr/bin/time -f "%e %U %S" -o "$out/time" "$bin" --quiet run-workflow "$recipe" --fresh --set "output.directory=$dir" \
    --set "input.synthetic.shape=[$shape]" --set "execution.workers=$workers" >"$out/stdout" 2>"$out/stderr" || {
    echo "the run of $recipe with $workers worker(s) failed:" >&2
    cat "$out/stderr" >&2
    exit 1
  }
  /usr/bin/python3 - "$dir" "$out/time" <<'PY'
import json, sys
state = json.load(open(sys.argv[1] + "/state.json"))
wall, user, system = (float(x) for x in open(sys.argv[2]).read().split()[-3:])
print(f"{wall:.2f} {user + system:.2f} {state['extract']['components']}")
PY
}

# Runs alternate (built-in, python, built-in, ...) so that a busy spell of the machine falls on both.
for workers in 1 2; do
  walls_b=() walls_p=() cpus_b=() cpus_p=()
  for ((n = 1; n <= runs; ++n)); do
    read -r b bcpu bc < <(run "$here/workflows/quickstart.yaml" "$workers")
    read -r p pcpu pc < <(run "$here/workflows/python_attribute.yaml" "$workers")
    echo "workers $workers, run $n: built-in ${b} s wall, ${bcpu} s CPU ($bc components); python ${p} s wall, ${pcpu} s CPU ($pc components)"
    walls_b+=("$b") walls_p+=("$p") cpus_b+=("$bcpu") cpus_p+=("$pcpu")
  done
  /usr/bin/python3 - "$workers" "$runs" "${walls_b[*]}" "${walls_p[*]}" "${cpus_b[*]}" "${cpus_p[*]}" <<'PY'
import statistics, sys
workers, runs = sys.argv[1], sys.argv[2]
wb, wp, cb, cp = ([float(x) for x in a.split()] for a in sys.argv[3:7])
print(f"workers {workers}: wall, fastest of {runs}: built-in {min(wb):.2f} s, python {min(wp):.2f} s, "
      f"python / built-in = {min(wp) / min(wb):.2f} (medians {statistics.median(wb):.2f} / "
      f"{statistics.median(wp):.2f} = {statistics.median(wp) / statistics.median(wb):.2f}); "
      f"CPU, least: {min(cb):.2f} s / {min(cp):.2f} s = {min(cp) / min(cb):.2f}")
PY
done
