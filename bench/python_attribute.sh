#!/usr/bin/env bash
# The python step against the built-in attribute it replaces: workflows/quickstart.yaml (the
# built-in envelope, a FIR Hilbert transformer) against workflows/python_attribute.yaml (the same
# recipe with the envelope computed by numpy's FFT in examples/python_attribute/seismic_attrs.py),
# end to end with run-workflow, with 1 worker (the extraction in this process) and 2 local workers.
# Prints each run's wall time, the ratio python / built-in (issue 53's target: at most 1.5) and the
# components extracted and kept (the FFT envelope differs from the FIR one near 0 Hz and Nyquist,
# so the counts may differ by a few specks).
#
#   bench/python_attribute.sh [GEOTANDEM] [SHAPE] [RUNS]
#
# GEOTANDEM defaults to build/release/bin/geotandem, SHAPE to 256,256,192, RUNS (alternated, the
# fastest of each kept) to 2. Every run starts from an empty output directory (--fresh).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bin="${1:-$here/build/release/bin/geotandem}"
shape="${2:-256,256,192}"
runs="${3:-2}"
[[ -x "$bin" ]] || { echo "bench/python_attribute.sh: no geotandem executable at $bin (build it, or pass its path)" >&2; exit 2; }
out="$(mktemp -d /tmp/geotandem-python-bench.XXXXXX)"
trap 'rm -rf "$out"' EXIT

echo "binary:  $bin"
echo "cube:    [$shape] (synthetic seismic, seed 1)"
echo "machine: $(nproc) cores, $(uname -sr), $(/usr/bin/python3 -c 'import numpy, sys; print("python", sys.version.split()[0], "numpy", numpy.__version__)')"

# One run: prints "SECONDS EXTRACTED KEPT".
run() {
  local recipe="$1" workers="$2" dir="$out/run"
  rm -rf "$dir"
  local start end
  start=$(date +%s.%N)
  "$bin" --quiet run-workflow "$recipe" --fresh --set "output.directory=$dir" \
    --set "input.synthetic.shape=[$shape]" --set "execution.workers=$workers" >"$out/stdout" 2>"$out/stderr" || {
    echo "the run of $recipe with $workers worker(s) failed:" >&2
    cat "$out/stderr" >&2
    exit 1
  }
  end=$(date +%s.%N)
  /usr/bin/python3 - "$dir" "$start" "$end" <<'PY'
import json, sys
state = json.load(open(sys.argv[1] + "/state.json"))
print(f"{float(sys.argv[3]) - float(sys.argv[2]):.2f} {state['extract']['components']}")
PY
}

for workers in 1 2; do
  best_builtin=""
  best_python=""
  for ((n = 1; n <= runs; ++n)); do
    read -r b bc < <(run "$here/workflows/quickstart.yaml" "$workers")
    read -r p pc < <(run "$here/workflows/python_attribute.yaml" "$workers")
    echo "workers $workers, run $n: built-in ${b} s ($bc components), python ${p} s ($pc components)"
    best_builtin=$(/usr/bin/python3 -c "print(min(x for x in [$b, ${best_builtin:-1e9}]))")
    best_python=$(/usr/bin/python3 -c "print(min(x for x in [$p, ${best_python:-1e9}]))")
  done
  ratio=$(/usr/bin/python3 -c "print(f'{$best_python / $best_builtin:.2f}')")
  echo "workers $workers: built-in ${best_builtin} s, python ${best_python} s (fastest of $runs): python / built-in = $ratio"
done
