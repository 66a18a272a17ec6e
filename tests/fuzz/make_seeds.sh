#!/usr/bin/env bash
# The fuzz targets' seeds, from the project's own files: the recipes under workflows/ and the
# regression inputs, the raw sidecar and SEG-Y file `geotandem synth` writes, and (with
# SURFACE_RECORD_SEEDS, the tool of that name) real working-surface records of an analytic cube.
#   tests/fuzz/make_seeds.sh GEOTANDEM SOURCE_DIR SEEDS_DIR [SURFACE_RECORD_SEEDS]
set -euo pipefail
geotandem=$1 root=$2 seeds=$3 surface_seeds=${4:-}
rm -rf "$seeds"
mkdir -p "$seeds/recipe" "$seeds/raw_sidecar" "$seeds/segy_header" "$seeds/surface_record"
cp "$root"/workflows/*.yaml "$root"/tests/fuzz/regressions/recipe_*.yaml "$seeds/recipe/"
export ASAN_OPTIONS=detect_leaks=0
if [ -n "$surface_seeds" ]; then
  "$surface_seeds" "$seeds/surface_record"
fi
"$geotandem" -q synth --kind analytic --shape 40 40 40 --out "$seeds/cube.raw" >/dev/null
cp "$seeds/cube.raw.json" "$seeds/raw_sidecar/sidecar.json"
cp "$root"/tests/fuzz/regressions/raw_sidecar_*.json "$seeds/raw_sidecar/"
"$geotandem" -q synth --kind analytic --shape 40 40 40 --out "$seeds/cube.segy" >/dev/null
cp "$seeds/cube.segy" "$seeds/segy_header/whole.segy"
head -c 8000 "$seeds/cube.segy" >"$seeds/segy_header/headers.segy"
# An irregular survey: the same file without its first trace and its 101st (400 bytes each after the
# 3600 bytes of file headers), read only under the NaN fill policy.
{
  head -c 3600 "$seeds/cube.segy"
  dd if="$seeds/cube.segy" bs=400 skip=10 count=99 status=none # 4000 bytes = 10 blocks of 400
  tail -c +$((3600 + 101 * 400 + 1)) "$seeds/cube.segy"
} >"$seeds/segy_header/irregular.segy"
# A placeholder in the first trace's place: flagged dead (bytes 29-30), every other header field 0
# but the sample count and interval (bytes 115-118), samples 0.
{
  head -c 3600 "$seeds/cube.segy"
  head -c 28 /dev/zero
  printf '\000\002'
  head -c 84 /dev/zero
  dd if="$seeds/cube.segy" bs=1 skip=$((3600 + 114)) count=4 status=none
  head -c $((122 + 160)) /dev/zero
  tail -c +$((3600 + 400 + 1)) "$seeds/cube.segy"
} >"$seeds/segy_header/placeholder.segy"
# Line numbers far apart: the first trace's inline (bytes 189-192) is -2147483645, where the
# others count from 1000 (differences beyond an int; the scan once overflowed on them).
{
  head -c $((3600 + 188)) "$seeds/cube.segy"
  printf '\200\000\000\003'
  tail -c +$((3600 + 192 + 1)) "$seeds/cube.segy"
} >"$seeds/segy_header/far_apart.segy"
