#!/usr/bin/env bash
# Fused attributes against an attribute file, measured in one run (issue 12, part 1): the quickstart
# recipe's extraction with the attribute chain computed block by block as marching cubes reads it
# ("fused"), against writing the attribute cube on its own and extracting from that file.
#
#   bench/fused_vs_file.sh [GEOTANDEM] [SHAPE] [OUTDIR]      defaults: build/release/bin/geotandem
#                                                            [256,256,192], a new temporary directory
#
# Three commands run one after the other:
#   1. run-workflow quickstart.yaml                     -> "fused": the extract phase
#   2. run-workflow quickstart.yaml, output.attribute   -> "write": the phase writing facies.nc
#   3. geotandem extract facies.nc (same iso, E0, leaves) -> "from file": its extract phase
# and the script prints each phase's seconds (from the progress lines), the ratio
# fused / (write + from file) (target <= 1.3), and the component counts, which must agree.
# Needs python3. The machine may be shared: run it a few times and look at the spread.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bin="${1:-$here/build/release/bin/geotandem}"
shape="${2:-[256,256,192]}"
out="${3:-$(mktemp -d /tmp/geotandem-fused-bench.XXXXXX)}"
recipe="$here/workflows/quickstart.yaml"
[[ -x "$bin" ]] || { echo "bench/fused_vs_file.sh: no geotandem executable at $bin (build it, or pass its path)" >&2; exit 2; }
mkdir -p "$out"
echo "binary: $bin"
echo "cube:   $shape (synthetic seismic, quickstart recipe)"
echo "output: $out"

# The progress line "NAME: 100% (...), S s, done" of the phase whose name starts with $2 (a regular
# expression).
phase_seconds() {
  python3 - "$1" "$2" <<'PY'
import re, sys
text = open(sys.argv[1]).read().replace("\r", "\n")
hits = [float(m.group(1)) for m in re.finditer(r"^" + sys.argv[2] + r".*?([0-9.]+) s, done$", text, re.M)]
print(hits[-1] if hits else "nan")
PY
}

"$bin" run-workflow "$recipe" --fresh --set "output.directory=$out/fused" --set "input.synthetic.shape=$shape" \
  >"$out/fused.stdout" 2>"$out/fused.stderr" || { cat "$out/fused.stderr" >&2; exit 1; }
"$bin" run-workflow "$recipe" --fresh --set "output.directory=$out/file" --set "input.synthetic.shape=$shape" \
  --set output.attribute=facies.nc >"$out/file.stdout" 2>"$out/file.stderr" || { cat "$out/file.stderr" >&2; exit 1; }
"$bin" extract "$out/file/facies.nc" --iso 0.2 --max-error 0.5 --block-size 128 --out "$out/from-file" \
  >"$out/from-file.stdout" 2>"$out/from-file.stderr" || { cat "$out/from-file.stderr" >&2; exit 1; }

# The extraction's phase: "extraction, N blocks" with workers (the default), "tandem" in one process.
fused=$(phase_seconds "$out/fused.stderr" '(?:extraction|tandem)')
write=$(phase_seconds "$out/file.stderr" writing)
from_file=$(phase_seconds "$out/from-file.stderr" '(?:extraction|tandem)')
python3 - "$fused" "$write" "$from_file" "$out" <<'PY'
import json, re, sys
fused, write, from_file = (float(x) for x in sys.argv[1:4])
out = sys.argv[4]
n_fused = json.load(open(out + "/fused/state.json"))["extract"]["components"]
m = re.search(r"extracted (\d+) components", open(out + "/from-file.stdout").read() + open(out + "/from-file.stderr").read())
n_file = int(m.group(1)) if m else -1
print(f"fused extraction:              {fused:7.2f} s  ({n_fused} components)")
print(f"write the attribute cube:      {write:7.2f} s")
print(f"extract from that file:        {from_file:7.2f} s  ({n_file} components)")
print(f"fused / (write + from file):   {fused / (write + from_file):7.2f}   (target <= 1.3)")
if n_fused != n_file:
    print("COMPONENT COUNTS DIFFER")
    sys.exit(1)
PY
