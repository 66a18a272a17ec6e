#!/usr/bin/env bash
# run-workflow with its workers as jobs of a private single-node Slurm (scripts/slurm-test-cluster.sh):
# the time from starting `geotandem run-workflow` to the first worker's HELLO (its job started and
# it connected) and to its READY (it rebuilt the input volume), and the share of the extraction
# spent waiting on the scheduler (from the first sbatch to the first worker joining). The same run
# with local worker processes is printed for comparison.
#
#   bench/slurm_workflow.sh [GEOTANDEM] [WORKERS] [-- --set KEY=VALUE ...]
#
# GEOTANDEM defaults to build/release/bin/geotandem, WORKERS to 2. The quickstart recipe runs on a
# 96x96x64 cube unless --set says otherwise. Prints figures; it is not a test.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bin="${1:-$here/build/release/bin/geotandem}"
workers="${2:-2}"
shift $(( $# > 2 ? 2 : $# )) || true
[ "${1:-}" = "--" ] && shift
[ -x "$bin" ] || { echo "slurm_workflow: $bin is not built" >&2; exit 1; }
work="$(mktemp -d /tmp/geotandem-slurm-workflow.XXXXXX)"
chmod 755 "$work" # munged wants its socket's directories searchable
trap '"$here/scripts/slurm-test-cluster.sh" stop "$work/cluster" >/dev/null 2>&1; rm -rf "$work"' EXIT
SLURM_TEST_PORT="${SLURM_TEST_PORT:-16919}" "$here/scripts/slurm-test-cluster.sh" start "$work/cluster" >/dev/null
export SLURM_CONF="$work/cluster/slurm.conf"

# One run (python3: the manager's log lines and the first READY in a worker log, stamped with the
# seconds since run-workflow started), then one line of figures.
run() { # scheduler out
  python3 - "$bin" "$here/workflows/quickstart.yaml" "$workers" "$@" <<'PY'
import os, re, subprocess, sys, threading, time
bin, recipe, workers, scheduler, out = sys.argv[1:6]
extra = sys.argv[6:]
t0 = time.monotonic()
stamp = lambda: time.monotonic() - t0
ready = []
def watch_ready():  # a worker prints "ready" into its job log once it rebuilt the input volume
    logs = os.path.join(out, "worker-logs")
    while not ready and not done.is_set():
        if os.path.isdir(logs):
            for f in os.listdir(logs):
                try:
                    if ": ready (" in open(os.path.join(logs, f)).read():
                        ready.append(stamp()); break
                except OSError:
                    pass
        time.sleep(0.01)
done = threading.Event()
threading.Thread(target=watch_ready, daemon=True).start()
cmd = [bin, "--log-level", "info", "run-workflow", recipe, "--fresh", "--set", "input.synthetic.shape=[96,96,64]",
       "--set", "steps.extract.block_size=16", "--set", "output.directory=" + out,
       "--set", "execution.workers=" + workers, "--scheduler", scheduler] + extra
lines = []
p = subprocess.Popen(cmd, stderr=subprocess.PIPE, stdout=subprocess.DEVNULL, text=True)
for line in p.stderr:
    lines.append((stamp(), line))
p.wait()
end = stamp()
done.set()
if p.returncode != 0:
    sys.exit("".join(l for _, l in lines[-20:]) + f"run-workflow --scheduler {scheduler} failed ({p.returncode})")
first = lambda pat: next((t for t, l in lines if re.search(pat, l)), float("nan"))
submit, hello = first("submitted as job|manager listening"), first(" joined; 1 connected")
started, finished = first("extraction, .*started"), first("extraction, .*done")
r = ready[0] if ready else first(r": ready \(")  # local workers log to the manager's stderr
print(f"{scheduler:6s} to first submission {submit:6.2f} s | to first worker HELLO {hello:6.2f} s | "
      f"to first READY {r:6.2f} s | extraction {finished - started:6.2f} s | whole run {end:6.2f} s | "
      f"waiting on the scheduler (first submission to first HELLO) {100 * (hello - submit) / (finished - started):5.1f} % "
      f"of the extraction")
PY
}

echo "quickstart on 96x96x64 in blocks of 16, $workers workers, nproc $(nproc); seconds since run-workflow started:"
run slurm "$work/slurm" "$@"
run local "$work/local" "$@"
