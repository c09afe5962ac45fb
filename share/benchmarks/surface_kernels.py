#!/usr/bin/env python3
"""Which field makes the best surface: dump/surface's three kernels compared on the dam break.

    share/benchmarks/surface_kernels.py [--binary build/pbfengine] [--rate build/bench/surface_rate]
        [--particles 33750] [--times 0,0.2,0.4,0.6] [--threads 1] [--out DIR] [--markdown FILE]

Runs scenarios/dambreak.lua once, writing text frames at the given times (t = 0 is the column
at rest, a lattice), meshes each frame with each kernel (anisotropic: Yu & Turk 2013; spheres:
Zhu & Bridson 2005; isotropic: a plain colour field), without and with one pass of the
smoothing filter, through build/bench/surface_rate (the same code as dump/surface, timed), and
measures each mesh:

  volume     the enclosed volume over the particles' (N s^3), at every frame: a surface that
             swells or shrinks the water changes it;
  top        at t = 0 only: the largest angle of a vertex normal from vertical on the column's
             top (more than 2 s from the walls), and the largest distance of those vertices from
             the column's height, in spacings;
  bend       the surface's bending at each edge, |n_i - n_j| / |x_i - x_j|, times s: its median
             and 95th percentile over the edges (weighted by length). A surface with bumps at the
             particles' scale bends by about 1 per spacing; a smooth one much less;
  pieces     the mesh's connected pieces against the particles' clusters (particles closer than
             2 s joined): a splash's droplets kept or lost; and of the pieces, the specks (an
             enclosed volume below half a particle's, s^3 / 2: no particle makes one) and the
             cavities (negative volume: a bubble the field leaves inside the water);
  seconds    the reconstruction's time (median of 3) and particles per core-second.

Prints a table (and writes it as Markdown with --markdown).
"""
import argparse
import math
import os
import re
import struct
import subprocess
import sys

import numpy as np


VARIANTS = [("anisotropic", 0), ("anisotropic", 1), ("spheres", 0), ("spheres", 1), ("isotropic", 0),
            ("isotropic", 1)]


def read_ply(path):
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    head = data[:end].decode().splitlines()
    nv = nf = 0
    props = []
    for line in head:
        w = line.split()
        if w[:2] == ["element", "vertex"]:
            nv = int(w[2])
        elif w[:2] == ["element", "face"]:
            nf = int(w[2])
        elif w[0] == "property" and w[1] == "float":
            props.append(w[2])
    cols = len(props)
    verts = np.frombuffer(data, dtype="<f4", count=nv * cols, offset=end).reshape(nv, cols)
    faces = np.frombuffer(data, dtype=np.dtype([("n", "u1"), ("i", "<i4", 3)]), count=nf, offset=end + nv * cols * 4)
    return verts[:, :3].astype(float), verts[:, 3:6].astype(float), faces["i"].astype(np.int64)


def volume(x, tri):
    a, b, c = x[tri[:, 0]], x[tri[:, 1]], x[tri[:, 2]]
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6)


def piece_volumes(x, tri):
    """Each connected piece's enclosed volume (scipy's connected components)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    e = np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]]])
    graph = coo_matrix((np.ones(len(e)), (e[:, 0], e[:, 1])), shape=(len(x), len(x)))
    count, label = connected_components(graph, directed=False)
    a, b, c = x[tri[:, 0]], x[tri[:, 1]], x[tri[:, 2]]
    v = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6
    return np.bincount(label[tri[:, 0]], weights=v, minlength=count)[np.unique(label[tri[:, 0]])]


def components(n, edges):
    parent = np.arange(n)

    def find(v):
        root = v
        while parent[root] != root:
            root = parent[root]
        while parent[v] != root:
            parent[v], v = root, parent[v]
        return root

    for a, b in edges:
        ra, rb = find(a), find(b)
        if ra != rb:
            parent[ra] = rb
    return len({find(v) for v in range(n)})


def particle_clusters(p, r):
    """Clusters of particles closer than r (a grid of r-wide cells)."""
    cells = {}
    keys = np.floor(p / r).astype(np.int64)
    for i, k in enumerate(map(tuple, keys)):
        cells.setdefault(k, []).append(i)
    edges = []
    for k, members in cells.items():
        near = []
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    near += cells.get((k[0] + dx, k[1] + dy, k[2] + dz), [])
        near = np.array(near)
        for i in members:
            d = np.sum((p[near] - p[i]) ** 2, axis=1)
            for j in near[(d < r * r) & (near > i)]:
                edges.append((i, int(j)))
    return components(len(p), edges)


def analyse(ply, spacing, particles, column=None):
    x, n, tri = read_ply(ply)
    out = {"volume": volume(x, tri) / (particles * spacing ** 3)}
    e = np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]])
    e = e[e[:, 0] < e[:, 1]]  # each edge once
    length = np.linalg.norm(x[e[:, 0]] - x[e[:, 1]], axis=1)
    ok = length > 1e-9
    bend = np.linalg.norm(n[e[ok, 0]] - n[e[ok, 1]], axis=1) / length[ok] * spacing
    order = np.argsort(bend)
    cum = np.cumsum(length[ok][order]) / length[ok].sum()
    out["bend50"] = float(bend[order][np.searchsorted(cum, 0.5)])
    out["bend95"] = float(bend[order][np.searchsorted(cum, 0.95)])
    pieces = piece_volumes(x, tri)
    out["pieces"] = len(pieces)
    out["specks"] = int(((pieces > 0) & (pieces < 0.5 * spacing ** 3)).sum())
    out["cavities"] = int((pieces < 0).sum())
    if column:
        height, width, depth = column
        top = (x[:, 2] > height - 2 * spacing) & (x[:, 0] > 2 * spacing) & (x[:, 0] < width - 2 * spacing) & \
              (x[:, 1] > 2 * spacing) & (x[:, 1] < depth - 2 * spacing)
        out["top_angle"] = float(np.degrees(np.arccos(np.clip(n[top, 2], -1, 1))).max())
        out["top_height"] = float(np.abs(x[top, 2] - height).max() / spacing)
    return out


def read_frame(path):
    with open(path) as f:
        lines = f.read().split("\n")
    count = int(lines[0])
    return np.array([[float(v) for v in line.split()[:3]] for line in lines[1:count + 1]])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", default="build/pbfengine")
    ap.add_argument("--rate", default="build/bench/surface_rate")
    ap.add_argument("--particles", type=int, default=33750)
    ap.add_argument("--times", default="0,0.2,0.4,0.6")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--out", default="out/surface_kernels")
    ap.add_argument("--markdown")
    args = ap.parse_args()
    for tool in (args.binary, args.rate):
        if not os.access(tool, os.X_OK):
            sys.exit(f"surface_kernels.py: {tool} is not an executable (build it first)")
    times = [float(t) for t in args.times.split(",")]
    steps = sorted(set(times))
    interval = min(b - a for a, b in zip([0] + steps, steps) if b > a) if len(steps) > 1 else 1
    a = 0.1
    layers = max(4, math.floor(args.particles ** (1 / 3) + 0.5))
    s = a / layers
    depth = layers // 2 * s
    domain = [0, 0, 0, 5 * a, depth, 4 * a]
    os.makedirs(args.out, exist_ok=True)
    subprocess.run([args.binary, "run", "scenarios/dambreak.lua", "-v", f"particles={args.particles}",
                    "-v", f"t_end={max(times)}", "-v", f"out={args.out}", "-v", f"interval={interval}",
                    "-v", "restart_interval=0", "--log", "none"], check=True, stdout=subprocess.DEVNULL)
    rows = []
    for t in times:
        frame = os.path.join(args.out, f"frame_{round(t / interval):05d}.txt")
        p = read_frame(frame)
        clusters = particle_clusters(p, 2 * s)
        for kernel, smoothing in VARIANTS:
            ply = os.path.join(args.out, f"surface_{kernel}_{smoothing}_{t:g}.ply")
            run = subprocess.run([args.rate, frame, "--spacing", str(s), "--kernel", kernel, "--smoothing",
                                  str(smoothing), "--threads", str(args.threads), "--ply", ply, "--domain"] +
                                 [str(v) for v in domain], check=True, capture_output=True, text=True).stdout
            seconds = float(re.search(r"total ([0-9.]+)", run).group(1))
            rate = float(re.search(r"per core-second: ([0-9.]+)", run).group(1))
            m = analyse(ply, s, len(p), (2 * a, a, depth) if t == 0 else None)
            rows.append((t, kernel, smoothing, m, clusters, seconds, rate))
    head = ("| t (s) | kernel | smoothing | volume | top angle (deg) | top height (s) | bend median | bend 95% | "
            "pieces / clusters | specks | cavities | seconds | particles per core-s |")
    lines = [head, "|" + "---|" * 13]
    for t, kernel, smoothing, m, clusters, seconds, rate in rows:
        top = (f"{m['top_angle']:.1f}", f"{m['top_height']:.2f}") if "top_angle" in m else ("", "")
        lines.append(f"| {t:g} | {kernel} | {smoothing} | {m['volume']:.4f} | {top[0]} | {top[1]} | {m['bend50']:.3f} | "
                     f"{m['bend95']:.3f} | {m['pieces']} / {clusters} | {m['specks']} | {m['cavities']} | "
                     f"{seconds:.3f} | {rate:.0f} |")
    text = "\n".join(lines)
    print(text)
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write(text + "\n")


if __name__ == "__main__":
    main()
