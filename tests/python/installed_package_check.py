"""The package as `scripts/setup.sh` installs it into .venv, used as a user would: from another
directory, without PYTHONPATH, so that only the installed copy (its _core, libraries and the
executable its workers run) can be imported.

Run by ctest (python_installed_package) with .venv's interpreter; argv[1] is a scratch directory.
Exits non-zero, saying why, when anything differs."""

import sys
from pathlib import Path

import numpy as np

import geotandem

scratch = Path(sys.argv[1])
scratch.mkdir(parents=True, exist_ok=True)
package = Path(geotandem.__file__).resolve()
if ".venv" not in package.parts:
    sys.exit(f"geotandem was imported from {package}, not from the virtual environment")

# A small field with a few closed bodies: the in-process route and two workers (the installed
# executable) must give the same components.
cube_path = geotandem.synth(scratch / "cube.raw", kind="analytic", shape=(48, 48, 48), seed=3, overwrite=True)
cube = np.fromfile(cube_path, dtype="<f4").reshape(48, 48, 48)
alone = geotandem.extract(cube, 0.5, out=scratch / "alone", fresh=True, block_size=24)
paired = geotandem.extract(cube, 0.5, out=scratch / "paired", fresh=True, block_size=24, workers=2)
a = alone.components().set_index("key").volume.sort_index()
b = paired.components().set_index("key").volume.sort_index()
if len(a) == 0:
    sys.exit("the analytic cube gave no component")
if list(a.index) != list(b.index) or not np.allclose(a.values, b.values, rtol=1e-3):
    sys.exit(f"in process {dict(a)} but with two workers {dict(b)}")
print(f"geotandem {geotandem.__version__} from {package.parent}: {len(a)} components, the same with two workers")
