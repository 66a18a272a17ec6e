"""The label cube (issue 54) read back by other programs' readers: segyio for SEG-Y, GDAL's
multidimensional API for netCDF. The labels are checked against this file's own flood fill of the
samples on the body's side of iso (6-connected), for every body the store keeps, on both sides."""

import csv
from collections import deque

import numpy as np
import pytest

from conftest import cli, ls_json

segyio = pytest.importorskip("segyio")
gdal = pytest.importorskip("osgeo.gdal")


def flood_fill(inside):
    """6-connected components of a boolean cube: labels (-1 outside) and sizes."""
    labels = np.full(inside.shape, -1, dtype=np.int64)
    sizes = []
    shape = inside.shape
    for seed in zip(*np.nonzero(inside)):
        if labels[seed] >= 0:
            continue
        c = len(sizes)
        labels[seed] = c
        queue, n = deque([seed]), 0
        while queue:
            p = queue.popleft()
            n += 1
            for a in range(3):
                for d in (-1, 1):
                    q = list(p)
                    q[a] += d
                    q = tuple(q)
                    if 0 <= q[a] < shape[a] and inside[q] and labels[q] < 0:
                        labels[q] = c
                        queue.append(q)
        sizes.append(n)
    return labels, sizes


def expected_labels(values, iso, below, keys):
    """The IDs a label cube must hold: each key's crossed edge seeds the component of its inside end."""
    inside = (values <= iso) if below else (values >= iso)
    component, sizes = flood_fill(inside)
    flat = component.ravel()
    n = flat.size
    strides = (values.shape[1] * values.shape[2], values.shape[2], 1)
    smallest = {}
    for key in keys:
        ends = [key - 3 * n] if key // 3 >= n else [key // 3, key // 3 + strides[key % 3]]
        hits = [flat[e] for e in ends if flat[e] >= 0]
        assert len(hits) == 1, key
        smallest[hits[0]] = min(key, smallest.get(hits[0], key))
    order = sorted(smallest.values())
    ids = {c: order.index(k) + 1 for c, k in smallest.items()}
    out = np.zeros(values.shape, dtype=np.float32)
    for c, i in ids.items():
        out[component == c] = i
    return out, {order.index(k) + 1: sizes[c] for c, k in smallest.items()}


@pytest.mark.parametrize("side,iso", [("above", 0.5), ("below", 0.3)])
def test_segy_labels_read_by_segyio(scratch_root, side, iso):
    cube = scratch_root / f"labels-in-{side}.segy"
    cli("synth", "--kind", "analytic", "--shape", "40", "36", "32", "--seed", "5", "--out", cube)
    with segyio.open(cube) as f:
        values = segyio.tools.cube(f).astype(np.float32)
    store = scratch_root / f"labels-store-{side}"
    cli("-q", "extract", cube, "--iso", iso, "--side", side, "--block-size", "16", "--workers", "0", "--out", store)
    keys = [r["key"] for r in ls_json(store)]
    assert len(keys) > 3
    out = scratch_root / f"labels-{side}.segy"
    cli("-q", "store", "labels", store, "--out", out)
    expected, sizes = expected_labels(values, iso, side == "below", keys)
    with segyio.open(out) as f:
        got = segyio.tools.cube(f)
        with segyio.open(cube) as g:  # the input's trace headers: line numbers and coordinates
            for field in (segyio.TraceField.INLINE_3D, segyio.TraceField.CROSSLINE_3D, segyio.TraceField.CDP_X,
                          segyio.TraceField.CDP_Y):
                assert list(f.attributes(field)[:]) == list(g.attributes(field)[:])
        assert "BODY LABELS" in segyio.tools.wrap(f.text[0])
    np.testing.assert_array_equal(got, expected)
    with open(str(out) + ".bodies.csv") as table:
        rows = list(csv.DictReader(table))
    assert len(rows) == len(sizes)
    for r in rows:
        assert int(r["samples"]) == sizes[int(r["id"])]
        assert int(r["key"]) in keys


def test_netcdf_labels_read_by_gdal(scratch_root):
    cube = scratch_root / "labels-in.nc"
    cli("synth", "--kind", "analytic", "--shape", "36", "40", "32", "--seed", "6", "--out", cube)
    store = scratch_root / "labels-store-nc"
    cli("-q", "extract", cube, "--iso", "0.5", "--block-size", "16", "--workers", "0", "--out", store)
    keys = [r["key"] for r in ls_json(store)]
    assert len(keys) > 3
    out = scratch_root / "labels.nc"
    cli("-q", "store", "labels", store, "--out", out)
    ds = gdal.OpenEx(str(cube), gdal.OF_MULTIDIM_RASTER)
    group = ds.GetRootGroup()
    name = [a.GetName() for a in group.GetMDArrays() if a.GetDimensionCount() == 3][0]
    values = group.OpenMDArray(name).ReadAsArray().astype(np.float32)
    got_ds = gdal.OpenEx(str(out), gdal.OF_MULTIDIM_RASTER)
    got_group = got_ds.GetRootGroup()
    got = got_group.OpenMDArray("body_id").ReadAsArray()
    expected, _ = expected_labels(values, 0.5, False, keys)
    np.testing.assert_array_equal(got, expected)
    # The input's coordinates: the same dimension variables, the same values.
    for dim in ("iline", "xline"):
        np.testing.assert_array_equal(got_group.OpenMDArray(dim).ReadAsArray(), group.OpenMDArray(dim).ReadAsArray())
