#!/usr/bin/env python3
"""Read VTK XML UnstructuredGrid (.vtu) particle frames and ParaView collections (.pvd)
with the standard library and numpy, as render_frames.py does.

    import vtu
    points, arrays = vtu.read_vtu("out/frame_00003.vtu")  # (N, 3); {name: (N,) or (N, k)}
    for time, path in vtu.read_pvd("out/frames.pvd"):      # particle frames, made absolute
        ...

Reads appended (raw or base64), inline base64 ("binary") and ascii arrays, UInt32 or
UInt64 block headers, any integer or float type (all returned as float64), little-endian
and uncompressed only. Errors raise VtuError naming the file. Run as a script to print
a summary: python3 share/vtu.py FRAME.vtu|COLLECTION.pvd
"""
import base64
import binascii
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np

DTYPES = {"Int8": "i1", "UInt8": "u1", "Int16": "<i2", "UInt16": "<u2", "Int32": "<i4",
          "UInt32": "<u4", "Int64": "<i8", "UInt64": "<u8", "Float32": "<f4", "Float64": "<f8"}


class VtuError(Exception):
    pass


def _b64(text):
    """Decode base64 that may be several padded runs back to back (VTK encodes the size
    header and the data separately)."""
    text = b"".join(text.split())
    out, i = [], 0
    while i < len(text):
        pad = text.find(b"=", i)
        end = len(text) if pad < 0 else i + ((pad - i) // 4 + 1) * 4  # end of the padded quantum
        out.append(base64.b64decode(text[i:end], validate=True))
        i = end
    return b"".join(out)


def read_vtu(path):
    """(points, arrays): points an (N, 3) float64 array, arrays {name: (N,) or (N, k)}."""
    def fail(msg):
        raise VtuError(f"{path}: {msg}")

    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        fail(e.strerror)
    # The XML parser cannot take the raw binary block: parse only the head before it.
    tag, block = data.find(b"<AppendedData"), None
    head = data
    if tag >= 0:
        gt = data.find(b">", tag)
        start, end = data.find(b"_", gt), data.rfind(b"</AppendedData>")
        if gt < 0 or start < 0 or end < start:
            fail("truncated file: the appended data is incomplete")
        # A view, not a copy: each array below slices it from its offset.
        head, block = data[:gt].rstrip(b"/") + b"/></VTKFile>", memoryview(data)[start + 1:end]
    try:
        root = ET.fromstring(head)
    except ET.ParseError as e:
        fail(f"not valid XML ({e})")
    if root.tag != "VTKFile" or root.get("type") != "UnstructuredGrid":
        fail(f"not a VTK UnstructuredGrid (type={root.get('type')!r})")
    if root.get("compressor"):
        fail("compressed files are not supported; re-save it uncompressed")
    if root.get("byte_order", "LittleEndian") != "LittleEndian":
        fail("only LittleEndian files are supported")
    header = {"UInt32": "<u4", "UInt64": "<u8"}.get(root.get("header_type", "UInt32"))
    if header is None:
        fail(f"unsupported header_type {root.get('header_type')!r}")
    hsize = np.dtype(header).itemsize
    encoding = root.find("AppendedData").get("encoding", "raw") if block is not None else None
    piece = root.find("UnstructuredGrid/Piece")
    if piece is None:
        fail("no <Piece>")
    n = int(piece.get("NumberOfPoints", "-1"))

    def array(a, what):
        comps = int(a.get("NumberOfComponents", "1"))
        if a.get("type") not in DTYPES:
            fail(f"{what}: unknown type {a.get('type')!r}")
        dtype = np.dtype(DTYPES[a.get("type")])
        count, fmt = n * comps, a.get("format")
        try:
            if fmt == "ascii":
                values = np.array((a.text or "").split(), dtype=float)
            else:
                if fmt == "binary":
                    raw = _b64((a.text or "").encode())
                elif fmt == "appended" and encoding == "raw":
                    raw = block[int(a.get("offset")):]
                elif fmt == "appended" and encoding == "base64":
                    text = bytes(block[int(a.get("offset")):]).lstrip()
                    hchars = (hsize + 2) // 3 * 4
                    size = int(np.frombuffer(_b64(text[:hchars])[:hsize], header)[0])
                    if text[hchars - 1:hchars] == b"=":  # the header is a base64 run of its own
                        raw = _b64(text[:hchars]) + _b64(text[hchars:hchars + (size + 2) // 3 * 4])
                    else:  # header and data encoded as one run
                        raw = _b64(text[:(hsize + size + 2) // 3 * 4])
                else:
                    fail(f"{what}: unsupported format {fmt!r}")
                size = int(np.frombuffer(raw[:hsize], header)[0])
                if size != count * dtype.itemsize or len(raw) < hsize + size:
                    fail(f"{what}: holds {size} bytes, expected {count * dtype.itemsize}")
                values = np.frombuffer(raw[hsize:hsize + size], dtype)
        except (ValueError, IndexError, binascii.Error) as e:
            fail(f"{what}: {e}")
        if values.size != count:
            fail(f"{what}: {values.size} values, NumberOfPoints={n} needs {count}")
        values = values.astype(np.float64)
        return values.reshape(n, comps) if comps > 1 else values

    points = piece.find("Points/DataArray")
    if points is None:
        fail("no <Points>")
    pts = array(points, "Points")
    if pts.ndim != 2 or pts.shape[1] != 3:
        fail("Points must have 3 components")
    arrays = {}
    for a in piece.findall("PointData/DataArray"):
        arrays[a.get("Name")] = array(a, f"PointData array {a.get('Name')!r}")
    return pts, arrays


def read_pvd(path, part=0):
    """[(time, absolute path)] of one part of a .pvd collection, in file order: by default
    part 0, the particle frames (dump/vtk lists the solids' .vtp surfaces as parts 1, 2, ...;
    a DataSet without a part is part 0). part=None: every DataSet."""
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as e:
        raise VtuError(f"{path}: {getattr(e, 'strerror', None) or e}")
    if root.get("type") != "Collection" or root.find("Collection") is None:
        raise VtuError(f"{path}: not a ParaView collection (VTKFile type='Collection')")
    base = os.path.dirname(os.path.abspath(path))
    try:
        return [(float(d.get("timestep", "nan")), os.path.join(base, d.get("file")))
                for d in root.find("Collection").findall("DataSet")
                if part is None or int(d.get("part", "0")) == part]
    except (TypeError, ValueError) as e:
        raise VtuError(f"{path}: a DataSet without a valid timestep or file ({e})")


if __name__ == "__main__":
    if len(sys.argv) != 2 or sys.argv[1].startswith("-"):
        sys.exit(__doc__)
    try:
        if sys.argv[1].endswith(".pvd"):
            for t, p in read_pvd(sys.argv[1]):
                print(t, p)
        else:
            pts, arrays = read_vtu(sys.argv[1])
            print(f"{len(pts)} points" + (f"; bounds {pts.min(axis=0)} .. {pts.max(axis=0)}"
                                           if len(pts) else ""))
            for name, a in arrays.items():
                print(f"  {name}: {a.shape[1] if a.ndim == 2 else 1} component(s)")
    except VtuError as e:
        sys.exit(f"vtu.py: error: {e}")
