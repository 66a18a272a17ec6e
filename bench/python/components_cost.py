"""Benchmark: the cost of Store.components() (the whole index as a DataFrame) on a store of
200,000 components, written through the C++ store API (tests/python/store_writer).

  PYTHONPATH=build/release/python /usr/bin/python3 bench/python/components_cost.py \
      [--count 200000] [--writer build/release/bin/store_writer]
"""

import argparse
import os
import shutil
import sqlite3
import subprocess
import tempfile
import time
from pathlib import Path

import pandas as pd

import geotandem


def best_of(n, f):
    times = []
    for _ in range(n):
        t = time.perf_counter()
        result = f()
        times.append(time.perf_counter() - t)
    return min(times), result


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--count", type=int, default=200_000)
    parser.add_argument("--writer", default=os.environ.get("GEOTANDEM_STORE_WRITER", "build/release/bin/store_writer"))
    args = parser.parse_args()
    work = Path(tempfile.mkdtemp(prefix="geotandem-components-bench-"))
    try:
        store = work / "store"
        t = time.perf_counter()
        subprocess.run([args.writer, str(store), str(args.count)], check=True)
        print(f"store of {args.count} components written in {time.perf_counter() - t:.1f} s")
        s = geotandem.open_store(store)
        seconds, df = best_of(3, s.components)
        print(f"Store.components(): {seconds:.3f} s for {len(df)} rows x {len(df.columns)} columns "
              f"({seconds / len(df) * 1e6:.2f} us per row)")
        seconds, df = best_of(3, lambda: s.components(selection="every_other"))
        print(f"Store.components(selection=...): {seconds:.3f} s for {len(df)} rows")
        # For scale: pandas.read_sql of the index table alone (no conversion, signed keys).
        with sqlite3.connect(f"file:{store / 'index.sqlite'}?mode=ro", uri=True) as db:
            table = db.execute("select name from sqlite_master where type='table' and name like '%component%'").fetchone()
            if table:
                seconds, raw = best_of(3, lambda: pd.read_sql(f"select * from {table[0]}", db))
                print(f"pandas.read_sql of table {table[0]} (for scale): {seconds:.3f} s for {len(raw)} rows")
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
