# Shared by the install tests: sourced after setting `name` (the test's name in messages) and
# `plugin` (the example's plugin name), with the script's arguments CMAKE BUILD_DIR EXAMPLE_DIR.
# It checks the arguments, makes a scratch directory removed on exit, defines fail/step/expect_in,
# installs the build tree into a fresh prefix and builds the example out of tree against it with
# find_package(geotandem). Afterwards: $prefix, $geotandem, $example_build, $library, $log, $tmp.

if [[ $# -ne 3 ]]; then
  echo "usage: $0 CMAKE BUILD_DIR EXAMPLE_SOURCE_DIR" >&2
  exit 2
fi
cmake=$1
build=$2
example=$3

tmp=$(mktemp -d "${TMPDIR:-/tmp}/geotandem-$name.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
prefix=$tmp/prefix
example_build=$tmp/example-build
log=$tmp/log

fail() {
  echo "$name: FAIL: $*" >&2
  exit 1
}
# Runs a step quietly; on failure shows its output and stops.
step() {
  local what=$1
  shift
  echo "$name: $what"
  if ! "$@" >"$log" 2>&1; then
    cat "$log" >&2
    fail "$what: '$*' exited non-zero"
  fi
}
# expect_in TEXT NEEDLE WHAT: TEXT contains NEEDLE literally.
expect_in() {
  [[ $1 == *"$2"* ]] || fail "$3: expected to find '$2' in:"$'\n'"$1"
}

# Nothing from the caller's environment may point the installed program elsewhere.
unset GEOTANDEM_PLUGIN_PATH LD_LIBRARY_PATH CMAKE_PREFIX_PATH geotandem_DIR

step "install the build tree into $prefix" "$cmake" --install "$build" --prefix "$prefix"
geotandem=$prefix/bin/geotandem
[[ -x $geotandem ]] || fail "no geotandem executable at $geotandem"
[[ -f $prefix/include/geotandem/workflow/plugin_abi.h ]] || fail "plugin_abi.h is not installed"
[[ -f $prefix/lib/cmake/geotandem/geotandemConfig.cmake ]] || fail "the package config is not installed"
# The installed program must run on the installed libraries, not on the build tree's.
if ldd "$geotandem" | grep -E "not found|$build" >"$log"; then
  cat "$log" >&2
  fail "the installed geotandem resolves libraries outside $prefix"
fi

generator=()
if command -v ninja >/dev/null; then generator=(-G Ninja); fi
step "configure the example against the installed package" "$cmake" -S "$example" -B "$example_build" \
  "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_CXX_FLAGS=-Werror
grep -q "geotandem_DIR:PATH=$prefix/" "$example_build/CMakeCache.txt" ||
  fail "find_package(geotandem) did not find the package in $prefix"
step "build the example" "$cmake" --build "$example_build" -j2
library=$example_build/geotandem_$plugin.so
[[ -f $library ]] || fail "the example did not produce $library"
