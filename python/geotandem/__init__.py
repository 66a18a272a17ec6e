"""geotandem from Python: geobody inventories from seismic cubes.

- :func:`open_store` - a component store, read-only: ``components()`` (a pandas DataFrame of every
  measure the index holds), ``mesh(key)`` (numpy vertices and triangles), ``runs()``, ``check()``.
- :func:`extract` - a cube's isosurface into a store, from a numpy array, an ``np.memmap`` larger
  than memory or an ``xarray.DataArray`` (seisnc), with the command line's parameters.
- :func:`run_workflow` - a recipe, as ``geotandem run-workflow``.
- :func:`synth` - a synthetic cube with planted bodies.
- :mod:`geotandem.errors` - the exceptions (the command line's messages, with file, line, column).

Everything runs in the C++ libraries the ``geotandem`` command uses (docs/python.md).
"""

from ._native import _core
from .compute import extract, extract_parameters, geometry_of, run_workflow, synth
from .errors import DataError, Error, FormatError, InvalidArgumentError, IoError, RecipeError
from .store import Store, open_store

__version__: str = _core.__version__

__all__ = [
    "__version__", "open_store", "Store", "extract", "extract_parameters", "geometry_of", "run_workflow", "synth",
    "Error", "InvalidArgumentError", "RecipeError", "IoError", "FormatError", "DataError",
]
