#!/usr/bin/env python3
"""Check a .vtu written by pbfengine with an implementation independent of the engine's
(standard library only: xml.etree for the XML, struct for the appended block).

Usage:
    check_vtu.py FRAME.vtu [EXPECTED.json]
    check_vtu.py SURFACE.vtp
    check_vtu.py --pvd COLLECTION.pvd

For a .vtu: checks the layout the engine promises (UnstructuredGrid, LittleEndian,
UInt64 headers, every array appended raw with a byte count that matches
NumberOfPoints, one VTK_VERTEX cell per point: connectivity 0..n-1, offsets 1..n,
types all 1) and prints 'points N' and one line 'NAME TYPE COMPONENTS' per array.
With EXPECTED.json ({"points": N, "arrays": {"NAME": [values...]}}; "Points" for the
coordinates) every value must be equal exactly (NaN matches NaN).

For a .vtp (a solid's surface): checks the same layout for PolyData (Points Float64,
Polys as connectivity and offsets, no other cells), that every polygon is a triangle of
existing points, and prints 'points N' and 'triangles T'.

For a .pvd: prints one line 'TIMESTEP PART FILE' per DataSet, times as Python's repr().
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


def read_head_and_block(path, dataset):
    """(root, block): the XML head parsed, the raw appended bytes, the layout checked."""
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
            (dataset, "LittleEndian", "UInt64"):
        fail(f"unexpected VTKFile attributes {attrs}")
    if root.find("AppendedData").get("encoding") != "raw":
        fail("AppendedData is not raw")
    return root, block


def read_array(a, block, count):
    """(type, components, values) of an appended DataArray of `count` tuples."""
    name, typ = a.get("Name"), a.get("type")
    comps = int(a.get("NumberOfComponents", "1"))
    if a.get("format") != "appended":
        fail(f"array {name} is not appended")
    off = int(a.get("offset"))
    (size,) = struct.unpack_from("<Q", block, off)
    item = struct.calcsize("<" + FORMATS[typ])
    if size != count * comps * item or off + 8 + size > len(block):
        fail(f"array {name}: {size} bytes at offset {off}, expected {count * comps * item} "
             f"within a block of {len(block)}")
    return typ, comps, list(struct.unpack_from(f"<{count * comps}{FORMATS[typ]}", block, off + 8))


def read_vtp(path):
    """(points, triangles): the surface's point count and its triangles as index triples."""
    root, block = read_head_and_block(path, "PolyData")
    piece = root.find("PolyData/Piece")
    n, polys = int(piece.get("NumberOfPoints")), int(piece.get("NumberOfPolys"))
    for other in ("NumberOfVerts", "NumberOfLines", "NumberOfStrips"):
        if int(piece.get(other, "0")) != 0:
            fail(f"{other} is not 0")
    typ, comps, _ = read_array(piece.find("Points/DataArray"), block, n)
    if (typ, comps) != ("Float64", 3):
        fail(f"Points are {typ} x {comps}")
    cells = {a.get("Name"): a for a in piece.find("Polys").findall("DataArray")}
    offsets = read_array(cells["offsets"], block, polys)[2]
    if offsets != [3 * (k + 1) for k in range(polys)]:
        fail("the polygons are not all triangles")
    connectivity = read_array(cells["connectivity"], block, 3 * polys)[2]
    if any(not 0 <= v < n for v in connectivity):
        fail("a triangle names a point that does not exist")
    return n, [connectivity[3 * k:3 * k + 3] for k in range(polys)]


def read_vtu(path):
    """(n, {name: (type, components, values)}); Points under 'Points', cells under their names."""
    root, block = read_head_and_block(path, "UnstructuredGrid")
    piece = root.find("UnstructuredGrid/Piece")
    n = int(piece.get("NumberOfPoints"))
    if int(piece.get("NumberOfCells")) != n:
        fail("NumberOfCells differs from NumberOfPoints")
    arrays = {}
    for section in ("PointData", "Points", "Cells"):
        for a in piece.find(section).findall("DataArray"):
            arrays[a.get("Name")] = read_array(a, block, n)
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
            print(repr(float(d.get("timestep"))), d.get("part"), d.get("file"))
        return
    if len(argv) == 1 and argv[0].endswith(".vtp"):
        n, triangles = read_vtp(argv[0])
        print("points", n)
        print("triangles", len(triangles))
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
