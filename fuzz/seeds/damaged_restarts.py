#!/usr/bin/env python3
"""Writes the restart regression inputs of fuzz/corpus/restart/ (fuzz/README.md) from the
engine-made seed pbf.restart: clocks that the reader once accepted, each with a valid
checksum (tests/test_restart.cpp has the same cases as unit tests).

    python3 fuzz/seeds/damaged_restarts.py fuzz/corpus/restart
"""
import math
import os
import struct
import sys
import zlib

out = sys.argv[1]
with open(os.path.join(out, "pbf.restart"), "rb") as f:
    good = f.read()
STEP, STEP_BASE, TIME_BASE = 104, 112, 120  # the clock: after the 32-byte header, domain, h, dt, rho0


def write(name, edits):
    data = bytearray(good)
    for at, fmt, value in edits:
        struct.pack_into(fmt, data, at, value)
    struct.pack_into("<I", data, 20, zlib.crc32(bytes(data[32:])))
    with open(os.path.join(out, name), "wb") as f:
        f.write(data)


# A NaN time: accepted, and every time-based schedule went wrong after it.
write("regression_nan_time.restart", [(TIME_BASE, "<d", math.nan)])
# A step near the int64 limit and a negative step_base: time() computed step - step_base,
# a signed overflow (undefined behaviour) on the read itself.
write("regression_step_overflow.restart", [(STEP, "<q", 2**63 - 2), (STEP_BASE, "<q", -10)])
