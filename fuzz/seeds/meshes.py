#!/usr/bin/env python3
"""Writes the seeds of fuzz/corpus/mesh/ (fuzz/README.md): a unit cube as OBJ, ASCII STL and
binary STL, and OBJ files one defect away from a closed mesh. Each starts with the byte by
which fuzz_mesh picks the extension hint: 'o' obj, 's' stl, anything else none.

    python3 fuzz/seeds/meshes.py fuzz/corpus
"""
import os
import struct
import sys

out = os.path.join(sys.argv[1], "mesh")
os.makedirs(out, exist_ok=True)
# Corners x + 2y + 4z; faces counter-clockwise seen from outside.
V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0), (0, 0, 1), (1, 0, 1), (0, 1, 1), (1, 1, 1)]
Q = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
T = [t for a, b, c, d in Q for t in ((a, b, c), (a, c, d))]


def write(name, data):
    with open(os.path.join(out, name), "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


obj = "# unit cube\n" + "".join("v %d %d %d\n" % v for v in V)
obj += "".join("f %d %d %d %d\n" % tuple(i + 1 for i in q) for q in Q)
write("cube.obj", "o" + obj)
stl = "solid cube\n"
for t in T:
    stl += " facet normal 0 0 0\n  outer loop\n" + "".join("   vertex %d %d %d\n" % V[i] for i in t)
    stl += "  endloop\n endfacet\n"
write("cube_ascii.stl", "s" + stl + "endsolid cube\n")
binary = b" " * 80 + struct.pack("<I", len(T))
for t in T:
    binary += struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *V[i]) for i in t) + b"\0\0"
write("cube_binary.stl", b"s" + binary)
write("nearly_open.obj", "o" + obj.rsplit("f ", 1)[0])  # a face missing
write("nearly_flipped.obj", "o" + obj.replace("f 1 3 4 2", "f 2 4 3 1"))
write("nearly_degenerate.obj", "o" + obj + "f 1 2 2\n")
write("sniffed.obj", "-" + obj)  # no hint: Assimp finds the reader by the contents
