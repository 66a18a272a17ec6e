#!/usr/bin/env bash
# geotandem against VTK FlyingEdges3D + meshopt_simplify, one core (issue 57, part 3): runs
# bench_flying_edges_meshopt with the machine's load beside it, since this machine is shared and
# its speed drifts.
#
#   bench/flying_edges_meshopt.sh [EDGE] [RUNS] [DIR]      defaults: 512, 2, /tmp/geotandem-fe-meshopt
#
# Needs the bench-only packages (GEOTANDEM_BENCH_DEPS=1 scripts/setup.sh installs libvtk9-dev and
# libmeshoptimizer-dev) and a release build of `bench_flying_edges_meshopt` (which builds geotandem).
# The cube (EDGE^3 float32, 512 MiB at 512) is generated once into DIR and reused by later runs.
# Each run prints `uptime` before and after, and the bench's table.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
edge="${1:-512}"
runs="${2:-2}"
dir="${3:-/tmp/geotandem-fe-meshopt}"
bin="$here/build/release/bin"
if [[ ! -x "$bin/bench_flying_edges_meshopt" ]]; then
  echo "bench/flying_edges_meshopt.sh: no $bin/bench_flying_edges_meshopt; install the bench-only packages" \
    "(GEOTANDEM_BENCH_DEPS=1 scripts/setup.sh), then" \
    "cmake --preset release && cmake --build --preset release --target bench_flying_edges_meshopt" >&2
  exit 2
fi
echo "commit: $(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo unknown), $(nproc) cores"
for ((run = 1; run <= runs; run++)); do
  echo "=== run $run of $runs: $(date -u +%FT%TZ)"
  echo "uptime before: $(uptime)"
  "$bin/bench_flying_edges_meshopt" "$bin/geotandem" "$edge" "$dir"
  echo "uptime after:  $(uptime)"
done
