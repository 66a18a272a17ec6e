#!/usr/bin/env bash
# A component step plugin as its author sees it, against the installed geotandem:
#   1. `cmake --install` this build tree into a fresh prefix;
#   2. configure and build examples/custom_component_step out of tree with find_package(geotandem);
#   3. the installed geotandem lists it as a component step, with its parameters and the host's
#      `selection`;
#   4. `geotandem validate` accepts the example recipe, and refuses the plugin placed before the
#      extraction (where attributes go) with the recipe's line and column;
#   5. `geotandem run-workflow` runs the recipe: the selection the plugin returned is in the store,
#      and it holds exactly the bodies of the previous selection whose elongation is in range,
#      largest first (checked against the store's own index with python3).
# Usage: install_component_step_test.sh CMAKE BUILD_DIR EXAMPLE_SOURCE_DIR
set -euo pipefail

name=install_component_step
plugin=shape_filter
# shellcheck source=install_common.sh
source "$(dirname "${BASH_SOURCE[0]}")/install_common.sh"
step "install the example into the prefix" "$cmake" --install "$example_build" --prefix "$prefix"
installed=$prefix/lib/geotandem/plugins/geotandem_$plugin.so
[[ -f $installed ]] || fail "the example did not install to $installed"

echo "install_component_step: the installed geotandem lists the plugin as a component step"
out=$("$geotandem" plugins "$plugin" 2>&1) || fail "geotandem plugins $plugin failed: $out"
expect_in "$out" "$plugin (component step, $installed, version 1.0)" "plugins $plugin"
for name in dip_min dip_max elongation_min elongation_max rank_by selection; do
  expect_in "$out" "$name" "plugins $plugin"
done
out=$("$geotandem" plugins 2>&1) || fail "geotandem plugins failed: $out"
expect_in "$out" "component steps:" "plugins"
expect_in "$out" "$plugin" "plugins"

echo "install_component_step: validate the example recipe"
recipe=$tmp/recipe.yaml
cp "$example/recipe.yaml" "$recipe"
out=$("$geotandem" validate "$recipe" 2>&1) || fail "the example recipe does not validate: $out"
expect_in "$out" "valid, 3 steps: extract remove_bubbles $plugin" "validate"

echo "install_component_step: the plugin where an attribute goes is refused at its line and column"
cat >"$tmp/early.yaml" <<'YAML'
version: 1
input:
  synthetic: {kind: analytic, shape: [48, 48, 48], seed: 1}
steps:
  - step: shape_filter
  - step: extract
    iso: 0.45
YAML
if out=$("$geotandem" validate "$tmp/early.yaml" 2>&1); then fail "a component step before the extraction was accepted"; fi
expect_in "$out" "$tmp/early.yaml:5:5: step 1 ($plugin) works on components" "component step in an attribute slot"

echo "install_component_step: an out-of-range parameter of the plugin is refused at its line and column"
sed "s/^    elongation_min: .*/    elongation_min: 1.5/" "$example/recipe.yaml" >"$recipe"
if out=$("$geotandem" validate "$recipe" 2>&1); then fail "elongation_min: 1.5 was accepted"; fi
line=$(grep -n "elongation_min: 1.5" "$recipe" | cut -d: -f1)
expect_in "$out" "$recipe:$line:21:" "out-of-range parameter"
expect_in "$out" "elongation_min" "out-of-range parameter"

echo "install_component_step: run the example recipe"
cp "$example/recipe.yaml" "$recipe"
run=$tmp/run
mkdir "$run"
out=$(cd "$run" && "$geotandem" -q run-workflow "$recipe" --set "output.directory=$run/out" 2>&1) ||
  fail "run-workflow failed on the example recipe: $out"
store=$run/out/store
"$geotandem" store ls "$store" --selection kept --json >"$tmp/kept.json" || fail "store ls --selection kept failed"
"$geotandem" store ls "$store" --selection elongated --sort selection --json >"$tmp/elongated.json" ||
  fail "store ls --selection elongated failed"
"$geotandem" store selections "$store" >"$tmp/selections.txt" || fail "store selections failed"
expect_in "$(cat "$tmp/selections.txt")" "\"step\":\"$plugin\"" "store selections"
python3 - "$tmp/kept.json" "$tmp/elongated.json" <<'PY' || fail "the selection is not what the plugin's ranges describe"
import json, sys
kept = json.load(open(sys.argv[1]))
got = [c["key"] for c in json.load(open(sys.argv[2]))]
size = lambda c: c["volume"] if c["closed"] else c["area"]
inside = [c for c in kept if c["elongation"] >= 0.2]
want = [c["key"] for c in sorted(inside, key=size, reverse=True)]
print(f"install_component_step: {len(kept)} kept bodies, {len(want)} with elongation >= 0.2")
if not want or len(want) == len(kept):
    sys.exit(f"the recipe does not discriminate: {len(want)} of {len(kept)}")
if got != want:
    sys.exit(f"selection {got} != expected {want}")
PY
[[ -f $run/out/report.html ]] || fail "no report"
[[ -f $run/out/bodies.ply ]] || fail "no export of the newest selection"
echo "install_component_step: passed"
