"""The store from Python against the command line: components() equals `store ls --json` field for
field, keys at and above 2^63 stay positive, mesh(key) equals the PLY export vertex for vertex, and
a damaged record raises an error naming its key as `store check` does."""

import json
import struct
import subprocess

import numpy as np
import pytest

import geotandem
from conftest import STORE_WRITER, cli, ls_json

TRIPLES = ("centroid", "box_min", "box_max")


def assert_frame_equals_ls(df, rows):
    """Every field of every `store ls --json` row, against the DataFrame's row of the same key."""
    assert len(df) == len(rows)
    assert df["key"].dtype == np.uint64
    by_key = {int(k): i for i, k in enumerate(df["key"])}
    assert len(by_key) == len(df)
    for r in rows:
        row = df.iloc[by_key[r["key"]]]
        for field in ("vertex_count", "triangle_count", "offset", "length"):
            assert int(row[field]) == r[field], field
        for field in ("volume", "area", "azimuth", "dip", "elongation", "cap_area"):
            assert float(row[field]) == r[field], field  # JSON keeps doubles exactly (shortest round trip)
        for field in ("closed", "cut_by_border"):
            assert bool(row[field]) == r[field], field
        for field in ("cut_faces", "shard", "checksum"):
            assert row[field] == r[field], field
        assert (None if row["run"] is None or row["run"] is np.nan or str(row["run"]) == "<NA>" else int(row["run"])) \
            == r["run"]
        # The volume in samples (issue 54): a nullable integer, as `store ls --json` gives it.
        assert (None if str(row["samples"]) == "<NA>" else int(row["samples"])) == r["samples"]
        for name in TRIPLES:
            assert [row[f"{name}_{a}"] for a in "xyz"] == r[name], name
        assert [row[f"obb_center_{a}"] for a in "xyz"] == r["obb"]["center"]
        for n in range(3):
            assert [row[f"obb_axis{n}_{a}"] for a in "xyz"] == r["obb"]["axes"][n]
        assert [row[f"obb_half_extent{n}"] for n in range(3)] == r["obb"]["half_extents"]


def test_components_equal_store_ls_on_the_quickstart_store(quickstart_store):
    s = geotandem.open_store(quickstart_store)
    df = s.components()
    rows = ls_json(quickstart_store)
    assert len(rows) > 20
    assert_frame_equals_ls(df, rows)
    # Every selection the recipe's steps wrote is a column, true exactly for its members.
    selections = json.loads(cli("store", "selections", quickstart_store, "--json").stdout)
    assert selections, "the quickstart recipe writes selections"
    for sel in selections:
        members = {r["key"] for r in ls_json(quickstart_store, "--selection", sel["name"])}
        column = df["in_" + sel["name"]]
        assert {int(k) for k in df["key"][column]} == members
        assert len(members) == sel["size"]


def test_a_selection_in_its_saved_order(quickstart_store):
    s = geotandem.open_store(quickstart_store)
    rows = ls_json(quickstart_store, "--selection", "sorted", "--sort", "selection")
    df = s.components(selection="sorted")
    assert [int(k) for k in df["key"]] == [r["key"] for r in rows]
    assert list(df["rank"]) == list(range(len(rows)))
    assert [int(k) for k in s.selection("sorted")] == [r["key"] for r in rows]
    assert_frame_equals_ls(df, rows)


def test_runs_match_store_runs(quickstart_store):
    s = geotandem.open_store(quickstart_store)
    expected = json.loads(cli("store", "runs", quickstart_store, "--json").stdout)
    runs = s.runs()
    assert [r["id"] for r in runs] == [r["id"] for r in expected]
    for got, want in zip(runs, expected):
        assert got["parameters"] == want["parameters"]
        assert got["statistics"] == want["statistics"]
        assert got["components"] == want["components"]
        assert got["ended"] == want["ended"]


@pytest.fixture(scope="module")
def high_key_store(scratch_root):
    """Keys 2^63 - 14, ..., crossing 2^63, up to about 2^64 - 1 - 7: written through the C++ store API."""
    path = scratch_root / "high-keys"
    first = (1 << 63) - 14
    subprocess.run([STORE_WRITER, path, "40", str(first)], check=True)
    return path, first


def test_keys_at_and_above_2_63_stay_positive(high_key_store):
    path, first = high_key_store
    df = geotandem.open_store(path).components()
    expected = [first + 7 * n for n in range(40)]
    assert df["key"].dtype == np.uint64
    assert sorted(int(k) for k in df["key"]) == expected
    # The order is the C++ query's, as `store ls` lists them (the index sorts keys as SQLite's signed
    # integers, so those at and above 2^63 come first there: left to the store's owners).
    assert [int(k) for k in df["key"]] == [r["key"] for r in ls_json(path)]
    assert (df["key"] >= np.uint64(1 << 63)).sum() == sum(k >= 1 << 63 for k in expected) > 30
    assert_frame_equals_ls(df, ls_json(path))
    # A key read back from SQL (negative) names the same component.
    s = geotandem.open_store(path)
    big = expected[-1]
    v1, t1 = s.mesh(big)
    v2, t2 = s.mesh(big - (1 << 64))
    assert np.array_equal(v1, v2) and np.array_equal(t1, t2)
    assert df["in_every_other"].sum() == 20


def read_ply(path):
    """A binary little-endian PLY as the export writes it: (vertices, faces)."""
    data = path.read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().splitlines()
    nv = int(next(l for l in header if l.startswith("element vertex")).split()[-1])
    nf = int(next(l for l in header if l.startswith("element face")).split()[-1])
    kind = next(l for l in header if l.startswith("property") and l.endswith(" x")).split()[1]
    assert kind == "double"
    vertices = np.frombuffer(data, dtype="<f8", count=nv * 3, offset=end).reshape(nv, 3)
    pos = end + nv * 24
    faces = []
    for _ in range(nf):
        n = data[pos]
        assert n == 3
        faces.append(struct.unpack_from("<3i", data, pos + 1))
        pos += 1 + 12 + 4
    return vertices, np.array(faces, dtype=np.int64).reshape(nf, 3)


@pytest.mark.parametrize("caps", [True, False])
def test_mesh_equals_the_ply_export(quickstart_store, scratch_root, caps):
    s = geotandem.open_store(quickstart_store)
    df = s.components()
    # A cut body (caps matter), the largest body and a small one.
    cut = df[df.cut_by_border & (df.cut_faces != "")]
    assert len(cut) > 0
    keys = [int(cut.key.iloc[0]), int(df.sort_values("volume").key.iloc[-1]), int(df.key.iloc[0])]
    out = scratch_root / f"ply-{caps}"
    args = ["store", "export", quickstart_store, "--format", "ply", "--per-component", "--out", out]
    cli(*args, *([] if caps else ["--no-caps"]))
    exported = 0
    for key, (v, t) in zip(keys, (s.mesh(k, caps=caps) for k in keys)):
        ply = out / f"geobody_{key}.ply"
        pv, pt = read_ply(ply)
        assert v.dtype == np.float64 and v.shape == pv.shape
        assert np.array_equal(v, pv)  # bit for bit: both are the stored doubles
        assert np.array_equal(t, pt)
        exported += 1
    assert exported == 3
    streamed = list(s.meshes(keys, caps=caps))
    assert [k for k, _, _ in streamed] == keys
    assert np.array_equal(streamed[0][1], s.mesh(keys[0], caps=caps)[0])


def test_a_damaged_record_raises_naming_its_key(scratch_root):
    path = scratch_root / "damaged"
    subprocess.run([STORE_WRITER, path, "10", "100"], check=True)
    rows = ls_json(path)
    victim = rows[3]
    shard = path / "shards" / f"{victim['shard']}.gts"
    data = bytearray(shard.read_bytes())
    data[victim["offset"] + victim["length"] // 2] ^= 0xFF
    shard.write_bytes(bytes(data))
    s = geotandem.open_store(path)
    with pytest.raises(geotandem.FormatError) as e:
        s.mesh(victim["key"])
    assert str(victim["key"]) in str(e.value)
    checked = cli("store", "check", path, "--json", check=False)
    assert checked.returncode == 4
    damaged = json.loads(checked.stdout)["damaged"]
    assert s.check() == [(d["key"], d["problem"]) for d in damaged]
    assert [k for k, _ in s.check()] == [victim["key"]]
    with pytest.raises(geotandem.FormatError):
        s.check(raise_on_damage=True)
    # The others still read.
    assert s.mesh(rows[2]["key"])[0].shape[1] == 3


def test_an_unknown_key_and_a_missing_store(scratch_root, quickstart_store):
    s = geotandem.open_store(quickstart_store)
    with pytest.raises(geotandem.InvalidArgumentError):
        s.mesh(int(s.components().key.max()) + 1)
    with pytest.raises(geotandem.Error):
        geotandem.open_store(scratch_root / "no-such-store")


def test_the_store_and_its_dataframe_show_the_crs(analytic_cube, scratch_root, quickstart_store):
    """Issue 54: the CRS the store keeps, as the command line gave it; a store without one says so."""
    out = scratch_root / "crs-store"
    cli("-q", "extract", str(analytic_cube), "--iso", "0.5", "--workers", "0", "--crs", "EPSG:23031",
        "--out", str(out))
    store = geotandem.open_store(out)
    assert store.crs["code"] == "EPSG:23031"
    assert store.crs["unit"] == "m"
    assert store.crs_label == "ED50 / UTM zone 31N (EPSG:23031)"
    df = store.components()
    assert df.attrs["crs_label"] == store.crs_label
    assert df.attrs["crs"] == store.crs["wkt"]
    assert store.runs()[0]["parameters"]["crs"]["code"] == "EPSG:23031"
    plain = geotandem.open_store(quickstart_store)  # a synthetic cube, no CRS given
    assert plain.crs is None
    assert plain.crs_label == "no CRS given"
    assert plain.components().attrs["crs"] is None


def test_the_geopackage_reads_in_fiona_as_the_store_says(scratch_root, analytic_cube):
    """Issue 54 part 2: the GeoPackage as geopandas users read it (fiona, from Debian's
    python3-fiona): both layers, one feature per component, the store's CRS, its measures."""
    import fiona  # python3-fiona, installed by scripts/setup.sh
    from osgeo import osr  # python3-gdal (scripts/setup.sh)
    out = scratch_root / "gpkg-store"
    cli("-q", "extract", str(analytic_cube), "--iso", "0.5", "--workers", "0", "--crs", "EPSG:23031",
        "--out", str(out))
    gpkg = scratch_root / "bodies.gpkg"
    if gpkg.exists():
        gpkg.unlink()
    cli("-q", "store", "export", str(out), "--format", "gpkg", "--out", str(gpkg))
    df = geotandem.open_store(out).components().set_index("key")
    assert sorted(fiona.listlayers(str(gpkg))) == ["centroids", "footprints"]
    epsg = osr.SpatialReference()
    epsg.ImportFromEPSG(23031)
    for name in ("footprints", "centroids"):
        with fiona.open(str(gpkg), layer=name) as layer:
            srs = osr.SpatialReference()
            srs.ImportFromWkt(layer.crs_wkt)
            assert srs.IsSame(epsg), name
            features = list(layer)
        assert sorted(int(f["properties"]["key"]) for f in features) == sorted(df.index.tolist()), name
        for f in features:
            row = df.loc[int(f["properties"]["key"])]
            assert f["properties"]["volume"] == pytest.approx(row.volume, rel=1e-12)
            assert f["properties"]["azimuth"] == pytest.approx(row.azimuth, rel=1e-12, abs=1e-12)
            if name == "centroids":
                assert f["geometry"]["coordinates"][0] == pytest.approx(row.centroid_x, rel=1e-15)
                assert f["geometry"]["coordinates"][1] == pytest.approx(row.centroid_y, rel=1e-15)

