"""A component store from Python: the index as a pandas DataFrame, bodies as numpy arrays.

The store is opened read-only through the C++ store library (the same queries as ``geotandem store
ls`` and the same reader as the exports), so it is safe to read while a run writes into it: each
call sees the components committed so far.
"""

from __future__ import annotations

import json
import os
from typing import Any, Dict, Iterable, Iterator, List, Optional, Tuple

import numpy as np
import pandas as pd

from ._native import _core
from .errors import FormatError

__all__ = ["Store", "open_store"]


class Store:
    """A component store (a directory made by ``geotandem extract``, a recipe, or
    :func:`geotandem.extract`), opened read-only.

    >>> s = geotandem.open_store("quickstart-out/store")
    >>> df = s.components()                 # one row per component
    >>> v, t = s.mesh(int(df.key[0]))        # world coordinates, triangles
    """

    def __init__(self, directory: "os.PathLike[str] | str") -> None:
        self._core = _core.Store(os.fspath(directory))
        self.directory: str = self._core.directory

    def __repr__(self) -> str:
        return f"geotandem.Store({self.directory!r}, {len(self)} components)"

    def __len__(self) -> int:
        return int(self._core.size())

    @property
    def geometry(self) -> Dict[str, Any]:
        """The cube's geometry: shape, line numbering, sampling and the survey affine."""
        return json.loads(self._core.geometry_json())

    @property
    def crs(self) -> Optional[Dict[str, Any]]:
        """The CRS of the map coordinates (x, y) as the store keeps it: ``name``, ``code``
        ("EPSG:23031"), ``unit`` ("m", "ft", "ftUS"), ``unit_name``, ``metres_per_unit`` and
        ``wkt`` (usable as ``pyproj.CRS(store.crs["wkt"])`` or ``GeoDataFrame.set_crs``); None
        when the store was made without one ("no CRS given")."""
        return self.geometry.get("crs")

    @property
    def crs_label(self) -> str:
        """``"ED50 / UTM zone 31N (EPSG:23031)"``, or ``"no CRS given"``."""
        crs = self.crs
        if not crs:
            return "no CRS given"
        return crs["name"] + (f" ({crs['code']})" if crs.get("code") else "")

    @property
    def info(self) -> Dict[str, Any]:
        """The whole store.json (format version, geometry, creation info)."""
        return json.loads(self._core.info_json())

    def components(self, selection: Optional[str] = None) -> pd.DataFrame:
        """Every component of the index as a DataFrame, one row per component in key order.

        Columns: ``key`` (uint64, never negative), ``vertex_count``, ``triangle_count``, ``volume``
        (world units: m3, or m2.ms for time cubes), ``area``, ``centroid_x/y/z``, ``box_min_x/y/z``,
        ``box_max_x/y/z``, ``samples`` (the volume in samples: voxels enclosed; nullable integer,
        NA in stores written before samples were counted), ``obb_center_x/y/z``, ``obb_axis0_x/y/z`` to ``obb_axis2_x/y/z`` (unit
        vectors, longest first), ``obb_half_extent0..2``, ``azimuth`` (degrees from north, axial),
        ``dip``, ``elongation``, ``closed``, ``cut_by_border``, ``cut_faces`` ("i-,k+"),
        ``cap_area``, ``run`` (nullable integer), ``shard``, ``offset``, ``length``, ``checksum``
        (xxh64, hex) - the fields of ``geotandem store ls --json`` - and one boolean column
        ``in_<name>`` per named selection (e.g. ``in_sorted``).

        With ``selection="sorted"``: only that selection's members, in the order it was saved,
        with their ``rank`` (0-based) in it.

        ``df.attrs["crs"]`` is the WKT of the CRS of the x and y columns (None without one) and
        ``df.attrs["crs_label"]`` its name, or "no CRS given".
        """
        cols = self._core.columns(selection or "")
        run = pd.array(cols.pop("run"), dtype="Int64")
        known = cols.pop("run_known")
        run[~known] = pd.NA
        samples = pd.array(cols.pop("samples"), dtype="Int64")
        samples[~cols.pop("samples_known")] = pd.NA
        df = pd.DataFrame(cols)
        df.insert(df.columns.get_loc("volume") + 1, "samples", samples)
        df.insert(df.columns.get_loc("cap_area") + 1, "run", run)
        for column in ("cut_faces", "shard", "checksum"):
            df[column] = df[column].astype(object)
        keys = df["key"].to_numpy(dtype=np.uint64)
        for sel in self._core.selections():
            members = self._core.selection_keys(sel["name"])
            df["in_" + sel["name"]] = np.isin(keys, members)
        if selection:
            df.insert(1, "rank", np.arange(len(df), dtype=np.int64))
        # The CRS of x and y (centroid_x, box_min_x, ...): df.attrs["crs"] is its WKT, or None.
        crs = self.crs
        df.attrs["crs"] = crs["wkt"] if crs else None
        df.attrs["crs_label"] = self.crs_label
        return df

    def selections(self) -> pd.DataFrame:
        """The named selections (name, size, created, parameters as a dict)."""
        rows = self._core.selections()
        for r in rows:
            r["parameters"] = _json_or_text(r["parameters"])
        return pd.DataFrame(rows, columns=["name", "size", "created", "parameters"])

    def selection(self, name: str) -> np.ndarray:
        """The keys of a selection, in the order it was saved (uint64)."""
        return self._core.selection_keys(name)

    def runs(self) -> List[Dict[str, Any]]:
        """The runs that wrote the store, as ``geotandem store runs --json`` lists them: id,
        started, ended (None while running or after a kill), components, and their parameters and
        statistics as dicts."""
        out = []
        for r in self._core.runs():
            r["parameters"] = _json_or_text(r["parameters"])
            r["statistics"] = _json_or_text(r["statistics"])
            out.append(r)
        return out

    def mesh(self, key: int, caps: bool = True) -> Tuple[np.ndarray, np.ndarray]:
        """One component's surface: ``(vertices, triangles)``, float64 (n, 3) world coordinates
        (x east, y north, z down in the sample unit) and int64 (m, 3) vertex indices, exactly as
        the PLY export writes that key. ``caps=False`` leaves out the caps that close a body cut by
        the cube's border (``store export --no-caps``).

        Raises :class:`~geotandem.errors.FormatError` naming the key, shard and offset when the
        record is damaged, :class:`~geotandem.errors.InvalidArgumentError` for an unknown key.
        """
        return self._core.mesh(_key(key), bool(caps))

    def meshes(self, keys: Iterable[int], caps: bool = True) -> Iterator[Tuple[int, np.ndarray, np.ndarray]]:
        """``(key, vertices, triangles)`` for each key in turn, one surface in memory at a time."""
        for key in keys:
            vertices, triangles = self._core.mesh(_key(key), bool(caps))
            yield int(key), vertices, triangles

    def check(self, keys: Optional[Iterable[int]] = None, *, raise_on_damage: bool = False) -> List[Tuple[int, str]]:
        """Reads back and verifies every record (or those of ``keys``), as ``geotandem store check``
        does: returns ``[(key, problem), ...]`` for the damaged ones (empty: all intact). With
        ``raise_on_damage``, raises FormatError naming the first damaged one instead."""
        damaged = self._core.check(None if keys is None else [_key(k) for k in keys])
        if damaged and raise_on_damage:
            key, problem = damaged[0]
            raise FormatError(f"damaged: key {key}: {problem}", message=problem, exit_code=4)
        return [(int(k), p) for k, p in damaged]


def open_store(directory: "os.PathLike[str] | str") -> Store:
    """Opens a component store read-only (see :class:`Store`)."""
    return Store(directory)


def _key(key: Any) -> int:
    value = int(key)
    if value < 0:
        # An index read with SQL shows keys at and above 2^63 negative: take them back.
        value += 1 << 64
    return value


def _json_or_text(text: str) -> Any:
    try:
        return json.loads(text)
    except (TypeError, ValueError):
        return text
