"""Shared fixtures of the Python package's tests: the geotandem executable (the independent oracle:
the command line's own output), scratch directories, and stores made once per session."""

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

BINARY = os.environ.get("GEOTANDEM_TEST_BINARY", "geotandem")
STORE_WRITER = os.environ.get("GEOTANDEM_TEST_STORE_WRITER", "store_writer")
SOURCE = Path(os.environ.get("GEOTANDEM_TEST_SOURCE_DIR", Path(__file__).resolve().parents[2]))
SCRATCH = Path(os.environ.get("GEOTANDEM_TEST_SCRATCH", "/tmp/geotandem-python-tests"))


def cli(*args, check=True, **kwargs):
    """Runs the geotandem executable; returns the CompletedProcess (text)."""
    return subprocess.run([BINARY, *map(str, args)], check=check, capture_output=True, text=True, **kwargs)


def ls_json(store, *extra):
    return json.loads(cli("store", "ls", store, "--json", *extra).stdout)


def python_env():
    """The environment a child Python process needs to import the package under test."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in sys.path if p)
    return env


@pytest.fixture(scope="session")
def scratch_root(tmp_path_factory):
    root = SCRATCH / f"{Path(sys.argv[-1]).stem}-{os.getpid()}"
    if root.exists():
        shutil.rmtree(root)
    root.mkdir(parents=True)
    yield root
    shutil.rmtree(root, ignore_errors=True)


@pytest.fixture(scope="session")
def analytic_cube(scratch_root):
    """A 64^3 analytic cube (bodies at iso 0.5) as a raw file, written by `geotandem synth`."""
    path = scratch_root / "analytic64.raw"
    cli("synth", "--kind", "analytic", "--shape", "64", "64", "64", "--seed", "3", "--out", path)
    return path


@pytest.fixture(scope="session")
def quickstart_store(scratch_root):
    """The quickstart recipe run by the command line (its store holds the steps' selections)."""
    out = scratch_root / "quickstart-out"
    cli("-q", "run-workflow", SOURCE / "workflows" / "quickstart.yaml", "--set", f"output.directory={out}",
        "--set", "input.synthetic.shape=[96,96,64]")
    return out / "store"


def read_raw(path):
    """A raw cube as numpy, from its sidecar (the test's own reading of the documented format)."""
    sidecar = json.loads(Path(str(path) + ".json").read_text())
    return np.fromfile(path, dtype="<f4").reshape(sidecar["shape"]), sidecar
