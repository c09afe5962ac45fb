#!/usr/bin/env python3
"""Memory of a run that emits and removes for a long time: scenarios/fountain.lua (a jet into a
basin with a drain, at a level particle count) for 60 simulated seconds, its resident size
(VmRSS of /proc/PID/status) sampled every half second of wall time against the simulated
time the thermo lines report. A run whose buffers keep their capacity from step to step
(and ids that are never reused, so no table sized by them) stays flat after the first
seconds; a leak grows with the particles that have passed.

    /usr/bin/python3 share/benchmarks/memory_flow.py --binary build/pbfengine \\
        --out docs/performance/memory_flow.md       # about 3 minutes on 2 cores

It prints a Markdown table (RSS at a few times, the growth after the first 5 s) and, with
--out, writes it there with the date and the machine, and the plot beside it (FILE with .png;
matplotlib needed).
"""
import argparse
import datetime
import os
import platform
import re
import subprocess
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")


def rss_kib(pid):
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1])
    except OSError:
        return None
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", default=os.path.join(ROOT, "build", "pbfengine"))
    parser.add_argument("--t_end", type=float, default=60.0)
    parser.add_argument("--out", help="write the table into this Markdown file, and its plot beside it")
    args = parser.parse_args()

    command = [args.binary, "run", os.path.join(ROOT, "scenarios", "fountain.lua"), "-v", f"t_end={args.t_end}",
               "-v", "out=", "--log", "none"]
    proc = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    latest = {"time": 0.0, "n": 0, "in": 0, "out": 0}
    row = re.compile(r"^\s*(\d+)\s+([0-9.e+-]+)\s+(\d+)\s+(\d+)\s+(\d+)\s")

    def read():
        for line in proc.stdout:
            m = row.match(line)
            if m:
                latest.update(time=float(m.group(2)), n=int(m.group(3)), **{"in": int(m.group(4)), "out": int(m.group(5))})

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    samples = []  # (simulated time, RSS MiB, count, emitted)
    started = time.time()
    while proc.poll() is None:
        kib = rss_kib(proc.pid)
        if kib is not None:
            samples.append((latest["time"], kib / 1024, latest["n"], latest["in"]))
        time.sleep(0.5)
    reader.join(timeout=5)
    wall = time.time() - started
    if proc.returncode != 0 or not samples:
        raise SystemExit(f"the run failed (exit {proc.returncode})")

    def at(t):
        return min(samples, key=lambda s: abs(s[0] - t))

    after = [s for s in samples if s[0] >= 5.0]
    entered, grown = samples[-1][3] - at(5)[3], samples[-1][2] - at(5)[2]
    low, high = min(s[1] for s in after), max(s[1] for s in after)
    times = [t for t in (1, 5, 10, 20, 30, 40, 50, 60) if t <= args.t_end]
    lines = ["| simulated time (s) | RSS (MiB) | particles | emitted so far |", "|---|---|---|---|"]
    for t in times:
        s = at(t)
        lines.append(f"| {s[0]:.1f} | {s[1]:.1f} | {s[2]} | {s[3]} |")
    summary = (f"After 5 s the resident size stays within {low:.1f} to {high:.1f} MiB ({high - low:.1f} MiB, "
               f"{100 * (high - low) / low:.1f}%) while {entered} more particles enter and {entered - grown} "
               f"leave; the run took {wall:.0f} s of wall time.")
    table = "\n".join(lines)
    print(table)
    print()
    print(summary)
    if args.out:
        png = os.path.splitext(args.out)[0] + ".png"
        head = (f"# Memory of a run that emits and removes\n\n"
                f"`share/benchmarks/memory_flow.py`, {datetime.date.today()}, {platform.node()} "
                f"({os.cpu_count()} cores), `scenarios/fountain.lua` for {args.t_end:g} simulated seconds "
                f"(PBF, spacing 1 cm, about 9,000 particles, no output files): the process's resident size "
                f"(VmRSS) every half second against the simulated time.\n\n")
        with open(args.out, "w") as f:
            f.write(head + table + "\n\n" + summary + f"\n\n![resident size against simulated time]({os.path.basename(png)})\n")
        try:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError:
            print("no matplotlib: no plot (on Debian: apt install python3-matplotlib, run with /usr/bin/python3)")
            return
        fig, ax = plt.subplots(figsize=(7, 3.6))
        ax.plot([s[0] for s in samples], [s[1] for s in samples], lw=1.5, label="resident size")
        ax.set_xlabel("simulated time (s)")
        ax.set_ylabel("RSS (MiB)")
        ax.set_ylim(0, 1.2 * max(s[1] for s in samples))
        twin = ax.twinx()
        twin.plot([s[0] for s in samples], [s[3] for s in samples], "C1--", lw=1, label="particles emitted so far")
        twin.set_ylabel("particles emitted so far")
        ax.set_title("fountain.lua: a jet into a drain")
        fig.legend(loc="lower right")
        fig.tight_layout()
        fig.savefig(png, dpi=110)


if __name__ == "__main__":
    main()
