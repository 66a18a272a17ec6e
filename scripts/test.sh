#!/usr/bin/env bash
# Sets up (packages, configure, build) and runs the whole test suite.
# Usage: scripts/test.sh [PRESET]   (default: release; asan runs the suite under sanitizers)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
preset="${1:-release}"
"$here/scripts/setup.sh" "$preset"
cd "$here"
ctest --preset "$preset"
