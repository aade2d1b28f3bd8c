#!/usr/bin/env python3
"""`make bench`: runs the `strand` program on the benchmark inputs of issue 13 and prints one
table (cpu time, peak memory per move or stroke, pen-up travel, check and sweep times) with
each target, so the next change compares in one run.
Usage: bench_table.py STRAND [--shared DIR] [--quick] [--repeat N]
DIR holds random_lines_svg.py and sweep-1000.json (default: ../shared/bench beside the
repository). --quick skips the 3.3M-move and 300k-stroke rows. Each figure is the child
process's own user + system cpu time and peak resident memory (wait4); the check and plot
rows run N times (default 3) and keep the least cpu, as other work on the machine only adds
to it. The load average before and after is printed under the table."""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))


REPEAT = 1  # runs per check and plot row (--repeat)


def run_min(cmd, cwd):
    """run() REPEAT times: (least cpu seconds, largest peak RSS bytes)."""
    runs = [run(cmd, cwd) for _ in range(max(1, REPEAT))]
    return min(r[0] for r in runs), max(r[1] for r in runs)


def run(cmd, cwd):
    """Runs cmd; returns (cpu seconds, peak RSS bytes). Output is discarded; failure stops."""
    with open(os.devnull, "w") as null:
        p = subprocess.Popen(cmd, cwd=cwd, stdout=null, stderr=subprocess.PIPE)
        _, status, ru = os.wait4(p.pid, 0)
        err = p.stderr.read().decode(errors="replace")
        p.stderr.close()
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"bench: {' '.join(cmd)} failed:\n{err}")
    return ru.ru_utime + ru.ru_stime, ru.ru_maxrss * 1024


def count_moves(path):
    """G0-G3 lines of a G-code file: the moves a machine executes."""
    n = 0
    with open(path, "rb") as f:
        for line in f:
            if line[:2] in (b"G0", b"G1", b"G2", b"G3") and line[2:3] in (b" ", b"\n"):
                n += 1
    return n


def profile(name, src, changes, work):
    """A shipped profile with a larger build volume, written to the work directory."""
    with open(os.path.join(REPO, "machines", "profiles", src + ".json")) as f:
        p = json.load(f)
    p["name"] = name
    p["kinematics"]["max_mm"] = changes
    path = os.path.join(work, name + ".json")
    with open(path, "w") as f:
        json.dump(p, f)
    return path


class Table:
    def __init__(self):
        self.rows = []

    def add(self, what, figure, value, unit, target=None, ok=None):
        self.rows.append((what, figure, value, unit, target or "", "" if ok is None else ("ok" if ok else "MISSED")))

    def print(self):
        head = ("benchmark", "figure", "value", "unit", "target", "")
        widths = [max(len(str(r[i])) for r in self.rows + [head]) for i in range(6)]
        line = lambda r: "  ".join(str(c).ljust(w) if i != 2 else str(c).rjust(w) for i, (c, w) in enumerate(zip(r, widths)))
        print(line(head).rstrip())
        print("  ".join("-" * w for w in widths))
        for r in self.rows:
            print(line(r).rstrip())


def scaffold(t, strand, work, label, machine, extra, memory_target, speed_target=True, out=None):
    """One scaffold job's rows; keeps the G-code when `out` is given (else removes it)."""
    keep = out is not None
    out = out or os.path.join(work, "scaffold.gcode")
    cpu, rss = run_min([strand, "scaffold", "--machine", machine, "--nozzle", "0.25", "--gap", "0.25",
                        "--size", "180x180", "-o", out] + extra, work)
    moves = count_moves(out)
    t.add(label, "moves", moves, "")
    if speed_target:
        t.add(label, "throughput", round(moves / cpu / 1e6, 2), "M moves/s cpu", ">= 3", moves / cpu >= 3e6)
    else:  # small jobs: the process's fixed start-up (profiles, tables) weighs in
        t.add(label, "throughput", round(moves / cpu / 1e6, 2), "M moves/s cpu")
    if memory_target:  # small jobs: the process's fixed ~20 MiB dominates, no per-move target
        t.add(label, "peak memory", round(rss / moves, 1), "bytes/move", "<= 100", rss / moves <= 100)
    else:
        t.add(label, "peak memory", round(rss / moves, 1), "bytes/move")
    t.add(label, "peak memory", round(rss / 2**20), "MiB")
    if not keep:
        os.remove(out)
    return rss


def check(t, strand, work, label, gcode, target_s, memory_target_mib=None):
    """`strand check` cpu and peak memory; it reads a layer at a time (issue 30: at most
    64 MiB at 3.3M moves, where it held the whole file: 581 MiB)."""
    cpu, rss = run_min([strand, "check", gcode], work)
    t.add(label, "check cpu", round(cpu, 2), "s", "<= %g" % target_s, cpu <= target_s)
    mib = rss / 2**20
    if memory_target_mib is None:
        t.add(label, "check peak memory", round(mib), "MiB")
    else:
        t.add(label, "check peak memory", round(mib), "MiB", "<= %d" % memory_target_mib, mib <= memory_target_mib)


def plot(t, strand, work, shared, n, machine, targets):
    svg = os.path.join(work, f"lines{n}.svg")
    subprocess.run([sys.executable, os.path.join(shared, "random_lines_svg.py"), str(n), svg, "--seed", "11"], check=True)
    report = os.path.join(work, "plot.json")
    cpu, rss = run_min([strand, "plot", svg, "--machine", machine, "-o", os.path.join(work, "plot.gcode"), "--report", report], work)
    with open(report) as f:
        pen_up = json.load(f)["pen_up_after_ordering"]
    pen_up_mm = pen_up["pen_up_mm"]
    label = f"plot {n // 1000}k lines"
    t.add(label, "cpu per stroke", round(cpu / n * 1e6, 2), "us", "<= 10", cpu / n <= 10e-6)
    if n >= 300000:  # the target is set at 300k strokes; below, the fixed ~20 MiB dominates
        t.add(label, "peak memory", round(rss / n), "bytes/stroke", "<= 1024", rss / n <= 1024)
    else:
        t.add(label, "peak memory", round(rss / n), "bytes/stroke")
    if n in targets:
        t.add(label, "pen-up travel", round(pen_up_mm), "mm", "<= %d" % targets[n], round(pen_up_mm) <= targets[n])
    else:
        t.add(label, "pen-up travel", round(pen_up_mm), "mm")


def sweep(t, strand, work, shared):
    spec = os.path.join(shared, "sweep-1000.json")
    for previews in (False, True):
        out = os.path.join(work, "sweep-previews" if previews else "sweep")
        cpu, _ = run([strand, "sweep", spec, "-o", out, "-j", "1"] + ([] if previews else ["--no-previews"]), work)
        with open(os.path.join(out, "manifest.json")) as f:
            n = len(json.load(f)["points"])
        label = "sweep 1000 " + ("with previews" if previews else "no previews")
        t.add(label, "cpu per specimen", round(cpu / n * 1e3, 2), "ms", None if previews else "<= 1", None if previews else cpu / n <= 1e-3)


def two_inks(t, strand, work):
    """Issue 33: printheads by feature cost little over one head. A tetrachiral lattice of
    40 x 40 cells (one strand per layer, cut at every node ring) on the two-head profile with a
    1 m bed: assign_tools copied the whole strand at each cut (171 s against 0.5 s)."""
    with open(os.path.join(REPO, "machines", "profiles", "two-head-pneumatic.json")) as f:
        p = json.load(f)
    p["name"] = "bench-two-heads"
    p["kinematics"].update({"max_mm": [1000, 1000, 100], "part_center_mm": [500, 500]})
    machine = os.path.join(work, "bench-two-heads.json")
    with open(machine, "w") as f:
        json.dump(p, f)
    job = [strand, "tetrachiral", "--nozzle", "0.5", "--cell", "10", "--cols", "40", "--rows", "40", "--layers", "4",
           "--machine", machine, "-o", os.path.join(work, "two-inks.gcode")]
    one, _ = run_min(job, work)
    two, _ = run_min(job + ["--tools", "node=1,ligament=0"], work)
    label = "tetrachiral 40x40 cells, 4 layers"
    t.add(label, "cpu one head", round(one, 2), "s")
    t.add(label, "cpu heads by feature", round(two, 2), "s", "<= 3x one head", two <= 3 * one)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("strand")
    ap.add_argument("--shared", default=os.path.join(os.path.dirname(REPO), "shared", "bench"))
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    global REPEAT
    REPEAT = a.repeat
    load_before = os.getloadavg()
    strand = os.path.abspath(a.strand)
    if not os.path.isfile(os.path.join(a.shared, "random_lines_svg.py")):
        sys.exit(f"bench: no benchmark inputs in {a.shared} (give --shared DIR)")
    t = Table()
    with tempfile.TemporaryDirectory(prefix="strand-bench-") as work:
        tall = profile("bench-tall", "marlin-xyz-200", [200, 200, 1200], work)
        wide = profile("bench-xy-500", "xy-plotter-servo", [500, 500, 10], work)
        small_rss = scaffold(t, strand, work, "scaffold 132k moves", "marlin-xyz-200", ["--height", "40"], False,
                             speed_target=False)
        if not a.quick:
            big = os.path.join(work, "scaffold-3.3M.gcode")
            big_rss = scaffold(t, strand, work, "scaffold 3.3M moves", tall, ["--layers", "4550"], True, out=big)
            # Issue 23: memory independent of job size (the layer-by-layer pipeline).
            t.add("scaffold 3.3M vs 132k", "peak memory ratio", round(big_rss / small_rss, 2), "x", "<= 1.5",
                  big_rss <= 1.5 * small_rss)
            check(t, strand, work, "check 3.3M moves, 4550 layers", big, 1.5, memory_target_mib=64)
            os.remove(big)
        long_rows = os.path.join(work, "long-rows.gcode")
        subprocess.run([sys.executable, os.path.join(HERE, "serpentine_gcode.py"), long_rows], check=True)
        check(t, strand, work, "check 4 x 250k-segment layers", long_rows, 0.5)
        os.remove(long_rows)
        small = os.path.join(work, "small-layers.gcode")
        scaffold(t, strand, work, "scaffold 1M moves", tall, ["--layers", "1364"], False, out=small)
        check(t, strand, work, "check 1M moves, 1364 layers", small, 0.5, memory_target_mib=64)
        os.remove(small)
        for n in ([10000, 100000] if a.quick else [10000, 100000, 300000]):
            plot(t, strand, work, a.shared, n, wide, {10000: 20900, 100000: 65316})
        sweep(t, strand, work, a.shared)
        two_inks(t, strand, work)
        # Issue 30.6: strand slice beside PrusaSlicer on public meshes (its own table, then rows).
        import slice_vs_prusaslicer
        slice_vs_prusaslicer.bench_rows(t, strand, work)
    t.print()
    load_after = os.getloadavg()
    print(f"load average (1/5/15 min) on {os.cpu_count()} cpus: before {' '.join('%.2f' % x for x in load_before)}, "
          f"after {' '.join('%.2f' % x for x in load_after)}; scaffold, check and plot rows: least cpu of {REPEAT} runs")


if __name__ == "__main__":
    main()
