#!/usr/bin/env bash
# clang-tidy (.clang-tidy: bug-prone checks and naming, every warning an error) over the project's
# C++ sources (framework, plugins, schedulers, apps, python; not tests, bench or examples), with the
# compile database of a configured build (default: build/release, made by `cmake --preset release`).
#   scripts/clang_tidy.sh            the sources changed since BASE (GEOTANDEM_TIDY_BASE, default:
#                                    the merge-base with main, else HEAD~1), and every source when
#                                    a .clang-tidy or a header under include/ changed
#   scripts/clang_tidy.sh --all      every source (about 200 files: see the timing in .ci/run)
# Exits non-zero when a check fails. Prints the files checked and the time taken.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build=${GEOTANDEM_TIDY_BUILD:-build/release}
jobs=${GEOTANDEM_JOBS:-2}
[ -f "$build/compile_commands.json" ] || { echo "clang_tidy.sh: no $build/compile_commands.json (cmake --preset release)" >&2; exit 2; }
command -v run-clang-tidy >/dev/null || { echo "clang_tidy.sh: run-clang-tidy not found (apt-get install clang-tidy)" >&2; exit 2; }

sources() { git ls-files 'framework/*.cpp' 'plugins/*.cpp' 'schedulers/*.cpp' 'apps/*.cpp' 'python/src/*.cpp'; }
all=$(sources)
if [ "${1:-}" = "--all" ]; then
  files=$all
else
  base=${GEOTANDEM_TIDY_BASE:-$(git merge-base HEAD main 2>/dev/null || git rev-parse HEAD~1)}
  changed=$( (git diff --name-only "$base" -- . ; git ls-files --others --exclude-standard) | sort -u)
  if echo "$changed" | grep -qE '(^\.clang-tidy$|/include/.*\.(hpp|h)$)'; then
    files=$all
  else
    files=$(comm -12 <(echo "$all" | sort) <(echo "$changed" | grep -E '\.cpp$' | sort) || true)
  fi
fi
count=$(echo "$files" | grep -c . || true)
echo "clang-tidy: $count files, $jobs jobs"
[ "$count" -gt 0 ] || exit 0
start=$SECONDS
# GCC's warning flags and LTO options in the database are unknown to clang: not an error here.
# shellcheck disable=SC2086
run-clang-tidy -p "$build" -quiet -j "$jobs" -extra-arg=-Wno-unknown-warning-option \
  -extra-arg=-Wno-ignored-optimization-argument $files
echo "clang-tidy: $count files in $((SECONDS - start)) s"
