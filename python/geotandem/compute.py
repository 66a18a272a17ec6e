"""Extraction and recipes from Python: the command line's ``extract``, ``run-workflow`` and
``synth``, through the same C++ functions, on numpy arrays, memory maps and xarray DataArrays.

Each call releases the GIL while it works, shows progress (see :mod:`geotandem.progress`), and
stops within about a second on KeyboardInterrupt (Ctrl-C, the notebook's stop button), keeping what
it committed: run it again to resume.
"""

from __future__ import annotations

import hashlib
import inspect
import mmap
import os
import uuid
from pathlib import Path
from typing import Any, Dict, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _native, progress as _progress
from ._native import _core
from .store import Store

__all__ = ["extract", "run_workflow", "synth", "extract_parameters", "geometry_of"]

PathLike = Union[str, "os.PathLike[str]"]

# The extract step's declared parameters (name, type, default as text, help, ...): the command
# line's options and the recipes' step take theirs from the same declarations.
_PARAMS = _core.extract_params()


def extract_parameters() -> Dict[str, Dict[str, Any]]:
    """The extraction's parameters as the C++ side declares them: {name: {type, default, help,
    valid, choices, unit}}; defaults are the command line's and the recipes'."""
    return {p["name"]: {k: v for k, v in p.items() if k != "name"} for p in _PARAMS}


def _typed_default(p: Dict[str, Any]) -> Any:
    text = p["default"]
    if text is None:
        return inspect.Parameter.empty
    if p["type"] == "real":
        return float(text)
    if p["type"] == "integer":
        return int(text)
    if p["type"] == "boolean":
        return text == "true"
    return text


def _param_text(value: Any) -> str:
    if isinstance(value, (bool, np.bool_)):
        return "true" if value else "false"
    if isinstance(value, (float, np.floating)):
        return repr(float(value))
    return str(value)


def geometry_of(volume: Any = None, *, shape: Optional[Sequence[int]] = None,
                spacing: Optional[Sequence[float]] = None, origin: Optional[Sequence[float]] = None,
                z_unit: Optional[str] = None, inline0: Optional[float] = None, crossline0: Optional[float] = None,
                geometry: Optional[Mapping[str, Any]] = None) -> Dict[str, Any]:
    """The cube geometry geotandem needs (the raw sidecar's "geometry" keys, with "shape").

    An ``xarray.DataArray`` in the seisnc layout gives it: dims ``iline``, ``xline`` and ``twt``
    (milliseconds) or ``depth`` (metres), with their coordinates as line numbers and sample
    times/depths, and 2-D coordinates ``cdp_x``, ``cdp_y`` (over iline, xline) giving the survey
    affine from three corner traces. Otherwise: ``spacing=(bin_i, bin_j, dz)`` (metres, metres,
    sample unit) and ``origin=(x0, y0, z0)``, with inline index i pointing east and j north;
    ``geometry`` (a dict such as ``Store.geometry``) overrides any key. Unset keys take the C++
    defaults (25 m bins, 4 ms samples).
    """
    g: Dict[str, Any] = {"inline0": 1.0, "inline_step": 1.0, "crossline0": 1.0, "crossline_step": 1.0,
                         "z0": 0.0, "dz": 4.0, "z_unit": "ms",
                         "affine": {"x0": 0.0, "xi": 25.0, "xj": 0.0, "y0": 0.0, "yi": 0.0, "yj": 25.0}}
    if volume is not None and hasattr(volume, "dims") and hasattr(volume, "coords"):
        g.update(_seisnc_geometry(volume))
    if shape is not None:
        g["shape"] = [int(n) for n in shape]
    elif volume is not None:
        g["shape"] = [int(n) for n in np.shape(volume)]
    if spacing is not None:
        bi, bj, dz = (float(v) for v in spacing)
        g["affine"].update({"xi": bi, "xj": 0.0, "yi": 0.0, "yj": bj})
        g["dz"] = dz
    if origin is not None:
        x0, y0, z0 = (float(v) for v in origin)
        g["affine"].update({"x0": x0, "y0": y0})
        g["z0"] = z0
    if z_unit is not None:
        g["z_unit"] = z_unit
    if inline0 is not None:
        g["inline0"] = float(inline0)
    if crossline0 is not None:
        g["crossline0"] = float(crossline0)
    if geometry is not None:
        for k, v in geometry.items():
            g[k] = dict(v) if k == "affine" else v
    return g


def _seisnc_geometry(da: Any) -> Dict[str, Any]:
    dims = tuple(da.dims)
    z_name = "twt" if "twt" in dims else "depth" if "depth" in dims else None
    if len(dims) != 3 or "iline" not in dims or "xline" not in dims or z_name is None:
        raise ValueError(f"a DataArray with dims {dims}: geotandem reads the seisnc layout (iline, xline, "
                         "twt or depth); transpose or rename it, or pass a numpy array with spacing= and origin=")
    if dims != ("iline", "xline", z_name):
        raise ValueError(f"dims {dims}: transpose to ('iline', 'xline', '{z_name}') first "
                         "(da.transpose('iline', 'xline', ...)); geotandem reads C order [inline][crossline][sample]")

    def axis(name: str) -> Tuple[float, float]:
        values = np.asarray(da.coords[name].values, dtype=np.float64) if name in da.coords else None
        if values is None or values.size < 2:
            return (float(values[0]) if values is not None and values.size else 1.0), 1.0
        return float(values[0]), float(values[1] - values[0])

    g: Dict[str, Any] = {}
    g["inline0"], g["inline_step"] = axis("iline")
    g["crossline0"], g["crossline_step"] = axis("xline")
    g["z0"], g["dz"] = axis(z_name)
    g["z_unit"] = "ms" if z_name == "twt" else "m"
    if "cdp_x" in da.coords and "cdp_y" in da.coords:
        x = np.asarray(da.coords["cdp_x"].transpose("iline", "xline").values, dtype=np.float64)
        y = np.asarray(da.coords["cdp_y"].transpose("iline", "xline").values, dtype=np.float64)
        ni, nj = x.shape
        # The affine from three corner traces, as interpretation systems keep it.
        g["affine"] = {"x0": x[0, 0], "xi": (x[-1, 0] - x[0, 0]) / max(ni - 1, 1),
                       "xj": (x[0, -1] - x[0, 0]) / max(nj - 1, 1),
                       "y0": y[0, 0], "yi": (y[-1, 0] - y[0, 0]) / max(ni - 1, 1),
                       "yj": (y[0, -1] - y[0, 0]) / max(nj - 1, 1)}
        g["affine"] = {k: float(v) for k, v in g["affine"].items()}
    return g


def _raw_layout_file(a: np.ndarray) -> Optional[str]:
    """The file of a memmap whose bytes are a raw cube as they are (float32 little-endian, C order,
    the whole file from byte 0): worker processes can read that file itself."""
    if not isinstance(a, np.memmap) or getattr(a, "filename", None) is None:
        return None
    if a.dtype != np.dtype("<f4") or not a.flags.c_contiguous or getattr(a, "offset", 0) != 0:
        return None
    base = a
    while isinstance(base.base, np.memmap):
        base = base.base
    if base is not a and base.shape != a.shape:
        return None  # a view of part of the file
    if os.path.getsize(a.filename) != a.nbytes:
        return None
    return str(a.filename)


def _crs_text(crs: Any) -> str:
    """crs= as the C++ side parses it: "" for none, else an EPSG code or a WKT."""
    if crs is None:
        return ""
    if hasattr(crs, "to_wkt"):  # pyproj.CRS
        return str(crs.to_wkt())
    if isinstance(crs, int) and not isinstance(crs, bool):
        return f"EPSG:{crs}"
    if isinstance(crs, str):
        if not crs.strip():
            raise ValueError("crs= is empty: give an EPSG code ('EPSG:23031') or a WKT, or leave it out")
        return crs
    raise TypeError(f"crs= must be an EPSG code, a WKT or a pyproj.CRS, not {type(crs).__name__}")


def extract(volume: Any, iso: float, *, out: PathLike, workers: Optional[int] = None, fresh: bool = False,
            nan: str = "error", no_data: Optional[float] = None, spacing: Optional[Sequence[float]] = None,
            origin: Optional[Sequence[float]] = None, z_unit: Optional[str] = None,
            geometry: Optional[Mapping[str, Any]] = None, crs: Any = None,
            progress: _progress.ProgressArg = None, **params: Any) -> Store:
    # The docstring is completed below from the C++ declarations.
    given = {"iso": iso, **params}
    names = {p["name"] for p in _PARAMS}
    for name in given:
        if name not in names:
            raise TypeError(f"extract() got an unexpected keyword argument '{name}' "
                            f"(the extraction's parameters: {', '.join(sorted(names))})")
    texts = {k: _param_text(v) for k, v in given.items()}
    crs_text = _crs_text(crs)
    report, sink = _progress.resolve(progress)  # not `mode`: an extraction parameter has that name
    out = os.fspath(out)
    common = dict(params=texts, out=out, workers=workers, fresh=fresh, nan=nan, no_data=no_data,
                  worker_command=_native.worker_command(), mode=report, sink=sink)
    if isinstance(volume, (str, os.PathLike)):
        # A file, as `geotandem extract FILE` reads it.
        result = _core.extract(None, os.fspath(volume), {}, crs_text, "", 0, "", **common)
        return _finish(out, result)
    data = volume.data if hasattr(volume, "dims") and hasattr(volume, "coords") else volume
    g = geometry_of(volume, spacing=spacing, origin=origin, z_unit=z_unit, geometry=geometry)
    is_memmap = isinstance(data, np.memmap)
    if is_memmap and (data.dtype != np.float32 or not data.flags.c_contiguous):
        raise ValueError("a memmap is read in place only as C-contiguous float32 (dtype '<f4'); converting it "
                         "would copy it whole into memory: np.memmap(file, dtype='<f4', shape=...) or convert it "
                         "to a raw file first")
    array = data if is_memmap else np.ascontiguousarray(np.asarray(data), dtype=np.float32)
    if array.ndim != 3:
        raise ValueError(f"a cube has three axes (inline, crossline, sample), not shape {array.shape}")
    # A read-only memmap is read from its file (pread: the same bytes, without faulting the mapping
    # into this process's resident memory); a writable one may hold changes not in the file yet.
    file, offset = "", 0
    if is_memmap and getattr(data, "mode", None) == "r" and getattr(data, "filename", None):
        at = _memmap_offset(data)
        if at is not None:
            file, offset = str(data.filename), at
    source = _source(array, is_memmap)
    if not workers:
        result = _core.extract(array, "", g, crs_text, file, offset, source, **common)
        return _finish(out, result)
    # Worker processes cannot see this process's memory: they read a raw cube file. A memmap of a
    # raw-layout file is read where it is (a link to it and a sidecar beside the store); any other
    # array is written, block by block, to OUT.input.<unique>.raw, removed when the run ends. The
    # name is this call's own: a second call into the same store, refused by the store's lock only
    # once its copy is written, must not replace the file the first call's workers read. The
    # store's identity is `source` (the samples), not the copy's name or time, so a rerun resumes.
    base = out.rstrip("/")
    cube = Path(f"{base}.input.{os.getpid()}-{uuid.uuid4().hex[:12]}.raw")
    sidecar = Path(str(cube) + ".json")
    own = _raw_layout_file(array) if is_memmap else None
    try:
        if own is not None:
            cube.symlink_to(os.path.abspath(own))
            _core.write_raw_sidecar(str(cube), g)
        else:
            _core.write_raw(array, g, file, offset, str(cube), report, sink)
        result = _core.extract(None, str(cube), {}, crs_text, "", 0, source, **common)
    finally:
        for path in (cube, sidecar):
            if path.is_symlink() or path.exists():
                path.unlink()
    return _finish(out, result)


def _memmap_offset(m: np.memmap) -> Optional[int]:
    """The byte of the memmap's file where the array's first sample is (a view may start later
    than the map): numpy maps from the allocation boundary at or before the memmap's offset."""
    mm = getattr(m, "_mmap", None)
    if mm is None:
        return None
    offset = int(getattr(m, "offset", 0))
    start = offset - offset % mmap.ALLOCATIONGRANULARITY
    return start + (m.ctypes.data - np.frombuffer(mm, dtype=np.uint8).ctypes.data)


def _source(array: np.ndarray, is_memmap: bool) -> str:
    """What identifies the samples (the store records it, and refuses to resume a run on other
    samples): a memmap's file when it is the whole file (its size, time and sampled bytes are
    fingerprinted as for any input file); otherwise a digest of the array's bytes."""
    if is_memmap:
        own = _raw_layout_file(array)
        if own is not None:
            return os.path.abspath(own)
        # Part of a file: its name, where the array lies in it, and the file's size and time (the
        # store then refuses to resume on a file that changed, as for any input file).
        info = os.stat(array.filename)
        return (f"numpy memmap {array.filename} offset {getattr(array, 'offset', 0)} shape {array.shape} "
                f"file size {info.st_size} mtime_ns {info.st_mtime_ns}")
    digest = hashlib.blake2b(memoryview(array).cast("B"), digest_size=16).hexdigest()
    return f"numpy array {array.shape} blake2b {digest}"


def _finish(out: str, result: Dict[str, Any]) -> Store:
    store = Store(out)
    store.last_result = result  # type: ignore[attr-defined]
    return store


def _extract_doc() -> str:
    lines = [
        "Extracts the isosurface ``value >= iso`` of a cube into a component store at ``out``, as",
        "``geotandem extract`` does, and returns the store opened (``Store``; ``.last_result`` holds",
        "the run's figures). Components are committed as they are found: an interrupted call keeps",
        "them, and calling again with the same arguments resumes (``fresh=True`` starts over).",
        "",
        "``volume``: a numpy array [inline, crossline, sample] (converted to C-contiguous float32",
        "when it is not); an ``np.memmap`` (C-contiguous '<f4'), read block by block in place, never",
        "whole, so it may be larger than memory; an ``xarray.DataArray`` in the seisnc layout (its",
        "coordinates give the geometry, see :func:`geometry_of`); or a file path (any format",
        "``geotandem info`` reads). ``spacing``, ``origin``, ``z_unit``, ``geometry``: the geometry of",
        "a plain array.",
        "",
        "``workers``: local worker processes (the manager/worker runtime). They cannot see this",
        "process's memory: a memmap of a raw float32 file is read from its own file (linked beside",
        "the store with a sidecar), any other array is first written to ``OUT.input.<unique>.raw`` (removed",
        "afterwards). Default for arrays: 0, in this process; for files: one per core, as on the",
        "command line.",
        "",
        "``nan``: missing samples (NaN, infinite, or ``no_data``) are an ``'error'`` (DataError) or",
        "``'fill'`` (outside). ``progress``: see :mod:`geotandem.progress`.",
        "",
        "``crs``: the coordinate reference system of the map coordinates (x, y), as ``--crs`` takes it:",
        "an EPSG code (``'EPSG:23031'``), a WKT, or an object with ``to_wkt()`` (``pyproj.CRS``). It",
        "replaces what a file says; without it a file's own CRS is kept and an array has none. The",
        "store keeps it (``Store.crs``, ``components().attrs['crs']``) and every export says it.",
        "",
        "The extraction's parameters (declared by the C++ extract step; the command line and recipes",
        "take the same defaults):",
        "",
    ]
    for p in _PARAMS:
        default = "required" if p["default"] is None else f"default {p['default']}"
        lines.append(f"``{p['name']}`` ({p['valid']}; {default}): {p['help']}")
    lines += ["", "Raises geotandem.errors.InvalidArgumentError for a bad parameter (the message names it),",
              "DataError for refused samples, IoError when the store cannot be written."]
    return "\n".join(lines)


extract.__doc__ = _extract_doc()
extract.__signature__ = inspect.signature(extract).replace(  # type: ignore[attr-defined]
    parameters=[q for q in inspect.signature(extract).parameters.values() if q.kind != q.VAR_KEYWORD] + [
        inspect.Parameter(p["name"], inspect.Parameter.KEYWORD_ONLY, default=_typed_default(p))
        for p in _PARAMS if p["name"] != "iso"])


def run_workflow(recipe: PathLike, overrides: Optional[Mapping[str, Any]] = None, *, fresh: bool = False,
                 dry_run: bool = False, progress: _progress.ProgressArg = None) -> Dict[str, Any]:
    """Runs a recipe file as ``geotandem run-workflow RECIPE --set KEY=VALUE ...`` does.

    ``overrides``: {"dotted.path": value}, e.g. ``{"steps.extract.iso": 0.4, "execution.workers": 2,
    "output.directory": "out"}`` (booleans as true/false). Returns the outcome: output_dir,
    store_dir, report, components, kept, extraction_reused, and ``store`` (the opened Store; None
    on a dry run). A rerun reuses the finished steps, as on the command line.

    Raises geotandem.errors.RecipeError with the recipe's file, line and column for an invalid
    recipe (``str(e)`` is the command line's message).
    """
    sets = [f"{k}={_param_text(v)}" for k, v in (overrides or {}).items()]
    mode, sink = _progress.resolve(progress)
    outcome = _core.run_workflow(os.fspath(recipe), sets, fresh, dry_run, _native.worker_command(),
                                 _native.plugin_path(), mode, sink)
    outcome["store"] = None if dry_run or not outcome["store_dir"] else Store(outcome["store_dir"])
    return outcome


def synth(out: PathLike, *, kind: str = "analytic", shape: Sequence[int] = (128, 128, 128), seed: int = 1,
          overwrite: bool = False, progress: _progress.ProgressArg = None) -> str:
    """Writes a procedural synthetic cube with planted bodies, as ``geotandem synth`` does: kind
    ``"analytic"`` (an attribute-like field in [0, 1], bodies at iso 0.5) or ``"seismic"``; the
    format comes from the extension of ``out`` (.raw, .nc, .zarr, .tif, .segy); the ground truth
    goes to OUT.truth.json. Returns ``out``. Read a .raw cube with ``np.memmap(out, dtype='<f4',
    mode='r', shape=shape)``."""
    mode, sink = _progress.resolve(progress)
    _core.synth(os.fspath(out), kind, [int(n) for n in shape], int(seed), overwrite, mode, sink)
    return os.fspath(out)
