#!/usr/bin/env python3
"""Writes the hand-made seeds of fuzz/corpus/{vtu,csv,scene_file}/ (fuzz/README.md): each
encoding and layout the readers accept, and a few files one defect away from valid. The
.vtu seed the engine itself writes comes from a dump/vtk frame (README.md).

    python3 fuzz/seeds/particle_files.py fuzz/corpus
"""
import base64
import os
import struct
import sys

out = sys.argv[1]
# Two particles inside the fuzz targets' domain [-1, 1]^3, h/2 apart (h = 0.05 there), as
# the engine wants them (resolution.hpp): seeds that load reach the mass rule.
POINTS = [0.1, 0.2, 0.3, 0.125, 0.2, 0.3]
VELOCITY = [1.0, 0.0, -1.0, 0.5, 0.5, 0.0]
MASS = [0.001, 0.002]


def write(target, name, data):
    os.makedirs(os.path.join(out, target), exist_ok=True)
    with open(os.path.join(out, target, name), "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


def vtk(piece, header_type="UInt32", appended=None, encoding="raw"):
    text = ('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" '
            f'byte_order="LittleEndian" header_type="{header_type}">\n  <UnstructuredGrid>\n'
            f'    <Piece NumberOfPoints="2" NumberOfCells="0">\n{piece}    </Piece>\n  </UnstructuredGrid>\n')
    data = text.encode()
    if appended is not None:
        data += f'  <AppendedData encoding="{encoding}">\n   _'.encode() + appended + b"\n  </AppendedData>\n"
    return data + b"</VTKFile>\n"


def array(type_, name, components, fmt, body="", offset=None):
    attrs = f'type="{type_}"' + (f' Name="{name}"' if name else "") + f' NumberOfComponents="{components}" format="{fmt}"'
    if offset is not None:
        return f"        <DataArray {attrs} offset=\"{offset}\"/>\n"
    return f"        <DataArray {attrs}>{body}</DataArray>\n"


def pack(code, values):
    return struct.pack(f"<{len(values)}{code}", *values)


# --- .vtu: ascii
write("vtu", "ascii.vtu", vtk(
    "      <PointData>\n" + array("Float32", "mass", 1, "ascii", " 0.001 +0.002 ") + "      </PointData>\n"
    "      <Points>\n" + array("Float64", "", 3, "ascii", "\n 0.1 0.2 0.3\n 0.125 0.2 0.3\n ") + "      </Points>\n"))

# --- .vtu: inline base64, VTK's way (size header and data as two base64 runs), UInt32 headers
def inline(code, values, header="I"):
    data = pack(code, values)
    return base64.b64encode(struct.pack("<" + header, len(data))).decode() + base64.b64encode(data).decode()


write("vtu", "binary_uint32.vtu", vtk(
    "      <PointData>\n" + array("Int32", "id", 1, "binary", inline("i", [3, 4]))
    + array("Float64", "velocity", 3, "binary", inline("d", VELOCITY)) + "      </PointData>\n"
    "      <Points>\n" + array("Float32", "", 3, "binary", inline("f", POINTS)) + "      </Points>\n"))

# --- .vtu: appended raw with UInt32 headers and <Cells>, as ParaView's "Save Data" writes it
blocks, piece, offset = b"", "", 0


def block(code, values, header="I"):
    global blocks, offset
    data = pack(code, values)
    at = offset
    blocks += struct.pack("<" + header, len(data)) + data
    offset = len(blocks)
    return at


piece = ("      <PointData>\n" + array("Float64", "mass", 1, "appended", offset=block("d", MASS)) + "      </PointData>\n"
         "      <Points>\n" + array("Float32", "Points", 3, "appended", offset=block("f", POINTS)) + "      </Points>\n"
         "      <Cells>\n" + array("Int64", "connectivity", 1, "appended", offset=block("q", [0, 1]))
         + array("Int64", "offsets", 1, "appended", offset=block("q", [1, 2]))
         + array("UInt8", "types", 1, "appended", offset=block("B", [1, 1])) + "      </Cells>\n")
write("vtu", "appended_raw_uint32.vtu", vtk(piece, "UInt32", blocks))

# The defect the issue names: header_type says UInt32, the blocks have UInt64 sizes.
blocks, offset = b"", 0
piece = ("      <PointData>\n" + array("Float64", "mass", 1, "appended", offset=block("d", MASS, "Q")) + "      </PointData>\n"
         "      <Points>\n" + array("Float64", "Points", 3, "appended", offset=block("d", POINTS, "Q")) + "      </Points>\n")
write("vtu", "header_type_mismatch.vtu", vtk(piece, "UInt32", blocks))

# --- .vtu: appended base64 (offsets count characters), UInt64 headers
def b64block(code, values):
    data = pack(code, values)
    return (base64.b64encode(struct.pack("<Q", len(data))) + base64.b64encode(data))


mass64, points64 = b64block("d", MASS), b64block("d", POINTS)
piece = ("      <PointData>\n" + array("Float64", "mass", 1, "appended", offset=0) + "      </PointData>\n"
         "      <Points>\n" + array("Float64", "Points", 3, "appended", offset=len(mass64)) + "      </Points>\n")
write("vtu", "appended_base64.vtu", vtk(piece, "UInt64", mass64 + points64, "base64"))

# --- .csv
write("csv", "scalars.csv", "x,y,z,vx,vy,vz,mass\n0.1,0.2,0.3,1,0,-1,0.001\n0.125,0.2,0.3,0.5,0.5,0,0.002\n")
write("csv", "bom_crlf_comments.csv",
      "\ufeff# particles\r\n\r\n \"x\" , y,z,T\r\n0.1, +0.2 ,0.3,20\r\n  # more\r\n1.25e-1,0.2,3e-1,21\r\n")
write("csv", "paraview.csv", '"Points:0","Points:1","Points:2","velocity:0","velocity:1","velocity:2","rho"\n'
      "0.1,0.2,0.3,1,0,-1,1000\n0.125,0.2,0.3,0.5,0.5,0,1001\n")
write("csv", "nearly_half_vector.csv", "x,y,vx,vy,vz\n0.1,0.2,0,0,0\n")
write("csv", "nearly_nan.csv", "x,y,z,mass\n0.1,0.2,nan,0.001\n0.1,inf,0.3,-1\n")

# --- scene files (the original study's format)
write("scene_file", "two.txt", "2 0.002 0.04 0.4 0.01 0.03\n0.1 0.1 0.1 0 0 -1\n0.12 0.1 0.1 1 0 0\n")
write("scene_file", "comments_bom_crlf.txt",
      "\ufeff# a comment\r\n2 0.002\r\n0.04 0.4\r\n  # another\r\n0.01 0.03\r\n0.1 0.1 0.1 0 0 -1\r\n\r\n+0.12 0.1 0.1 1 0 0\r\n")
lattice = "27 0.001 0.02 0.12 0.01 0.02\n" + "".join(
    f"{0.04 + 0.01 * i:.2f} {0.04 + 0.01 * j:.2f} {0.04 + 0.01 * k:.2f} 0 0 0\n"
    for k in range(3) for j in range(3) for i in range(3))
write("scene_file", "lattice.txt", lattice)
write("scene_file", "nearly_count.txt", "3 0.002 0.04 0.4 0.01 0.03\n0.1 0.1 0.1 0 0 -1\n0.2 0.1 0.1 1 0 0\n")
write("scene_file", "nearly_outside.txt", "2 0.002 0.04 0.4 0.01 0.03\n0.1 0.1 0.5 0 0 -1\n0.2 0.1 0.1 1e400 0 0\n")
