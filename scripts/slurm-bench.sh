#!/usr/bin/env bash
# Starts a private single-node Slurm (scripts/slurm-test-cluster.sh), runs the scheduler latency
# benchmark against it and against the local backend, and stops the cluster.
# Usage: scripts/slurm-bench.sh [BUILD_DIR] [JOBS]   (default build/release, 5 jobs)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build/release}"
jobs="${2:-5}"
bench="$build/bin/bench_scheduler_latency"
[ -x "$bench" ] || { echo "slurm-bench: $bench not built (cmake --build --preset release --target bench_scheduler_latency)" >&2; exit 1; }
cluster="$(mktemp -d /tmp/geotandem-slurm-bench.XXXXXX)"
trap '"$here/scripts/slurm-test-cluster.sh" stop "$cluster" >/dev/null; rm -rf "$cluster"' EXIT
SLURM_TEST_PORT="${SLURM_TEST_PORT:-16917}" "$here/scripts/slurm-test-cluster.sh" start "$cluster"
"$bench" --backend local --jobs "$jobs" --dir "$cluster/work-local"
SLURM_CONF="$cluster/slurm.conf" "$bench" --backend slurm --jobs "$jobs" --dir "$cluster/work-slurm"
