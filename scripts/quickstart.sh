#!/usr/bin/env bash
# The README's first command: sets up (packages, build), then runs the main job on an embedded
# default: workflows/quickstart.yaml, a synthetic seismic cube with planted channels and lobes of
# known azimuth -> chaos x normalised envelope -> extraction -> bubble removal -> azimuth sorting
# -> exports and an HTML report.
# Output goes to ./quickstart-out (override with GEOTANDEM_QUICKSTART_OUT). A second run reuses the
# finished extraction; pass --fresh to start over.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh" release
out="${GEOTANDEM_QUICKSTART_OUT:-$PWD/quickstart-out}"
bin="$here/build/release/bin/geotandem"

echo "== running $here/workflows/quickstart.yaml into $out"
"$bin" run-workflow "$here/workflows/quickstart.yaml" --set "output.directory=$out" "$@"
echo
echo "== the ten largest bodies kept"
"$bin" store ls "$out/store" --selection sorted --sort volume --limit 10
echo
echo "quickstart: done. Open $out/report.html in a browser; exports are in $out."
echo "From Python: $here/.venv/bin/python -c \"import geotandem; print(geotandem.open_store('$out/store').components())\" (docs/python.md)"
