#!/usr/bin/env bash
# The README's first command: sets up (packages, build), then runs the main job on an embedded
# default: a synthetic analytic cube with known bodies is generated, described, and its
# isosurface extracted into a component store, whose largest components are listed.
# Output goes to ./quickstart-out (override with GEOTANDEM_QUICKSTART_OUT).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh" release
out="${GEOTANDEM_QUICKSTART_OUT:-$PWD/quickstart-out}"
bin="$here/build/release/bin/geotandem"
mkdir -p "$out"

echo "== generating a synthetic analytic cube with planted bodies ($out/cube.nc)"
"$bin" synth --kind analytic --shape 160 160 128 --seed 7 --out "$out/cube.nc" --overwrite
echo "== describing it"
"$bin" info "$out/cube.nc"
