"""geotandem.extract on a numpy array, an np.memmap and an xarray.DataArray gives the components
`geotandem extract` gives on the same cube file (keys and volumes), in this process and with worker
processes; a memmap is read without being loaded (peak RSS far below its size)."""

import json
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import geotandem
from conftest import cli, ls_json, python_env, read_raw


def keys_and_volumes(rows):
    return {r["key"]: r["volume"] for r in rows}


@pytest.fixture(scope="module")
def reference(analytic_cube, scratch_root):
    """The command line's extraction of the cube file, block tree of 32-cell leaves, in one process."""
    out = scratch_root / "cli-store"
    cli("-q", "extract", analytic_cube, "--iso", "0.5", "--block-size", "32", "--workers", "0", "--out", out)
    rows = ls_json(out)
    assert len(rows) > 5
    return keys_and_volumes(rows), geotandem.open_store(out).geometry


def assert_same(store, reference, exact=True):
    expected, geometry = reference
    got = {int(k): v for k, v in zip(store.components()["key"], store.components()["volume"])}
    assert set(got) == set(expected)
    for key, volume in expected.items():
        if exact:
            assert got[key] == volume, key
        else:
            assert got[key] == pytest.approx(volume, rel=1e-9), key


def test_numpy_array(analytic_cube, scratch_root, reference):
    samples, sidecar = read_raw(analytic_cube)
    s = geotandem.extract(samples, 0.5, out=scratch_root / "py-array", block_size=32, geometry=sidecar["geometry"],
                          progress=False)
    assert_same(s, reference)
    assert s.geometry == reference[1]
    assert s.last_result["components"] == len(reference[0])


def test_array_of_another_dtype_and_order_is_converted(analytic_cube, scratch_root, reference):
    samples, sidecar = read_raw(analytic_cube)
    fortran = np.asfortranarray(samples.astype(np.float64))
    s = geotandem.extract(fortran, 0.5, out=scratch_root / "py-f64", block_size=32, geometry=sidecar["geometry"],
                          progress=False)
    assert_same(s, reference)


def test_memmap(analytic_cube, scratch_root, reference):
    _, sidecar = read_raw(analytic_cube)
    m = np.memmap(analytic_cube, dtype="<f4", mode="r", shape=tuple(sidecar["shape"]))
    s = geotandem.extract(m, 0.5, out=scratch_root / "py-memmap", block_size=32, geometry=sidecar["geometry"],
                          progress=False)
    assert_same(s, reference)


def test_memmap_at_an_offset_in_its_file(analytic_cube, scratch_root, reference):
    samples, sidecar = read_raw(analytic_cube)
    path = scratch_root / "with-header.bin"
    header = b"H" * 12345  # not a multiple of the page size
    path.write_bytes(header + samples.tobytes())
    m = np.memmap(path, dtype="<f4", mode="r", offset=len(header), shape=samples.shape)
    s = geotandem.extract(m, 0.5, out=scratch_root / "py-memmap-offset", block_size=32,
                          geometry=sidecar["geometry"], progress=False)
    assert_same(s, reference)


def test_data_array_in_the_seisnc_layout(analytic_cube, scratch_root, reference):
    xr = pytest.importorskip("xarray")
    samples, sidecar = read_raw(analytic_cube)
    g = sidecar["geometry"]
    ni, nj, nk = samples.shape
    i, j = np.meshgrid(np.arange(ni), np.arange(nj), indexing="ij")
    a = g["affine"]
    da = xr.DataArray(samples, dims=("iline", "xline", "twt"), coords={
        "iline": g["inline0"] + g["inline_step"] * np.arange(ni),
        "xline": g["crossline0"] + g["crossline_step"] * np.arange(nj),
        "twt": g["z0"] + g["dz"] * np.arange(nk),
        "cdp_x": (("iline", "xline"), a["x0"] + a["xi"] * i + a["xj"] * j),
        "cdp_y": (("iline", "xline"), a["y0"] + a["yi"] * i + a["yj"] * j)})
    s = geotandem.extract(da, 0.5, out=scratch_root / "py-xarray", block_size=32, progress=False)
    # The affine is fitted from corner coordinates: the same to rounding.
    assert_same(s, reference, exact=False)
    got, want = s.geometry, reference[1]
    for k in ("inline0", "inline_step", "crossline0", "crossline_step", "z0", "dz", "z_unit"):
        assert got[k] == want[k]
    for k, v in want["affine"].items():
        assert got["affine"][k] == pytest.approx(v, rel=1e-12, abs=1e-9)


@pytest.mark.parametrize("kind", ["memmap", "array"])
def test_with_two_worker_processes(analytic_cube, scratch_root, reference, kind):
    samples, sidecar = read_raw(analytic_cube)
    if kind == "memmap":  # read by the workers from its own file
        samples = np.memmap(analytic_cube, dtype="<f4", mode="r", shape=tuple(sidecar["shape"]))
    out = scratch_root / f"py-workers-{kind}"
    s = geotandem.extract(samples, 0.5, out=out, block_size=32, workers=2, geometry=sidecar["geometry"],
                          progress=False)
    assert s.last_result["workers"] == 2
    # Merged in another order by the workers: the same volumes to rounding.
    assert_same(s, reference, exact=False)
    # The raw copy (or link) beside the store is gone.
    assert not list(scratch_root.glob(f"py-workers-{kind}.input.*")), "the copy for the workers was left behind"
    assert json.loads(cli("store", "check", out, "--json").stdout)["damaged"] == []
    # Called again, with workers or in this process, it resumes the same store: the store knows
    # the samples (the array's digest, the memmap's file), not the name or time of the copy.
    for workers in (2, 0):
        again = geotandem.extract(samples, 0.5, out=out, block_size=32, workers=workers,
                                  geometry=sidecar["geometry"], progress=False)
        assert_same(again, reference, exact=False)


def test_parameters_come_from_the_cpp_declarations():
    declared = geotandem.extract_parameters()
    help_text = cli("extract", "--help").stdout
    for name in ("max_error", "isotropy", "block_size", "mode", "axis", "side"):
        default = declared[name]["default"]
        assert f"--{name.replace('_', '-')}" in help_text
        assert default in help_text  # the command line shows the same default
        import inspect
        shown = inspect.signature(geotandem.extract).parameters[name].default
        assert shown == (type(shown)(default) if not isinstance(shown, str) else default)
        assert name in geotandem.extract.__doc__


def test_side_below_is_the_negated_cube_and_the_command_lines(analytic_cube, scratch_root):
    """side="below" (issue 54): the components of the negated array above the negated iso, and those
    of `geotandem extract --side below` on the file; the store says which side."""
    samples, sidecar = read_raw(analytic_cube)
    below = geotandem.extract(samples, 0.3, out=scratch_root / "py-below", side="below", block_size=32,
                              geometry=sidecar["geometry"], progress=False)
    negated = geotandem.extract(-samples, -0.3, out=scratch_root / "py-negated", block_size=32,
                                geometry=sidecar["geometry"], progress=False)
    a, b = below.components(), negated.components()
    assert len(a) > 0
    assert list(a["key"]) == list(b["key"])
    assert list(a["volume"]) == list(b["volume"])
    assert list(a["samples"]) == list(b["samples"])
    out = scratch_root / "cli-below"
    cli("-q", "extract", analytic_cube, "--iso", "0.3", "--side", "below", "--block-size", "32", "--workers", "0",
        "--out", out)
    assert keys_and_volumes(ls_json(out)) == dict(zip(map(int, a["key"]), a["volume"]))
    runs = json.loads(cli("store", "runs", out, "--json").stdout)
    assert runs[-1]["parameters"]["side"] == "below"
    assert runs[-1]["parameters"]["identity"]["side"] == "below"


def test_a_bad_parameter_names_it(analytic_cube, scratch_root):
    samples, sidecar = read_raw(analytic_cube)
    with pytest.raises(geotandem.InvalidArgumentError, match="max_error"):
        geotandem.extract(samples, 0.5, out=scratch_root / "bad", max_error=-1, progress=False)
    with pytest.raises(TypeError, match="max_eror"):
        geotandem.extract(samples, 0.5, out=scratch_root / "bad", max_eror=1, progress=False)


def test_nan_samples_are_refused_or_filled(scratch_root):
    cube = np.zeros((16, 16, 16), dtype=np.float32)
    cube[4:9, 4:9, 4:9] = 1.0
    cube[1, 2, 3] = np.nan
    with pytest.raises(geotandem.DataError):
        geotandem.extract(cube, 0.5, out=scratch_root / "nan-error", progress=False)
    s = geotandem.extract(cube, 0.5, out=scratch_root / "nan-fill", nan="fill", progress=False)
    assert len(s) == 1


MEMMAP_RUN = textwrap.dedent("""
    import json, resource, sys
    import numpy as np
    import geotandem
    path, n, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    m = np.memmap(path, dtype="<f4", mode="r", shape=(n, n, n))
    s = geotandem.extract(m, 0.5, out=out, block_size=64, progress=False)
    print(json.dumps({"maxrss_kb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, "components": len(s)}))
""")


def blobs(path, n):
    """A cube of n^3 float32 with spheres on a grid, written slab by slab (never whole in memory)."""
    k = np.arange(n, dtype=np.float32)
    jj, kk = np.meshgrid(k, k, indexing="ij")
    period = 24.0
    with open(path, "wb") as f:
        for i in range(n):
            di = (i % period) - period / 2
            dj = (jj % period) - period / 2
            dk = (kk % period) - period / 2
            slab = 1.0 - np.sqrt(di * di + dj * dj + dk * dk) / 8.0
            f.write(slab.astype("<f4").tobytes())


def test_a_memmap_is_read_block_by_block(scratch_root):
    n = 384  # 216 MiB of float32
    path = scratch_root / "blobs.f32"
    blobs(path, n)
    size_kb = n ** 3 * 4 // 1024
    run = subprocess.run([sys.executable, "-c", MEMMAP_RUN, path, str(n), scratch_root / "memmap-rss"],
                         capture_output=True, text=True, env=python_env(), timeout=500)
    assert run.returncode == 0, run.stderr
    figures = json.loads(run.stdout.strip().splitlines()[-1])
    print(f"memmap of {size_kb // 1024} MiB: peak RSS {figures['maxrss_kb'] // 1024} MiB")
    assert figures["components"] > (n // 24) ** 3 // 2
    # The interpreter with numpy and pandas alone takes ~60 MiB; the array is never resident whole.
    assert figures["maxrss_kb"] < size_kb * 0.5
    path.unlink()


def test_the_gil_is_released_while_extracting(analytic_cube, scratch_root):
    import threading
    samples, sidecar = read_raw(analytic_cube)
    done = threading.Event()

    def work():
        geotandem.extract(samples, 0.5, out=scratch_root / "py-thread", block_size=16,
                          geometry=sidecar["geometry"], progress=False)
        done.set()

    thread = threading.Thread(target=work)
    spins = 0
    thread.start()
    while not done.is_set():
        spins += 1  # runs only while the extraction does not hold the GIL
    thread.join()
    assert spins > 100_000


class _WktOnly:
    """Stands for a pyproj.CRS (not installed here): crs= takes anything with to_wkt()."""

    def __init__(self, wkt):
        self.wkt = wkt

    def to_wkt(self):
        return self.wkt


def test_crs_is_the_command_lines_and_changes_no_vertex(analytic_cube, scratch_root, reference):
    samples, sidecar = read_raw(analytic_cube)
    cli_out = scratch_root / "cli-crs"
    cli("-q", "extract", analytic_cube, "--iso", "0.5", "--block-size", "32", "--workers", "0", "--crs", "EPSG:23031",
        "--out", cli_out)
    expected = geotandem.open_store(cli_out).crs
    assert expected and expected["code"] == "EPSG:23031"

    s = geotandem.extract(samples, 0.5, out=scratch_root / "py-crs-array", block_size=32,
                          geometry=sidecar["geometry"], crs="EPSG:23031", progress=False)
    assert s.crs == expected
    assert s.components().attrs["crs"] == expected["wkt"]
    assert_same(s, reference)  # the CRS labels the coordinates, it moves nothing

    # A file read by two worker processes, the CRS given as an object with to_wkt(): the workers open
    # the file with the same CRS as the manager.
    f = geotandem.extract(analytic_cube, 0.5, out=scratch_root / "py-crs-file", block_size=32, workers=2,
                          crs=_WktOnly(expected["wkt"]), progress=False)
    assert f.last_result["workers"] == 2
    assert f.crs["name"] == expected["name"] and f.crs["unit"] == expected["unit"]
    assert_same(f, reference, exact=False)

    # An integer is an EPSG code; without crs= an array has none.
    assert geotandem.extract(samples, 0.5, out=scratch_root / "py-crs-int", block_size=32,
                             geometry=sidecar["geometry"], crs=23031, progress=False).crs == expected
    assert geotandem.extract(samples, 0.5, out=scratch_root / "py-crs-none", block_size=32,
                             geometry=sidecar["geometry"], progress=False).crs is None


def test_a_bad_crs_is_refused_before_any_work(analytic_cube, scratch_root):
    samples, sidecar = read_raw(analytic_cube)
    out = scratch_root / "py-crs-bad"
    with pytest.raises(geotandem.errors.InvalidArgumentError, match="crs="):
        geotandem.extract(samples, 0.5, out=out, geometry=sidecar["geometry"], crs="EPSG:999999", progress=False)
    assert not out.exists()
    with pytest.raises(TypeError, match="crs="):
        geotandem.extract(samples, 0.5, out=out, geometry=sidecar["geometry"], crs=1.5, progress=False)
    with pytest.raises(ValueError, match="crs= is empty"):
        geotandem.extract(samples, 0.5, out=out, geometry=sidecar["geometry"], crs=" ", progress=False)


@pytest.mark.parametrize("suffix", ["nc", "tif"])
def test_a_gdal_format_is_read_in_this_process(scratch_root, suffix):
    """netCDF and GeoTIFF go through geotandem's GDAL module, which the Python process loads after
    holding the framework's libraries privately (extension modules are loaded RTLD_LOCAL): the same
    components as the command line's."""
    cube = scratch_root / f"gdal-cube.{suffix}"
    cli("-q", "synth", "--shape", "48", "48", "40", "--out", cube)
    expected = scratch_root / f"gdal-cli-{suffix}"
    cli("-q", "extract", cube, "--iso", "0.5", "--workers", "0", "--out", expected)
    s = geotandem.extract(cube, 0.5, out=scratch_root / f"gdal-py-{suffix}", workers=0, progress=False)
    assert len(s.components()) > 0
    assert keys_and_volumes(ls_json(expected)) == {int(k): v for k, v in zip(s.components()["key"],
                                                                             s.components()["volume"])}
