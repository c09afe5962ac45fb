#!/usr/bin/env python3
"""Render pbfengine frames to PNG images (and optionally an mp4): the visualiser of the
original study, rebuilt.

Usage:
    python3 share/render_frames.py out/                       # PNGs in out/png/
    python3 share/render_frames.py out/ --interval 0.02 --movie dambreak.mp4
    python3 share/render_frames.py out/ --every 5 --L 1.0 --vmax 3 --view 25 -70
    python3 share/render_frames.py out/frames.pvd --movie dambreak.mp4

Reads FRAMES_DIR/frame_00000.txt, frame_00001.txt, ... (line 1: the integer N, then N
lines 'x y z vx vy vz'); or, when the directory has no text frames (or with --format
vtu), FRAMES_DIR/frame_NNNNN.vtu; or the .vtu files that a ParaView collection (.pvd)
lists, with their times. A .vtu frame gives the Points and the PointData array
'velocity' (zero if absent). Each frame is drawn as a 3D scatter (z up) coloured by the
speed |v|, with a colour bar. Every image uses the same axes ([0,L]^3, L from --L or
the largest coordinate seen, rounded up) and the same colour range (0 to --vmax, or to
the largest speed in the frames rendered), so a movie does not flicker.

Images are numbered consecutively, OUT/img_00000.png, img_00001.png, ... (so ffmpeg
finds a gapless sequence even with --every); the title gives the frame number, and
the time: k * interval when --interval is given, else the .pvd's time. Images left
over from an earlier, longer run in OUT are removed so they cannot end up in the movie.

Needs numpy and matplotlib (on Debian: apt install python3-numpy python3-matplotlib,
then run with /usr/bin/python3), and ffmpeg for --movie.
"""
import argparse
import glob
import math
import os
import re
import shutil
import subprocess
import sys

try:
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")  # no display needed; must precede pyplot
    import matplotlib.pyplot as plt
    from matplotlib import cm, colors
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import vtu  # share/vtu.py, beside this script
except ImportError as e:
    sys.exit(f"render_frames.py: error: {e}; install python3-numpy and python3-matplotlib "
             "(Debian) and run with /usr/bin/python3")

FRAME_RE = re.compile(r"^frame_(\d{5})\.(txt|vtu)$")
IMG_RE = re.compile(r"^img_(\d{5})\.png$")


def fail(msg):
    sys.exit(f"render_frames.py: error: {msg}")


def list_frames(source, fmt="auto"):
    """Sorted (index, path, time or None) of the frames in a directory or a .pvd."""
    if source.endswith(".pvd") and os.path.isfile(source):
        try:
            return [(k, path, t) for k, (t, path) in enumerate(vtu.read_pvd(source))]
        except vtu.VtuError as e:
            fail(str(e))
    if not os.path.isdir(source):
        fail(f"frames directory {source!r} does not exist or is not a directory (or a .pvd file)")
    found = {"txt": [], "vtu": []}
    for path in glob.glob(os.path.join(source, "frame_*.*")):
        m = FRAME_RE.search(os.path.basename(path))
        if m:
            found[m.group(2)].append((int(m.group(1)), path, None))
    if fmt == "auto":  # text frames first, as before .vtu frames existed
        fmt = "txt" if found["txt"] or not found["vtu"] else "vtu"
        if found["txt"] and found["vtu"]:
            print(f"render_frames.py: note: {source!r} also holds .vtu frames; "
                  "--format vtu shows them", file=sys.stderr)
    if not found[fmt]:
        fail(f"no frame_NNNNN.{fmt} files in {source!r}")
    return sorted(found[fmt])


def read_vtu_frame(path):
    """(N, 6) array x y z vx vy vz of a .vtu frame; velocity zero if it has none."""
    try:
        points, arrays = vtu.read_vtu(path)
    except vtu.VtuError as e:
        fail(str(e))
    v = arrays.get("velocity")
    if v is None or v.shape != points.shape:
        if not getattr(read_vtu_frame, "warned", False):
            print(f"render_frames.py: note: {path} has no 3-component 'velocity'; "
                  "speeds shown as 0", file=sys.stderr)
            read_vtu_frame.warned = True
        v = np.zeros_like(points)
    return np.hstack([points, v])


def read_frame(path):
    """(N, 6) float array of one frame; checks the count against line 1."""
    if path.endswith(".vtu"):
        return read_vtu_frame(path)
    try:
        with open(path) as f:
            head = f.readline().strip()
            body = f.read()
    except (OSError, UnicodeDecodeError) as e:
        fail(f"cannot read {path}: {getattr(e, 'strerror', None) or e}")
    if not head.isdigit():
        fail(f"{path}:1: expected the particle count, found {head[:40]!r}")
    n = int(head)
    try:
        # np.loadtxt is several times slower on big frames; a flat parse is enough here.
        vals = np.array(body.split(), dtype=float)
    except ValueError:
        fail(f"{path}: a non-numeric value in the particle lines")
    if vals.size != 6 * n:
        fail(f"{path}: line 1 says {n} particles, but the file holds {vals.size} values "
             f"(expected {6 * n})")
    return vals.reshape(n, 6)


def nice_ceil(x):
    """Round up to a multiple of half a power of ten: 0.98 -> 1.0, 0.31 -> 0.35."""
    if x <= 0:
        return 1.0
    step = 10.0 ** math.floor(math.log10(x)) / 2
    return math.ceil(x / step - 1e-9) * step


def parse_args(argv):
    p = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0], epilog=__doc__.split("\n\n", 1)[1],
        formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("frames_dir",
                   help="directory holding frame_NNNNN.txt (or .vtu) files, or a .pvd")
    p.add_argument("--format", choices=("auto", "txt", "vtu"), default="auto",
                   help="which frames of the directory: auto (text ones if any, else .vtu)")
    p.add_argument("--out", help="directory for the PNGs (default FRAMES_DIR/png, or png/ "
                   "beside the .pvd)")
    p.add_argument("--every", type=int, default=1, metavar="K", help="render every Kth frame")
    p.add_argument("--L", type=float, help="domain side; default: largest coordinate, rounded up")
    p.add_argument("--box", type=float, nargs=3, metavar=("X", "Y", "Z"),
                   help="a box domain [0,X]x[0,Y]x[0,Z] instead of a cube (e.g. a dam-break tank)")
    p.add_argument("--vmax", type=float, help="top of the speed colour range (m/s); default: "
                   "the largest speed in the frames rendered")
    p.add_argument("--interval", type=float, help="output interval (s), to show time in titles")
    p.add_argument("--movie", metavar="FILE.mp4", help="also assemble an mp4 with ffmpeg")
    p.add_argument("--fps", type=float, default=25, help="movie frame rate (default 25)")
    p.add_argument("--size", type=int, nargs="+", default=[800], metavar="PX",
                   help="image size in pixels: W (square) or W H (default 800)")
    p.add_argument("--view", type=float, nargs=2, default=[20.0, -60.0],
                   metavar=("ELEV", "AZIM"), help="camera elevation and azimuth (deg)")
    p.add_argument("--max-points", type=int, default=50000,
                   help="draw at most this many particles per frame (default 50000)")
    p.add_argument("--point-size", type=float, help="marker size (points^2); default by count")
    p.add_argument("--cmap", default="viridis", help="matplotlib colour map (default viridis)")
    args = p.parse_args(argv)
    if args.every < 1 or args.max_points < 1:
        fail("--every and --max-points must be at least 1")
    if len(args.size) > 2 or min(args.size) < 16:
        fail("--size takes one or two pixel counts, each at least 16")
    for name in ("L", "vmax", "interval", "fps", "point_size"):
        v = getattr(args, name)
        if v is not None and not (math.isfinite(v) and v > 0):
            fail(f"--{name.replace('_', '-')} must be positive, got {v!r}")
    if args.cmap not in plt.colormaps():
        fail(f"unknown colour map {args.cmap!r}")
    return args


def main(argv=None):
    args = parse_args(argv)
    frames = list_frames(args.frames_dir, args.format)[::args.every]
    ffmpeg = shutil.which("ffmpeg")
    if args.movie and not ffmpeg:  # fail before spending minutes on images
        fail("--movie needs ffmpeg, which is not on PATH (Debian: apt install ffmpeg)")
    if args.movie and not os.path.isdir(os.path.dirname(os.path.abspath(args.movie))):
        fail(f"the directory for --movie {args.movie!r} does not exist")
    src = args.frames_dir if os.path.isdir(args.frames_dir) else os.path.dirname(args.frames_dir)
    out = args.out or os.path.join(src, "png")
    try:
        os.makedirs(out, exist_ok=True)
    except OSError as e:
        fail(f"cannot create {out!r}: {e.strerror}")

    # First pass, only if needed: fixed axes and colour range across all frames.
    L, vmax = args.L, args.vmax
    if L is None or vmax is None:
        cmax, smax = 0.0, 0.0
        for _, path, _ in frames:
            d = read_frame(path)
            if len(d):
                cmax = max(cmax, float(d[:, :3].max()))
                smax = max(smax, float(np.sqrt((d[:, 3:] ** 2).sum(axis=1)).max()))
        L = L if L is not None else nice_ceil(cmax)
        vmax = vmax if vmax is not None else (smax if smax > 0 else 1.0)
    print(f"render_frames.py: {len(frames)} frames, L={L:g}, speed range 0..{vmax:.4g} m/s",
          file=sys.stderr)

    # One figure reused for every frame: only the scatter and the title change.
    w, h = (args.size * 2)[:2]
    fig = plt.figure(figsize=(w / 100, h / 100), dpi=100)
    # Explicit placement: the default layout leaves the 3D box small in a wide margin.
    ax = fig.add_axes([0.0, 0.02, 0.84, 0.9], projection="3d")
    box = args.box if args.box else (L, L, L)
    if min(box) <= 0:
        fail("--box sides must be positive")
    ax.set_xlim(0, box[0]), ax.set_ylim(0, box[1]), ax.set_zlim(0, box[2])
    ax.set_box_aspect(box)
    ax.set_xlabel("x (m)"), ax.set_ylabel("y (m)"), ax.set_zlabel("z (m)")
    ax.view_init(elev=args.view[0], azim=args.view[1])
    norm = colors.Normalize(vmin=0.0, vmax=vmax)
    cmap = plt.get_cmap(args.cmap)
    fig.colorbar(cm.ScalarMappable(norm=norm, cmap=cmap), cax=fig.add_axes([0.87, 0.3, 0.025, 0.4]),
                 label="speed |v| (m/s)")
    suptitle = fig.suptitle("", y=0.97)
    scatter = None
    for i, (k, path, time) in enumerate(frames):
        d = read_frame(path)
        n = len(d)
        d = d[::max(1, math.ceil(n / args.max_points))]  # even, deterministic subsample
        speed = np.sqrt((d[:, 3:] ** 2).sum(axis=1))
        size = args.point_size or float(np.clip(6e4 / max(len(d), 1), 0.3, 20.0))
        if scatter is not None:
            scatter.remove()
        scatter = ax.scatter(d[:, 0], d[:, 1], d[:, 2], c=speed, cmap=cmap, norm=norm,
                             s=size, depthshade=False, linewidths=0)
        title = f"frame {k}"
        if args.interval:
            title += f"   t = {k * args.interval:.4g} s"
        elif time is not None:
            title += f"   t = {time:.4g} s"
        shown = f", {len(d)} drawn" if len(d) < n else ""
        suptitle.set_text(f"{title}   ({n} particles{shown})")
        fig.savefig(os.path.join(out, f"img_{i:05d}.png"))
        print(f"\rrender_frames.py: {i + 1}/{len(frames)}", end="", file=sys.stderr, flush=True)
    print(file=sys.stderr)
    plt.close(fig)

    # Images from an earlier, longer run would otherwise slip into the movie.
    for path in glob.glob(os.path.join(out, "img_*.png")):
        m = IMG_RE.search(os.path.basename(path))
        if m and int(m.group(1)) >= len(frames):
            os.remove(path)
    print(f"render_frames.py: images in {out}/img_00000.png ...", file=sys.stderr)

    if args.movie:
        cmd = [ffmpeg, "-y", "-framerate", f"{args.fps:g}", "-i",
               os.path.join(out, "img_%05d.png"), "-pix_fmt", "yuv420p",
               "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", args.movie]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            tail = "\n".join(r.stderr.strip().splitlines()[-5:])
            fail(f"ffmpeg failed (exit {r.returncode}):\n{tail}")
        print(f"render_frames.py: movie {args.movie}", file=sys.stderr)


if __name__ == "__main__":
    main()
