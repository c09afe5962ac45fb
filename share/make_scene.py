#!/usr/bin/env python3
"""Write a pbfengine scene file: a dam break, a falling cube or a hydrostatic column.

Usage:
    python3 share/make_scene.py --kind dambreak --particles 30000 -o dambreak.txt
    python3 share/make_scene.py --kind cube --particles 5000 --velocity 0 0 -1 cube.txt
    python3 share/make_scene.py --kind column --L 0.5 --a 0.3 column.txt
    pbfengine run scenarios/init_file.lua -v init=dambreak.txt -v out=frames

Pure standard library: any python3 runs it. The output is deterministic.

Scene file written: one '#' comment line describing the scene, then the six header
values on separate lines (N, dt, h, L, output interval, final time), then N lines
'x y z vx vy vz'. Floats are written with repr() so they round-trip exactly.

Geometry (domain [0,L]^3, z up; --a sets the fluid's size, its meaning per kind):
  dambreak  a block a wide (x) and 2a high (z) against the x=0 wall, filling the whole
            y extent: Martin & Moyce's column of height 2a. Default a = L/5; L >= 5a.
  cube      a cube of side a (default L/4), centred in x and y, its bottom --drop
            above the floor (default L/4).
  column    fluid over the whole x-y extent up to height a (default L/2).
Particles sit on a cubic lattice of spacing s at lo + (i+0.5)*s, so none lies on a
wall, and h = 2*s exactly. s is chosen so that the count is as close as possible to
--particles while keeping the geometry exact: the dam-break block is exactly
k*s = a wide and 2k*s = 2a high and the cube exactly k*s = a a side, so those counts
move in steps (dambreak with L = 5a: 10*k^3 particles, cube: k^3); the column fills
x-y completely or its height exactly, whichever comes closer. The actual count and
geometry are reported on stderr and in the comment line.

Default time step: dt = min(0.002, 0.4*h/v) rounded down to two significant digits,
where v = sqrt(2*g*L) + |velocity| bounds the speed a particle can reach by falling
across the domain (a CFL-like limit, so fine lattices get a smaller step).
"""
import argparse
import math
import sys

G = 9.81
EPS = 1e-9  # guards floor() against round-off when extent/s is an integer


def fail(msg):
    sys.exit(f"make_scene.py: error: {msg}")


def fit(extent, s):
    """Lattice sites of spacing s that fit in [0, extent] without touching its ends."""
    return int(math.floor(extent / s + EPS))


def scan(length, dims_of, target):
    """(s, dims) for s = length/k, k = 1, 2, ... until the count passes twice the target."""
    out, k = [], 1
    while True:
        s = length / k
        dims = dims_of(s, k)
        out.append((s, dims))
        if dims[0] * dims[1] * dims[2] > 2 * target:
            return out
        k += 1


def choose(candidates, target):
    """Pick (s, dims) from (s, dims) pairs: count closest to target, then coarser s."""
    def key(c):
        s, dims = c
        return (abs(dims[0] * dims[1] * dims[2] - target), -s)
    valid = [c for c in candidates if min(c[1]) >= 1]
    if not valid:
        fail("no lattice fits the requested geometry")
    return min(valid, key=key)


def plan(kind, L, a, drop, target):
    """Return (s, (nx, ny, nz), origin, description) for the kind's geometry."""
    if kind == "dambreak":
        # s = a/k keeps the block exactly a x 2a; y is filled as far as the lattice fits.
        cands = scan(a, lambda s, k: (k, fit(L, s), 2 * k), target)
        s, dims = choose(cands, target)
        desc = (f"dam break: column a={a!r} wide (x), 2a={2 * a!r} high (z), "
                f"{dims[1] * s:.6g} deep (y), against x=0")
        return s, dims, (0.0, 0.0, 0.0), desc
    if kind == "cube":
        cands = scan(a, lambda s, k: (k, k, k), target)
        s, dims = choose(cands, target)
        lo = 0.5 * (L - a)
        desc = f"falling cube: side a={a!r}, bottom at z={drop!r}, centred in x and y"
        return s, dims, (lo, lo, drop), desc
    # column: either s = L/m (x-y filled exactly) or s = a/k (height exact).
    cands = scan(L, lambda s, m: (m, m, fit(a, s)), target)
    cands += scan(a, lambda s, k: (fit(L, s), fit(L, s), k), target)
    s, dims = choose(cands, target)
    desc = (f"hydrostatic column: fluid over x-y [0,{dims[0] * s:.6g}]^2 "
            f"up to z={dims[2] * s:.6g} (requested {a!r})")
    return s, dims, (0.0, 0.0, 0.0), desc


def default_dt(h, L, vel):
    v = math.sqrt(2.0 * G * L) + math.sqrt(sum(c * c for c in vel))
    dt = min(0.002, 0.4 * h / v)
    mag = 10.0 ** (math.floor(math.log10(dt)) - 1)  # two significant digits, rounded down
    return float(f"{math.floor(dt / mag + EPS) * mag:.2g}")  # clean repr, e.g. 0.0011


class Formatter(argparse.RawDescriptionHelpFormatter, argparse.ArgumentDefaultsHelpFormatter):
    def _get_help_string(self, action):  # show defaults, but not 'None'
        if action.default is None:
            return action.help
        return super()._get_help_string(action)


def parse_args(argv):
    p = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0], epilog=__doc__.split("\n\n", 1)[1],
        formatter_class=Formatter)
    p.add_argument("output", nargs="?", help="output scene file ('-' for stdout)")
    p.add_argument("-o", "--output", dest="output_opt", metavar="FILE",
                   help="output scene file (alternative to the positional argument)")
    p.add_argument("--kind", choices=["dambreak", "cube", "column"], default="dambreak",
                   help="what to build (see below)")
    p.add_argument("--particles", type=int, default=5000, help="approximate particle count")
    p.add_argument("--L", type=float, default=1.0, help="cubic domain side (m)")
    p.add_argument("--a", type=float, default=None, metavar="SIZE",
                   help="fluid size (m): dambreak column width (default L/5), "
                        "cube side (default L/4), column fill height (default L/2)")
    p.add_argument("--drop", type=float, default=None,
                   help="cube only: height of the cube's bottom above the floor (default L/4)")
    p.add_argument("--dt", type=float, default=None,
                   help="time step (s); default min(0.002, 0.4 h / v), see docstring")
    p.add_argument("--interval", type=float, default=0.02, help="output interval (s)")
    p.add_argument("--t-final", type=float, default=1.0, help="final time (s)")
    p.add_argument("--velocity", type=float, nargs=3, default=[0.0, 0.0, 0.0],
                   metavar=("VX", "VY", "VZ"), help="initial velocity of every particle (m/s)")
    return p.parse_args(argv)


def validate(args):
    if args.output and args.output_opt and args.output != args.output_opt:
        fail("give the output file once, either positionally or with -o")
    args.output = args.output or args.output_opt
    if not args.output:
        fail("no output file given (positional FILE or -o FILE; '-' for stdout)")
    L = args.L
    nums = {"--L": L, "--interval": args.interval, "--t-final": args.t_final}
    for name, v in list(nums.items()) + [("--velocity", c) for c in args.velocity]:
        if not math.isfinite(v):
            fail(f"{name} must be a finite number, got {v!r}")
    for name, v in nums.items():
        if v <= 0:
            fail(f"{name} must be positive, got {v!r}")
    if args.particles < 1:
        fail(f"--particles must be at least 1, got {args.particles}")
    if args.dt is not None and not (math.isfinite(args.dt) and args.dt > 0):
        fail(f"--dt must be positive, got {args.dt!r}")
    if args.a is None:
        args.a = {"dambreak": L / 5, "cube": L / 4, "column": L / 2}[args.kind]
    if not (math.isfinite(args.a) and args.a > 0):
        fail(f"--a must be positive, got {args.a!r}")
    if args.drop is not None and args.kind != "cube":
        fail("--drop applies to --kind cube only")
    if args.kind == "dambreak" and L < 5 * args.a * (1 - EPS):
        fail(f"dambreak needs L >= 5a (the surge needs room): L={L!r}, a={args.a!r}")
    if args.kind == "cube":
        args.drop = L / 4 if args.drop is None else args.drop
        if args.a > L or args.drop < 0 or args.drop + args.a > L:
            fail(f"the cube (side {args.a!r}, bottom at {args.drop!r}) does not fit in [0,{L!r}]^3")
    if args.kind == "column" and args.a > L:
        fail(f"column height {args.a!r} exceeds the domain side {L!r}")
    if args.t_final < args.interval:
        print("make_scene.py: warning: --t-final is shorter than --interval; "
              "only frame 0 will be written", file=sys.stderr)


def main(argv=None):
    args = parse_args(argv)
    validate(args)
    L = args.L
    s, (nx, ny, nz), (ox, oy, oz), desc = plan(args.kind, L, args.a, args.drop, args.particles)
    n = nx * ny * nz
    h = 2.0 * s
    dt = args.dt if args.dt is not None else default_dt(h, L, args.velocity)
    vel = " ".join(repr(float(c)) for c in args.velocity)

    # Sites lie strictly inside the fluid block, which lies inside [0, L]^3.
    lines = [f"# {desc}; lattice {nx}x{ny}x{nz} spacing s={s!r}, h=2s; "
             f"velocity ({vel}); header: N dt h L interval t_final",
             str(n), repr(dt), repr(h), repr(L), repr(args.interval), repr(args.t_final)]
    for k in range(nz):
        z = oz + (k + 0.5) * s
        for j in range(ny):
            y = oy + (j + 0.5) * s
            for i in range(nx):
                lines.append(f"{ox + (i + 0.5) * s!r} {y!r} {z!r} {vel}")
    text = "\n".join(lines) + "\n"
    if args.output == "-":
        sys.stdout.write(text)
    else:
        try:
            with open(args.output, "w") as f:
                f.write(text)
        except OSError as e:
            fail(f"cannot write {args.output}: {e.strerror}")
    off = 100.0 * (n - args.particles) / args.particles
    print(f"make_scene.py: {args.kind}: {n} particles ({off:+.1f}% from the {args.particles} "
          f"requested), lattice {nx}x{ny}x{nz}, s={s:.6g}, h={h:.6g}, L={L:g}, dt={dt:.6g}, "
          f"a={args.a:.6g} -> {args.output}", file=sys.stderr)


if __name__ == "__main__":
    main()
