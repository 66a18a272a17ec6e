#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (address + undefined-behaviour sanitizers, the framework
# instrumented with fuzzer-no-link) in build/fuzz, seeds them with the project's own files (the
# recipes under workflows/, the raw sidecar and SEG-Y file `geotandem synth` writes), and runs each
# for a bounded time. Exit status: 0 when no target found a crash; the crashing inputs are left in
# build/fuzz/findings/<target>/.
#
#   tests/fuzz/run_fuzz.sh [SECONDS_PER_TARGET=45] [JOBS=2]
#
# Needs clang and libclang-rt-14-dev (libFuzzer); scripts/setup.sh installs them.
set -euo pipefail
seconds=${1:-45}
jobs=${2:-2}
root=$(cd "$(dirname "$0")/../.." && pwd)
build="$root/build/fuzz"

cmake -S "$root" -B "$build" -G Ninja \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DGEOTANDEM_SANITIZE=address,undefined,fuzzer-no-link \
  -DGEOTANDEM_BUILD_TESTS=OFF -DGEOTANDEM_BUILD_BENCH=OFF -DGEOTANDEM_FUZZ=ON >/dev/null
nice cmake --build "$build" -j"$jobs" --target fuzz_recipe fuzz_raw_sidecar fuzz_segy_header fuzz_surface_record surface_record_seeds

# The seed cubes come from a release build's geotandem when there is one (faster than building the
# instrumented one).
geotandem="$root/build/release/bin/geotandem"
if [ ! -x "$geotandem" ]; then
  nice cmake --build "$build" -j"$jobs" --target geotandem
  geotandem="$build/bin/geotandem"
fi

# Seeds: the project's own files.
seeds="$build/seeds"
"$root/tests/fuzz/make_seeds.sh" "$geotandem" "$root" "$seeds" "$build/bin/surface_record_seeds"

status=0
for target in recipe raw_sidecar segy_header surface_record; do
  corpus="$build/corpus/$target"
  findings="$build/findings/fuzz_$target"
  mkdir -p "$corpus" "$findings"
  max_len=65536
  [ "$target" = segy_header ] && max_len=700000
  [ "$target" = surface_record ] && max_len=1048576 # the seeds are whole records
  echo "fuzz_$target: ${seconds} s"
  if ! "$build/bin/fuzz_$target" "$corpus" "$seeds/$target" -max_total_time="$seconds" -max_len="$max_len" \
    -timeout=10 -rss_limit_mb=2048 -artifact_prefix="$findings/" -print_final_stats=1 2>"$build/fuzz_$target.log"; then
    echo "fuzz_$target: FOUND A CRASH; see $build/fuzz_$target.log and $findings/" >&2
    tail -40 "$build/fuzz_$target.log" >&2
    status=1
  else
    grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$build/fuzz_$target.log" | sed "s/^/fuzz_$target: /"
  fi
done
exit $status
