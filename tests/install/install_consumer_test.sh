#!/usr/bin/env bash
# The installed geotandem as a plugin author sees it:
#   1. `cmake --install` this build tree into a fresh prefix;
#   2. configure and build examples/custom_attribute out of tree with find_package(geotandem);
#   3. the installed geotandem lists the plugin from GEOTANDEM_PLUGIN_PATH, then, once the example
#      is installed into the prefix, without it;
#   4. `geotandem validate` accepts the example recipe, and a wrong parameter of the plugin is
#      reported with its name, the recipe's line and column, and the nearest valid name;
#   5. `geotandem run-workflow` runs the example recipe and its store holds components computed
#      from the plugin's attribute;
#   6. the installed geotandem writes and reads a netCDF-4 cube (the GDAL module, loaded on first use,
#      is installed beside the libraries).
# Usage: install_consumer_test.sh CMAKE BUILD_DIR EXAMPLE_SOURCE_DIR
set -euo pipefail

name=install_consumer
plugin=avg_abs_amplitude
# shellcheck source=install_common.sh
source "$(dirname "${BASH_SOURCE[0]}")/install_common.sh"
nm -D --defined-only "$library" | grep -q " geotandem_plugin_entry$" || fail "$library does not export the entry point"

check_listing() { # check_listing OUTPUT ORIGIN
  expect_in "$1" "$plugin (attribute, $2, version 1.0)" "plugins $plugin"
  expect_in "$1" "half_window" "plugins $plugin"
  expect_in "$1" "default 5; an integer in [0, 500]" "plugins $plugin"
  expect_in "$1" "half_traces" "plugins $plugin"
  expect_in "$1" "default 0; an integer in [0, 50]" "plugins $plugin"
  expect_in "$1" "in samples" "plugins $plugin"
}

echo "install_consumer: the installed geotandem finds the plugin through GEOTANDEM_PLUGIN_PATH"
out=$(GEOTANDEM_PLUGIN_PATH=$example_build "$geotandem" plugins "$plugin" 2>&1) ||
  fail "geotandem plugins $plugin failed with GEOTANDEM_PLUGIN_PATH: $out"
check_listing "$out" "$library"

echo "install_consumer: without the path and before installing the example, the plugin is unknown"
if out=$("$geotandem" plugins "$plugin" 2>&1); then fail "the plugin was found before it was installed: $out"; fi
expect_in "$out" "unknown plugin '$plugin'" "plugins $plugin before install"

step "install the example into the prefix" "$cmake" --install "$example_build" --prefix "$prefix"
installed=$prefix/lib/geotandem/plugins/geotandem_$plugin.so
[[ -f $installed ]] || fail "the example did not install to $installed"
out=$("$geotandem" plugins "$plugin" 2>&1) || fail "geotandem plugins $plugin failed after install: $out"
check_listing "$out" "$installed"
out=$("$geotandem" plugins 2>&1) || fail "geotandem plugins failed: $out"
expect_in "$out" "$plugin" "plugins"

echo "install_consumer: validate the example recipe"
recipe=$tmp/recipe.yaml
cp "$example/recipe.yaml" "$recipe"
out=$("$geotandem" validate "$recipe" 2>&1) || fail "the example recipe does not validate: $out"
expect_in "$out" "valid, 2 steps: $plugin extract" "validate"

# bad_recipe KEY_LINE: the example recipe with its half_window line replaced by KEY_LINE.
bad_recipe() {
  grep -q "^    half_window: " "$example/recipe.yaml" || fail "the example recipe has no half_window line"
  sed "s/^    half_window: .*/    $1/" "$example/recipe.yaml" >"$recipe"
}
# position NEEDLE: "line:column" of the first NEEDLE in the recipe (1-based).
position() {
  awk -v s="$1" '{ c = index($0, s); if (c > 0) { print NR ":" c; exit } }' "$recipe"
}
validate_fails() {
  if out=$("$geotandem" validate "$recipe" 2>&1); then fail "a bad recipe was accepted:"$'\n'"$(cat "$recipe")"; fi
}

echo "install_consumer: a misspelt parameter of the plugin names it, its place and the right name"
bad_recipe "half_windw: 2"
validate_fails
expect_in "$out" "$recipe:$(position half_windw): unknown key 'half_windw' in step 1 ($plugin)" "misspelt parameter"
expect_in "$out" "did you mean 'half_window'?" "misspelt parameter"

echo "install_consumer: a parameter of the plugin out of its range names it and its place"
bad_recipe "half_window: 9999"
validate_fails
expect_in "$out" "$recipe:$(position 9999):" "out-of-range parameter"
expect_in "$out" "half_window" "out-of-range parameter"
expect_in "$out" "9999" "out-of-range parameter"

echo "install_consumer: a parameter of the wrong type names it and its place"
bad_recipe "half_window: wide"
validate_fails
expect_in "$out" "$recipe:$(position wide):" "wrongly typed parameter"
expect_in "$out" "half_window" "wrongly typed parameter"

echo "install_consumer: run the example recipe (48^3 analytic cube, the plugin, extraction)"
cp "$example/recipe.yaml" "$recipe"
run=$tmp/run
mkdir "$run"
# From a directory of its own, so that nothing is written into the caller's working directory.
out=$(cd "$run" && "$geotandem" -q run-workflow "$recipe" --set "output.directory=$run/out" 2>&1) ||
  fail "run-workflow failed on the example recipe: $out"
components=$(sed -n 's/^components: \([0-9]*\) extracted.*/\1/p' <<<"$out")
[[ -n $components && $components -gt 0 ]] || fail "run-workflow extracted no components: $out"
store=$run/out/store
[[ -d $store ]] || fail "run-workflow wrote no store at $store: $out"
out=$("$geotandem" store ls "$store" 2>&1) || fail "store ls failed: $out"
expect_in "$out" "# $components of $components components" "store ls"
out=$("$geotandem" store runs "$store" 2>&1) || fail "store runs failed: $out"
expect_in "$out" "\"source\":\"$plugin(" "store runs (the extraction read the plugin's attribute)"

echo "install_consumer: the installed geotandem writes and reads netCDF-4 through the installed GDAL module"
module=$prefix/lib/libgeotandem_volume_gdal.so
[[ -f $module ]] || fail "the GDAL module is not installed at $module"
cube=$run/cube.nc
out=$(cd "$run" && "$geotandem" synth --shape 40 40 40 --out "$cube" 2>&1) || fail "synth to netCDF-4 failed: $out"
out=$("$geotandem" info "$cube" 2>&1) || fail "info on the netCDF-4 cube failed: $out"
expect_in "$out" "format:     netCDF-4" "info"
expect_in "$out" "40 inlines x 40 crosslines x 40 samples" "info"

echo "install_consumer: passed"
