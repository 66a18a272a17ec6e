#!/usr/bin/env bash
# Installs every Debian 12 package geotandem needs (idempotent), then configures and builds.
# Usage: scripts/setup.sh [PRESET ...]   (default preset: release)
# libjs-three: three.js, inlined into run reports for the 3-D view of the bodies; chromium: the
# headless browser the report test draws that view with. ccache: a rebuild, or a build of the same
# commit in another clone, reuses the objects already compiled (cmake -DGEOTANDEM_CCACHE=OFF turns it off).
# python3-*, pybind11-dev, jupyter-nbconvert: the Python package (docs/python.md), installed after the
# release (or dev) build into .venv, a virtual environment that sees Debian's numpy, pandas,
# xarray and matplotlib; nothing comes from PyPI.
# Environment: GEOTANDEM_SKIP_APT=1 skips the package step (for machines that already have them);
# GEOTANDEM_SKIP_PYTHON=1 skips installing the Python package into .venv (the build still makes it);
# GEOTANDEM_BENCH_DEPS=1 also installs the bench-only packages (bench_packages below: VTK and
# meshoptimizer for bench_flying_edges_meshopt; VTK pulls in Java, Open MPI and Qt, so neither CI nor
# a default setup installs them, and without them that one bench is left out of the build).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"

packages=(
  build-essential cmake ninja-build pkg-config git ca-certificates ccache
  libgtest-dev libgmock-dev libbenchmark-dev
  libgdal-dev gdal-bin libsegyio-dev python3-segyio
  libopenmesh-dev libeigen3-dev
  libzmq3-dev cppzmq-dev
  nlohmann-json3-dev libyaml-cpp-dev libcli11-dev
  libsqlite3-dev sqlite3 libxxhash-dev zlib1g-dev
  clang-format clang-tidy
  clang libclang-rt-14-dev
  slurmctld slurmd slurm-client munge iproute2
  libjs-three chromium
  python3-dev pybind11-dev python3-numpy python3-pandas python3-xarray python3-pytest python3-matplotlib
  python3-nbconvert jupyter-nbconvert python3-ipykernel python3-venv python3-setuptools python3-wheel
  python3-fiona python3-gdal
)
bench_packages=(libvtk9-dev libmeshoptimizer-dev)
[ "${GEOTANDEM_BENCH_DEPS:-0}" != 1 ] || packages+=("${bench_packages[@]}")

as_root() {
  if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi
}

if [ "${GEOTANDEM_SKIP_APT:-0}" != 1 ]; then
  missing=()
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    echo "setup: installing ${#missing[@]} Debian packages: ${missing[*]}"
    as_root apt-get update -qq
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
  else
    echo "setup: all Debian packages present"
  fi
fi

presets=("$@")
[ ${#presets[@]} -gt 0 ] || presets=(release)
jobs="${GEOTANDEM_JOBS:-$(nproc)}"
for preset in "${presets[@]}"; do
  echo "setup: configuring and building preset '$preset' with $jobs jobs"
  cmake --preset "$preset" >/dev/null
  cmake --build --preset "$preset" -j "$jobs"
done

# The Python package into .venv (`.venv/bin/python -c "import geotandem"`), from the release or dev
# tree just built: setup.py reuses it, so nothing is compiled twice.
if [ "${GEOTANDEM_SKIP_PYTHON:-0}" != 1 ]; then
  for preset in "${presets[@]}"; do
    case "$preset" in release | dev) ;; *) continue ;; esac
    echo "setup: installing the Python package into $here/.venv (from build/$preset)"
    [ -x .venv/bin/python ] || /usr/bin/python3 -m venv --system-site-packages .venv
    GEOTANDEM_PYTHON_PRESET="$preset" GEOTANDEM_JOBS="$jobs" .venv/bin/pip install --quiet --disable-pip-version-check \
      --no-build-isolation --no-deps --no-index .
    break
  done
fi
