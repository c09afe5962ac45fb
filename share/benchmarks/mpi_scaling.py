#!/usr/bin/env python3
"""Distributed runs of pbfengine: the original study's MPI tables, measured on this machine.

The runs are those of scaling.py (the dam break of share/make_scene.py --kind dambreak, run
through scenarios/init_file.lua: PBF with 4 iterations, vorticity, XSPH, box walls), under
`mpirun -np P --bind-to none` with OMP_NUM_THREADS=T, or without mpirun for one process.
Each figure is the median of --repeats runs, the configurations compared taking turns, so
that slow spells of a shared machine fall on all of them. Tables (Markdown on stdout; with
--out DIR also DIR/mpi.md):

  strong   the 33,750-particle dam break (75 steps) as 1 process x 1 thread, 1 process x 2
           threads and 2 ranks x 1 thread: time per step, speed-up over 1 x 1, and the
           2 ranks x 1 thread / 1 process x 2 threads ratio (target: within 15%).
  weak     about 2,197 particles per rank (100 steps): 1 rank and 2 ranks of 1 thread,
           efficiency t(1) / t(2).
  profile  the original study's phases per step at 2 ranks x 1 thread on the 33,750-particle
           dam break, with communication: migration and ghosts at the neighbour stage, and
           the ghosts' updates inside the solver's passes, as a share of the step (target:
           at most 10%): rank 0's, and the least and most of the two ranks in each run (a
           rank's time includes waiting at each exchange for the slower one; the least is
           nearest the transfers' own cost), medians over the runs.

    share/benchmarks/mpi_scaling.sh [--repeats 5] [--out docs/performance] [--solver dfsph]

Open MPI as root needs OMPI_ALLOW_RUN_AS_ROOT(_CONFIRM); in containers
OMPI_MCA_btl_vader_single_copy_mechanism=none: this script sets them.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scaling  # noqa: E402  (the scene, the timing table's parser, the phases)

COMMUNICATION = re.compile(r"communication on rank 0: ([0-9.]+) s")
LEAST = re.compile(r"communication of any rank: least ([0-9.]+) s, [0-9.]+%, most ([0-9.]+) s")
LOAD = re.compile(r"particles per rank: min (\d+), mean ([0-9.]+), max (\d+)")
GHOSTS = re.compile(r"ghosts per rank: mean (\d+)")


def environment(threads):
    env = dict(os.environ)
    env.update({"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
                "OMPI_MCA_btl_vader_single_copy_mechanism": "none", "OMP_NUM_THREADS": str(threads)})
    return env


def run(args, scene, ranks, threads, work):
    """One run: its timing table, with 'communication' (s, rank 0's) and 'load' added."""
    command = [args.binary, "run", "--log", "none", scaling.SCENARIO, "-v", f"init={scene}",
               "-v", f"out={os.path.join(work, 'frames')}", "--threads", str(threads)]
    if args.solver != "pbf":
        command += ["-v", f"solver={args.solver}"]
    if ranks > 1:
        command = [args.mpirun, "-q", "--bind-to", "none", "--oversubscribe", "-np", str(ranks)] + command
    done = subprocess.run(command, capture_output=True, text=True, env=environment(threads), cwd=work)
    what = f"{ranks} rank(s) x {threads} thread(s)"
    if done.returncode != 0:
        scaling.fail(f"{what} exited with status {done.returncode}: {scaling.last_line(done.stderr)}")
    table = scaling.parse_timing(done.stdout, what)
    found = COMMUNICATION.search(done.stdout)
    table["communication"] = float(found.group(1)) if found else 0.0
    spread = LEAST.search(done.stdout)
    table["least"], table["most"] = (float(spread.group(1)), float(spread.group(2))) if spread else (0.0, 0.0)
    ghosts = GHOSTS.search(done.stdout)
    table["ghosts"] = int(ghosts.group(1)) if ghosts else 0
    load = LOAD.search(done.stdout)
    table["load"] = tuple(float(v) for v in load.groups()) if load else None
    return table


def series(args, scene, configurations, work):
    """Each configuration's tables, the configurations taking turns, --repeats rounds."""
    tables = {c: [] for c in configurations}
    for r in range(args.repeats):
        for c in configurations:
            scaling.progress(f"round {r + 1}/{args.repeats}: {c[0]} rank(s) x {c[1]} thread(s)")
            tables[c].append(run(args, scene, c[0], c[1], work))
    return tables


def med_step(tables):
    return scaling.median([scaling.step_ms(t) for t in tables])


def comm_cells(tables, ranks):
    """Ghosts per rank and the least rank's communication (ms per step), medians: '-' for one rank."""
    if ranks == 1:
        return "- | -"
    least = scaling.median([1000 * t["least"] / t["steps"] for t in tables])
    ghosts = scaling.median([t["ghosts"] for t in tables])
    return f"{ghosts:,.0f} | {least:.3f}"


def strong(args, work):
    scene, n = scaling.make_scene(33750, 75, work)
    configs = [(1, 1), (1, 2), (2, 1)]
    tables = series(args, scene, configs, work)
    base = med_step(tables[(1, 1)])
    out = [f"Strong scaling, the {n:,}-particle dam break, 75 steps, median of {args.repeats}:", "",
           "| ranks x threads | ms per step | speed-up over 1 x 1 | ghosts per rank | communication, least rank "
           "(ms per step) | runs (ms per step) |", "|---|---|---|---|---|---|"]
    for c in configs:
        t = med_step(tables[c])
        runs = ", ".join(f"{scaling.step_ms(x):.1f}" for x in tables[c])
        out.append(f"| {c[0]} x {c[1]} | {t:.2f} | {base / t:.2f} | {comm_cells(tables[c], c[0])} | {runs} |")
    ratio = med_step(tables[(2, 1)]) / med_step(tables[(1, 2)])
    out += ["", f"2 ranks x 1 thread / 1 process x 2 threads: **{ratio:.3f}** (target: at most 1.15)."]
    return "\n".join(out), tables[(2, 1)]


def weak(args, work):
    one, n1 = scaling.make_scene(2197, 100, work)
    two, n2 = scaling.make_scene(2 * 2197, 100, work)
    rows = []
    for r in range(args.repeats):
        scaling.progress(f"weak, round {r + 1}/{args.repeats}")
        rows.append((run(args, one, 1, 1, work), run(args, two, 2, 1, work)))
    t1 = scaling.median([scaling.step_ms(a) for a, _ in rows])
    t2 = scaling.median([scaling.step_ms(b) for _, b in rows])
    per_rank = n2 / 2
    twos = [b for _, b in rows]
    out = [f"Weak scaling, about 2,197 particles per rank, 1 thread each, 100 steps, median of {args.repeats}:",
           "", "| ranks | particles | per rank | ms per step | efficiency t(1) / t(P) | same, per particle | ghosts per "
           "rank | communication, least rank (ms per step) |",
           "|---|---|---|---|---|---|---|---|",
           f"| 1 | {n1:,} | {n1:,} | {t1:.3f} | 1.00 | 1.00 | - | - |",
           f"| 2 | {n2:,} | {per_rank:,.0f} | {t2:.3f} | {t1 / t2:.2f} | {(t1 / n1) / (t2 / per_rank):.2f} | "
           f"{comm_cells(twos, 2)} |"]
    return "\n".join(out)


def profile(args, tables):
    """The phases at 2 ranks x 1 thread, per step, from the median run."""
    ordered = sorted(tables, key=scaling.step_ms)
    table = ordered[len(ordered) // 2]
    steps = table["steps"]
    ph = scaling.phases(table, "2 ranks")
    communication_rows = sum(scaling.seconds(r, table) for s in table["stages"] if s["name"] == "communication"
                             for r in s["rows"])
    out = [f"Profile at 2 ranks x 1 thread (rank 0's timing table, the median run of {len(tables)}), ms per step:",
           "", "| phase | ms per step | share |", "|---|---|---|"]
    wall = table["wall"]
    for name in scaling.PHASES:
        value = ph[name] - (communication_rows if name == "other" else 0)
        out.append(f"| {name} | {1000 * value / steps:.3f} | {100 * value / wall:.1f}% |")
    out.append(f"| migration and ghosts (communication rows) | {1000 * communication_rows / steps:.3f} | "
               f"{100 * communication_rows / wall:.1f}% |")
    comm = table["communication"]
    least = scaling.median([t["least"] / t["wall"] for t in tables])
    most = scaling.median([t["most"] / t["wall"] for t in tables])
    out += ["", f"Communication in all (migration, ghosts, and the ghosts' updates inside the passes), share of "
                f"the step: rank 0 in the median run {100 * comm / wall:.1f}% ({1000 * comm / steps:.3f} ms per "
                f"step); over the {len(tables)} runs, median of the least of the two ranks **{100 * least:.1f}%**, "
                f"of the most {100 * most:.1f}% (target: at most 10%). Beyond the least is waiting for the slower "
                f"rank."]
    if table["load"]:
        least, mean, most = table["load"]
        out.append(f"Particles per rank at the end: min {least:.0f}, mean {mean:.1f}, max {most:.0f}.")
    return "\n".join(out)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", default=os.path.join(scaling.REPO, "build", "pbfengine"))
    parser.add_argument("--mpirun", default="mpirun")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--out", nargs="?", const=os.path.join(scaling.REPO, "docs", "performance"))
    parser.add_argument("--solver", choices=["pbf", "wcsph", "dfsph"], default="pbf",
                        help="init_file.lua's solver; another measures the strong table and the profile "
                        "only, into mpi_SOLVER.md")
    args = parser.parse_args()
    args.binary = scaling.check_binary(args.binary)
    with tempfile.TemporaryDirectory() as work:
        strong_text, two_rank_tables = strong(args, work)
        weak_text = weak(args, work) if args.solver == "pbf" else ""
        parts = [strong_text, weak_text, profile(args, two_rank_tables)]
    header = scaling.header_line(args.binary) + ("" if args.solver == "pbf" else f"; init_file.lua -v solver={args.solver}")
    text = "\n\n".join(p for p in [header] + parts if p) + "\n"
    print(text)
    if args.out:
        os.makedirs(args.out, exist_ok=True)
        name = "mpi.md" if args.solver == "pbf" else f"mpi_{args.solver}.md"
        with open(os.path.join(args.out, name), "w") as f:
            f.write("# Distributed runs: the original study's MPI tables\n\n" + text)


if __name__ == "__main__":
    main()
