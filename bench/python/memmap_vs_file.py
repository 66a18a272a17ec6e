"""Benchmark: geotandem.extract on an np.memmap against `geotandem extract` on the same raw file.

Prints the wall time and peak RSS of each (each in a process of its own). The cube: spheres on a
24-sample grid, N^3 float32 (default N=640: 1.0 GiB), written slab by slab.

  PYTHONPATH=build/release/python /usr/bin/python3 bench/python/memmap_vs_file.py [N] [--workers W]
  (or .venv/bin/python bench/python/memmap_vs_file.py after scripts/setup.sh)
"""

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

CHILD = """
import json, resource, sys, time
import numpy as np
import geotandem
path, n, out, workers = sys.argv[1], int(sys.argv[2]), sys.argv[3], int(sys.argv[4])
m = np.memmap(path, dtype="<f4", mode="r", shape=(n, n, n))
t = time.monotonic()
s = geotandem.extract(m, 0.5, out=out, block_size=64, workers=workers, progress=False)
print(json.dumps({"seconds": time.monotonic() - t, "components": len(s),
                  "maxrss_kb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss}))
"""


def write_cube(path: Path, n: int) -> None:
    k = np.arange(n, dtype=np.float32)
    jj, kk = np.meshgrid(k, k, indexing="ij")
    dj, dk = (jj % 24) - 12, (kk % 24) - 12
    with open(path, "wb") as f:
        for i in range(n):
            di = (i % 24) - 12
            f.write((1.0 - np.sqrt(di * di + dj * dj + dk * dk) / 8.0).astype("<f4").tobytes())
    (Path(str(path) + ".json")).write_text(json.dumps({
        "format": "geotandem-raw", "version": 1, "dtype": "float32", "byte_order": "little", "order": "C",
        "axes": ["inline", "crossline", "sample"], "shape": [n, n, n],
        "geometry": {"inline0": 1, "inline_step": 1, "crossline0": 1, "crossline_step": 1, "z0": 0, "dz": 4,
                     "z_unit": "ms", "affine": {"x0": 0, "xi": 25, "xj": 0, "y0": 0, "yi": 0, "yj": 25}}}))


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("n", type=int, nargs="?", default=640)
    parser.add_argument("--workers", type=int, default=0)
    parser.add_argument("--binary", default=os.environ.get("GEOTANDEM_BINARY", "build/release/bin/geotandem"))
    args = parser.parse_args()
    work = Path(tempfile.mkdtemp(prefix="geotandem-memmap-bench-", dir=os.environ.get("TMPDIR", "/tmp")))
    try:
        cube = work / "cube.raw"
        write_cube(cube, args.n)
        size = args.n ** 3 * 4
        print(f"cube {args.n}^3 float32: {size / 2**30:.2f} GiB; block_size 64, workers {args.workers}")
        run = subprocess.run([sys.executable, "-c", CHILD, str(cube), str(args.n), str(work / "py"),
                              str(args.workers)], capture_output=True, text=True, check=True)
        py = json.loads(run.stdout.strip().splitlines()[-1])
        t = time.monotonic()
        child = subprocess.Popen([args.binary, "-q", "extract", str(cube), "--iso", "0.5", "--block-size", "64",
                                  "--workers", str(args.workers), "--out", str(work / "cli")])
        _, status, usage = os.wait4(child.pid, 0)  # this child's own peak RSS
        cli_seconds = time.monotonic() - t
        assert status == 0, status
        cli_rss = usage.ru_maxrss
        print(f"geotandem.extract(memmap): {py['seconds']:7.2f} s, peak RSS {py['maxrss_kb'] / 1024:7.1f} MiB, "
              f"{py['components']} components")
        print(f"geotandem extract FILE:    {cli_seconds:7.2f} s, peak RSS {cli_rss / 1024:7.1f} MiB")
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
