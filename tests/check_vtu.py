#!/usr/bin/env python3
"""Check a .vtu written by pbfengine with an implementation independent of the engine's
(standard library only: xml.etree for the XML, struct for the appended block).

Usage:
    check_vtu.py FRAME.vtu [EXPECTED.json]
    check_vtu.py --pvd COLLECTION.pvd

For a .vtu: checks the layout the engine promises (UnstructuredGrid, LittleEndian,
UInt64 headers, every array appended raw with a byte count that matches
NumberOfPoints, one VTK_VERTEX cell per point: connectivity 0..n-1, offsets 1..n,
types all 1) and prints 'points N' and one line 'NAME TYPE COMPONENTS' per array.
With EXPECTED.json ({"points": N, "arrays": {"NAME": [values...]}}; "Points" for the
coordinates) every value must be equal exactly (NaN matches NaN).

For a .pvd: prints one line 'TIMESTEP FILE' per DataSet, times as Python's repr().
Exit status 0 if all is well, 1 with a message on stderr otherwise.
"""
import json
import math
import struct
import sys
import xml.etree.ElementTree as ET

FORMATS = {"Int8": "b", "UInt8": "B", "Int16": "h", "UInt16": "H", "Int32": "i", "UInt32": "I",
           "Int64": "q", "UInt64": "Q", "Float32": "f", "Float64": "d"}


def fail(msg):
    print(f"check_vtu.py: error: {msg}", file=sys.stderr)
    sys.exit(1)


def read_vtu(path):
    """(n, {name: (type, components, values)}); Points under 'Points', cells under their names."""
    data = open(path, "rb").read()
    tag = data.find(b"<AppendedData")
    if tag < 0:
        fail("no <AppendedData>")
    gt = data.index(b">", tag)
    root = ET.fromstring(data[:gt] + b"/></VTKFile>")  # the XML head, the binary left out
    underscore = data.index(b"_", gt)
    if data[gt + 1:underscore].strip():
        fail("text between <AppendedData> and '_'")
    block = data[underscore + 1:data.rindex(b"</AppendedData>")]
    attrs = root.attrib
    if (attrs.get("type"), attrs.get("byte_order"), attrs.get("header_type")) != \
            ("UnstructuredGrid", "LittleEndian", "UInt64"):
        fail(f"unexpected VTKFile attributes {attrs}")
    if root.find("AppendedData").get("encoding") != "raw":
        fail("AppendedData is not raw")
    piece = root.find("UnstructuredGrid/Piece")
    n = int(piece.get("NumberOfPoints"))
    if int(piece.get("NumberOfCells")) != n:
        fail("NumberOfCells differs from NumberOfPoints")
    arrays = {}
    for section in ("PointData", "Points", "Cells"):
        for a in piece.find(section).findall("DataArray"):
            name, typ = a.get("Name"), a.get("type")
            comps = int(a.get("NumberOfComponents", "1"))
            if a.get("format") != "appended":
                fail(f"array {name} is not appended")
            off = int(a.get("offset"))
            (size,) = struct.unpack_from("<Q", block, off)
            item = struct.calcsize("<" + FORMATS[typ])
            if size != n * comps * item or off + 8 + size > len(block):
                fail(f"array {name}: {size} bytes at offset {off}, expected {n * comps * item} "
                     f"within a block of {len(block)}")
            values = struct.unpack_from(f"<{n * comps}{FORMATS[typ]}", block, off + 8)
            arrays[name] = (typ, comps, list(values))
    cells = (arrays["connectivity"][2], arrays["offsets"][2], arrays["types"][2])
    if cells != (list(range(n)), list(range(1, n + 1)), [1] * n):
        fail("the cells are not one VTK_VERTEX per point")
    if arrays["Points"][1] != 3:
        fail("Points do not have 3 components")
    return n, arrays


def same(a, b):
    both_nan = isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b)
    return a == b or both_nan


def main(argv):
    if len(argv) == 2 and argv[0] == "--pvd":
        root = ET.parse(argv[1]).getroot()
        if root.get("type") != "Collection":
            fail("not a Collection")
        for d in root.find("Collection").findall("DataSet"):
            print(repr(float(d.get("timestep"))), d.get("file"))
        return
    if len(argv) not in (1, 2) or argv[0].startswith("-"):
        sys.exit(__doc__)
    n, arrays = read_vtu(argv[0])
    print("points", n)
    for name, (typ, comps, _) in arrays.items():
        print(name, typ, comps)
    if len(argv) == 2:
        expected = json.load(open(argv[1]))
        if expected["points"] != n:
            fail(f"{n} points, expected {expected['points']}")
        for name, values in expected["arrays"].items():
            got = arrays[name][2] if name in arrays else fail(f"no array {name}")
            if len(got) != len(values):
                fail(f"{name}: {len(got)} values, expected {len(values)}")
            for i, (g, e) in enumerate(zip(got, values)):
                if not same(g, e):
                    fail(f"{name}[{i}] = {g!r}, expected {e!r}")
        print("ok")


if __name__ == "__main__":
    main(sys.argv[1:])
