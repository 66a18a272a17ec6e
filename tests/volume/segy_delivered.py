#!/usr/bin/env python3
"""SEG-Y files as delivered, written with segyio, and segyio's own reading of them.

Usage: segy_delivered.py CASE OUT.sgy ORACLE.json

Writes OUT.sgy for CASE through segyio (trace headers and samples), puts the line numbers and
coordinates at the case's bytes and types (patched into the bytes segyio wrote when segyio has no
key for them), then reopens the file with segyio (ignore_geometry: trace by trace) and writes what
segyio reads: each trace's samples and header bytes, decoded with struct, the coordinate scalar
applied as SEG-Y says (negative divides, 0 means 1). The C++ test compares geotandem's reading of
OUT.sgy with ORACLE.json. Run with Debian's /usr/bin/python3 (python3-segyio).
"""
import json
import random
import struct
import sys

import numpy as np
import segyio

NI, NJ, NS = 6, 7, 20
IL0, IL_STEP, XL0, XL_STEP = 100, 2, 300, 1


def ibm_bits(value):
    """IEEE double to IBM System/360 single precision bits (exact for the values used here)."""
    if value == 0:
        return 0
    sign = 0x80000000 if value < 0 else 0
    v = abs(value)
    exponent = 64
    while v >= 1.0:
        v /= 16.0
        exponent += 1
    while v < 1.0 / 16.0:
        v *= 16.0
        exponent -= 1
    fraction = int(round(v * (1 << 24)))
    if fraction >= 1 << 24:
        fraction >>= 4
        exponent += 1
    return sign | (exponent << 24) | fraction


def encode(value, kind):
    if kind == "int16":
        return struct.pack(">h", int(value))
    if kind == "int32":
        return struct.pack(">i", int(value))
    if kind == "ieee":
        return struct.pack(">f", float(value))
    if kind == "ibm":
        return struct.pack(">I", ibm_bits(float(value)))
    raise ValueError(kind)


def decode(buf, byte, kind):
    raw = bytes(buf[byte - 1:byte - 1 + (2 if kind == "int16" else 4)])
    if kind == "int16":
        return struct.unpack(">h", raw)[0]
    if kind == "int32":
        return struct.unpack(">i", raw)[0]
    if kind == "ieee":
        return struct.unpack(">f", raw)[0]
    bits = struct.unpack(">I", raw)[0]
    fraction = bits & 0xFFFFFF
    if fraction == 0:
        return 0.0
    value = fraction / float(1 << 24) * 16.0 ** (((bits >> 24) & 0x7F) - 64)
    return -value if bits & 0x80000000 else value


# Each case: where the line numbers and coordinates go, their types, the scalar written at byte 71,
# whether the traces are shuffled or one is duplicated, the revision and extended headers.
CASES = {
    "lines_221_225": dict(il=(221, "int32"), xl=(225, "int32"), x=(181, "int32"), y=(185, "int32"), scalar=-100),
    "lines_9_13_int16": dict(il=(9, "int16"), xl=(13, "int16"), x=(181, "int32"), y=(185, "int32"), scalar=0),
    "float_221_225": dict(il=(221, "ieee"), xl=(225, "ieee"), x=(73, "ieee"), y=(77, "ieee"), scalar=10),
    "ibm_9_13": dict(il=(9, "ibm"), xl=(13, "ibm"), x=(181, "ibm"), y=(185, "ibm"), scalar=10),
    "unsorted": dict(il=(189, "int32"), xl=(193, "int32"), x=(181, "int32"), y=(185, "int32"), scalar=-100,
                     shuffle=True),
    "unsorted_221": dict(il=(221, "int32"), xl=(225, "int32"), x=(181, "int32"), y=(185, "int32"), scalar=10,
                         shuffle=True),
    "duplicated": dict(il=(189, "int32"), xl=(193, "int32"), x=(181, "int32"), y=(185, "int32"), scalar=-100,
                       shuffle=True, duplicate=True),
    "revision_2": dict(il=(189, "int32"), xl=(193, "int32"), x=(181, "int32"), y=(185, "int32"), scalar=-100,
                       revision=2, ext_headers=2),
    "feet": dict(il=(189, "int32"), xl=(193, "int32"), x=(181, "int32"), y=(185, "int32"), scalar=-100,
                 measurement=2),
    "revision_2_extensions": dict(il=(221, "int32"), xl=(225, "int32"), x=(181, "int32"), y=(185, "int32"),
                                  scalar=-100, revision=2, ext_headers=1, extensions=2, shuffle=True),
}


def world(i, j, scalar):
    """Coordinates of bin (i, j), as stored (before the scalar) and as meant (after it): an affine
    function of (i, j) whose stored values are whole numbers (centimetres for -100, tens of metres
    for 10)."""
    if scalar > 0:
        x = 500000.0 + 20.0 * i - 10.0 * j
        y = 6700000.0 + 10.0 * i + 30.0 * j
        return (x / scalar, y / scalar), (x, y)
    x = 500000.0 + 10.0 * i - 6.0 * j
    y = 6700000.0 + 8.0 * i + 7.5 * j
    if scalar < 0:
        x += 0.25
        y += 0.5
        return (round(x * -scalar), round(y * -scalar)), (x, y)
    y += 0.5 * j  # whole metres
    return (x, y), (x, y)


def write(case, path):
    c = CASES[case]
    bins = [(i, j) for i in range(NI) for j in range(NJ)]
    if c.get("shuffle"):
        random.Random(54).shuffle(bins)
    if c.get("duplicate"):
        bins.insert(17, bins[5])  # trace 17 repeats trace 5's bin
    spec = segyio.spec()
    spec.format = 5
    spec.samples = list(range(NS))
    spec.tracecount = len(bins)
    spec.ext_headers = c.get("ext_headers", 0)
    with segyio.create(path, spec) as f:
        for t, (i, j) in enumerate(bins):
            f.header[t] = {
                segyio.TraceField.TRACE_SEQUENCE_FILE: t + 1,
                segyio.TraceField.TRACE_SAMPLE_COUNT: NS,
                segyio.TraceField.TRACE_SAMPLE_INTERVAL: 4000,
                segyio.TraceField.SourceGroupScalar: c["scalar"],
            }
            f.trace[t] = np.array([1000.0 * i + 10.0 * j + 0.25 * k for k in range(NS)], dtype=np.float32)
        f.bin.update(hns=NS, hdt=4000, format=5)
        if "revision" in c:
            f.bin[segyio.BinField.SEGYRevision] = c["revision"] << 8
        if "measurement" in c:  # binary header bytes 3255-3256: 1 metres, 2 feet
            f.bin[segyio.BinField.MeasurementSystem] = c["measurement"]
    ext = c.get("ext_headers", 0)
    trace_bytes = 240 + 4 * NS
    with open(path, "r+b") as out:
        for t, (i, j) in enumerate(bins):
            stored, _ = world(i, j, c["scalar"])
            il, xl = IL0 + i * IL_STEP, XL0 + j * XL_STEP
            for (byte, kind), v in ((c["il"], il), (c["xl"], xl), (c["x"], stored[0]), (c["y"], stored[1])):
                out.seek(3600 + 3200 * ext + t * trace_bytes + byte - 1)
                out.write(encode(v, kind))


def read(case, path):
    """segyio's reading: samples trace by trace, header bytes as segyio hands them."""
    c = CASES[case]
    traces = []
    with segyio.open(path, ignore_geometry=True) as f:
        revision = f.bin[segyio.BinField.SEGYRevision]
        measurement = f.bin[segyio.BinField.MeasurementSystem]
        for t in range(f.tracecount):
            h = f.header[t]
            buf = h.buf
            scalar = h[segyio.TraceField.SourceGroupScalar]
            factor = 1.0 if scalar == 0 else (scalar if scalar > 0 else 1.0 / -scalar)
            traces.append({
                "trace": t,
                "inline": decode(buf, *c["il"]),
                "crossline": decode(buf, *c["xl"]),
                "x": decode(buf, *c["x"]) * factor,
                "y": decode(buf, *c["y"]) * factor,
                "samples": [float(v) for v in f.trace[t]],
            })
        samples = len(f.samples)
    return {"case": case, "samples": samples, "revision": revision, "measurement": measurement, "traces": traces,
            "il": list(c["il"]), "xl": list(c["xl"]), "x": list(c["x"]), "y": list(c["y"]),
            "scalar": c["scalar"]}


def add_extensions(path, count):
    """Rev 2 trace header extensions: `count` 240-byte blocks after each standard trace header
    (filled with 0xA5, so that reading them as samples or as the next header shows), and the count
    at binary header bytes 3507-3510."""
    with open(path, "rb") as f:
        data = f.read()
    ext = struct.unpack(">h", data[3504:3506])[0]
    head = bytearray(data[:3600 + 3200 * ext])
    head[3506:3510] = struct.pack(">i", count)
    trace_bytes = 240 + 4 * NS
    body = bytearray()
    for start in range(len(head), len(data), trace_bytes):
        body += data[start:start + 240] + b"\xa5" * (240 * count) + data[start + 240:start + trace_bytes]
    with open(path, "wb") as f:
        f.write(head + body)


def main():
    case, path, oracle = sys.argv[1:4]
    write(case, path)
    result = read(case, path)  # segyio reads the file before the extensions: it knows none
    extensions = CASES[case].get("extensions", 0)
    if extensions:
        add_extensions(path, extensions)
    result["extensions"] = extensions
    with open(oracle, "w") as f:
        json.dump(result, f)


if __name__ == "__main__":
    main()
