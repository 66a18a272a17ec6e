#!/usr/bin/env bash
# Runs workflows/quickstart.yaml end to end, as a user would, and prints its wall time, peak
# resident memory and the number of components before and after each step.
#
#   bench/quickstart.sh [GEOTANDEM] [OUTDIR] [-- --set KEY=VALUE ...]
#
# GEOTANDEM defaults to build/release/bin/geotandem, OUTDIR to a new temporary directory. Extra
# arguments after -- go to run-workflow (e.g. -- --set input.synthetic.shape=[256,256,128]). Every
# run starts from an empty output directory (--fresh), so the extraction is measured, not reused.
# Needs /usr/bin/time (Debian package `time`) and python3.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bin="${1:-$here/build/release/bin/geotandem}"
out="${2:-$(mktemp -d /tmp/geotandem-quickstart-bench.XXXXXX)}"
shift $(( $# > 2 ? 2 : $# )) || true
[[ "${1:-}" == "--" ]] && shift
recipe="$here/workflows/quickstart.yaml"

[[ -x "$bin" ]] || { echo "bench/quickstart.sh: no geotandem executable at $bin (build it, or pass its path)" >&2; exit 2; }
[[ -x /usr/bin/time ]] || { echo "bench/quickstart.sh: /usr/bin/time is missing (apt-get install time)" >&2; exit 2; }

echo "recipe:  $recipe"
echo "binary:  $bin"
echo "output:  $out"
echo "machine: $(nproc) cores, $(uname -sr)"
"$bin" --version 2>/dev/null | head -1 || true

mkdir -p "$out"
timing="$out/bench.time"
/usr/bin/time -v -o "$timing" "$bin" --quiet run-workflow "$recipe" --fresh --set "output.directory=$out" "$@" \
  >"$out/bench.stdout" 2>"$out/bench.stderr" || {
  echo "the run failed:" >&2
  cat "$out/bench.stderr" >&2
  exit 1
}

"$bin" store selections "$out/store" --json >"$out/bench.selections.json"
python3 - "$out" <<'PY'
import json, re, sys
out = sys.argv[1]
text = open(out + "/bench.time").read()
def field(name):
    m = re.search(r"^\s*" + re.escape(name) + r": (.*)$", text, re.M)
    return m.group(1).strip() if m else "?"
parts = [float(p) for p in field("Elapsed (wall clock) time (h:mm:ss or m:ss)").split(":")]
seconds = sum(p * 60 ** n for n, p in enumerate(reversed(parts)))
rss_mb = int(field("Maximum resident set size (kbytes)")) / 1024
state = json.load(open(out + "/state.json"))
sels = {s["name"]: s for s in json.load(open(out + "/bench.selections.json"))}
truth = json.load(open(out + "/truth.json"))
shape = truth["geometry"]["shape"]
extracted = state["extract"]["components"]
print(f"cube:            {shape[0]} x {shape[1]} x {shape[2]} samples (synthetic seismic, seed {truth['seed']})")
print(f"wall time:       {seconds:.2f} s (user {field('User time (seconds)')} s, system {field('System time (seconds)')} s)")
print(f"peak RSS:        {rss_mb:.0f} MiB")
print(f"extract:         -> {extracted} components")
# Each component step wrote a selection; its parameters say what it started from.
for sel in sorted(sels.values(), key=lambda s: s["created"]):
    p = sel["parameters"]
    source = p.get("from") or ""
    before = p.get("before", sels[source]["size"] if source in sels else extracted)
    print(f"{p.get('step', sel['name']) + ':':<16} {before} -> {sel['size']} components (selection '{sel['name']}')")
planted = sum(1 for b in truth["bodies"] if b["chaotic"])
spots = sum(1 for b in truth["bodies"] if b["negative_control"])
print(f"planted:         {planted} chaotic bodies, {spots} bright spot (negative control)")
PY
echo "report:          $out/report.html"
