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
    cli("synth", "--kind", "analytic", "--shape", "44", "40", "40", "--seed", "5", "--out", cube)
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


def test_segy_labels_keep_headers_at_any_byte(scratch_root):
    """An input made by segyio the way other programs lay files out: inline/crossline at bytes
    221/225, CDP X/Y with a scalar of -100, IBM floats, crossline-sorted, and fields geotandem does
    not read (offset, source X/Y, trace numbers). The label cube keeps every trace header byte for
    byte, in the file's order, and its labels are the flood fill's of segyio's own reading."""
    ni, nj, ns = 28, 24, 30
    rng = np.random.default_rng(11)
    i, j, k = np.meshgrid(np.arange(ni), np.arange(nj), np.arange(ns), indexing="ij")
    values = (np.sin(i / 3.1) * np.cos(j / 2.7) * np.sin(k / 4.3 + 0.4) + 0.2 * rng.standard_normal((ni, nj, ns)))
    values = values.astype(np.float32)
    cube = scratch_root / "labels-in-221.sgy"
    spec = segyio.spec()
    spec.format = 1  # IBM floats
    spec.samples = list(range(ns))
    spec.tracecount = ni * nj
    order = [(a, b) for b in range(nj) for a in range(ni)]  # crossline-sorted
    with segyio.create(str(cube), spec) as f:
        f.bin.update({segyio.BinField.Interval: 4000, segyio.BinField.Samples: ns})
        for t, (a, b) in enumerate(order):
            h = {segyio.TraceField.TRACE_SEQUENCE_LINE: t + 1, segyio.TraceField.offset: 7 + t % 5,
                 segyio.TraceField.SourceX: 1000 + t, segyio.TraceField.SourceY: 2000 - t,
                 segyio.TraceField.SourceGroupScalar: -100,
                 segyio.TraceField.CDP_X: int((500000 + 25 * a + 3 * b) * 100),
                 segyio.TraceField.CDP_Y: int((6000000 + 2 * a + 25 * b) * 100),
                 segyio.TraceField.TRACE_SAMPLE_COUNT: ns, segyio.TraceField.TRACE_SAMPLE_INTERVAL: 4000}
            f.header[t] = h
            f.trace[t] = values[a, b]
    # segyio names no field at 221/225: write the line numbers into the file's bytes directly.
    data = bytearray(cube.read_bytes())
    stride = 240 + 4 * ns
    for t, (a, b) in enumerate(order):
        at = 3600 + t * stride
        data[at + 220:at + 224] = int(300 + 2 * a).to_bytes(4, "big", signed=True)
        data[at + 224:at + 228] = int(1000 + b).to_bytes(4, "big", signed=True)
    cube.write_bytes(bytes(data))
    with segyio.open(cube, ignore_geometry=True) as f:  # the samples as segyio reads them
        read = np.stack([f.trace[t] for t in range(f.tracecount)])
    grid = np.zeros((ni, nj, ns), dtype=np.float32)
    for t, (a, b) in enumerate(order):
        grid[a, b] = read[t]

    iso = float(np.quantile(grid, 0.9))
    store = scratch_root / "labels-store-221"
    cli("-q", "extract", cube, "--iso", repr(iso), "--inline-byte", "221", "--crossline-byte", "225",
        "--block-size", "8", "--workers", "0", "--out", store)
    keys = [r["key"] for r in ls_json(store)]
    assert len(keys) > 3
    out = scratch_root / "labels-221.sgy"
    cli("-q", "store", "labels", store, "--all", "--out", out)
    expected, sizes = expected_labels(grid, np.float32(iso), False, keys)
    with segyio.open(out, ignore_geometry=True) as f, segyio.open(cube, ignore_geometry=True) as g:
        assert f.tracecount == g.tracecount
        assert f.bin[segyio.BinField.Format] == 5 and g.bin[segyio.BinField.Format] == 1
        assert f.bin[segyio.BinField.Interval] == g.bin[segyio.BinField.Interval]
        for t in range(f.tracecount):
            assert f.header[t].buf == g.header[t].buf, f"trace {t}"
            a, b = order[t]
            np.testing.assert_array_equal(f.trace[t], expected[a, b])
        text_in, text_out = segyio.tools.wrap(g.text[0]), segyio.tools.wrap(f.text[0])
        assert "GEOTANDEM BODY LABELS" in text_out
        assert "GEOTANDEM BODY LABELS" not in text_in
    # Byte for byte, the trace headers (240 bytes each, at the same places).
    a_bytes, b_bytes = out.read_bytes(), cube.read_bytes()
    assert len(a_bytes) == len(b_bytes)
    for t in range(ni * nj):
        at = 3600 + t * stride
        assert a_bytes[at:at + 240] == b_bytes[at:at + 240], f"trace {t}"
    with open(str(out) + ".bodies.csv") as table:
        rows = list(csv.DictReader(table))
    assert {int(r["id"]): int(r["samples"]) for r in rows} == sizes


def test_netcdf_labels_read_by_gdal(scratch_root):
    cube = scratch_root / "labels-in.nc"
    cli("synth", "--kind", "analytic", "--shape", "40", "44", "40", "--seed", "6", "--out", cube)
    store = scratch_root / "labels-store-nc"
    cli("-q", "extract", cube, "--iso", "0.5", "--block-size", "16", "--workers", "0", "--out", store)
    keys = [r["key"] for r in ls_json(store)]
    assert len(keys) > 3
    out = scratch_root / "labels.nc"
    cli("-q", "store", "labels", store, "--out", out)
    ds = gdal.OpenEx(str(cube), gdal.OF_MULTIDIM_RASTER)
    group = ds.GetRootGroup()
    name = [n for n in group.GetMDArrayNames() if group.OpenMDArray(n).GetDimensionCount() == 3][0]
    values = group.OpenMDArray(name).ReadAsArray().astype(np.float32)
    got_ds = gdal.OpenEx(str(out), gdal.OF_MULTIDIM_RASTER)
    got_group = got_ds.GetRootGroup()
    got = got_group.OpenMDArray("body_id").ReadAsArray()
    expected, _ = expected_labels(values, 0.5, False, keys)
    np.testing.assert_array_equal(got, expected)
    # The input's coordinates: the same dimension variables, the same values.
    for dim in ("iline", "xline"):
        np.testing.assert_array_equal(got_group.OpenMDArray(dim).ReadAsArray(), group.OpenMDArray(dim).ReadAsArray())


def test_netcdf_labels_carry_the_crs_extract_was_given(scratch_root):
    """A file that says no CRS, extracted with --crs: the label cube is the store's (the cube
    reopened with the store's CRS, not refused as another grid) and says that CRS, read by GDAL."""
    osr = pytest.importorskip("osgeo.osr")
    cube = scratch_root / "labels-crs-in.nc"
    cli("synth", "--kind", "analytic", "--shape", "40", "40", "40", "--seed", "7", "--out", cube)
    store = scratch_root / "labels-crs-store"
    cli("-q", "extract", cube, "--iso", "0.5", "--workers", "0", "--crs", "EPSG:23031", "--out", store)
    out = scratch_root / "labels-crs.nc"
    cli("-q", "store", "labels", store, "--out", out)
    got = gdal.OpenEx(str(out), gdal.OF_MULTIDIM_RASTER).GetRootGroup().OpenMDArray("body_id")
    srs = osr.SpatialReference()
    assert srs.ImportFromWkt(got.GetAttribute("geotandem_crs").ReadAsString()) == 0
    assert srs.GetAuthorityName(None) == "EPSG" and srs.GetAuthorityCode(None) == "23031"
    assert int(got.ReadAsArray().max()) > 0
