#!/usr/bin/env python3
"""Side by side: `strand slice` and PrusaSlicer's CLI on the public mesh corpus
(tests/data/meshes-public/README.md), each part scaled to fit 30 x 30 x 30 mm, nozzle 0.6 mm,
one perimeter, Strand's scaffold (gap 1 mm) against PrusaSlicer's rectilinear infill at the
same line spacing and layer height. Per mesh and tool: wall and CPU time (user + system, all
threads; the least of 3 runs), layers with material, those with no deposit, strands per layer
(max, mean) and the share of the deposit inside the part's section; both files are measured by
strand_slice_compare (Strand's G-code reader and mesh slicer, the same rules for both).
PrusaSlicer is not a build dependency (apt-get install prusa-slicer); without it its columns
are left out with a note.
Usage: slice_vs_prusaslicer.py STRAND [--compare BIN] [--work DIR] [--only NAME ...] [--repeat N]
                               [--threads N]
STRAND is the strand program (build/cli/strand); BIN defaults to the build's
tests/bench/strand_slice_compare beside it; --threads N is passed to strand slice (default:
every core, as PrusaSlicer)."""
import argparse
import glob
import gzip
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
BOX = "30x30x30"
NOZZLE_MM = 0.6
GAP_MM = 1.0
PRUSA_CENTER = (100.0, 100.0)  # PrusaSlicer centres the part's bounding box here
REPEAT = 3  # runs per tool and mesh; the least wall and the least CPU time are kept
THREADS = None  # strand slice --threads (None: every core)


def corpus():
    """(name, path) of every bench mesh: the corpus directory plus two meshes kept elsewhere."""
    paths = sorted(glob.glob(os.path.join(REPO, "tests", "data", "meshes-public", "*.*")))
    paths = [p for p in paths if not p.endswith(".md")]
    paths += [os.path.join(REPO, "tests", "data", "cheese.off"), os.path.join(REPO, "samples", "meshes", "spot.obj")]
    out = []
    for p in paths:
        name = os.path.basename(p)
        name = name[:-3] if name.endswith(".gz") else name
        out.append((name.rsplit(".", 1)[0], p))
    return sorted(out)


def unpacked(path, work):
    """The mesh file itself: a .gz is expanded into the work directory."""
    if not path.endswith(".gz"):
        return path
    out = os.path.join(work, os.path.basename(path)[:-3])
    with gzip.open(path, "rb") as src, open(out, "wb") as dst:
        shutil.copyfileobj(src, dst)
    return out


def timed(cmd, cwd, may_fail=False):
    """Runs cmd REPEAT times: (least wall s, least cpu s of the child and its threads); other
    work on the machine only adds to either. Failure stops the bench, or with may_fail returns
    the error's last lines (a string) instead."""
    runs = []
    for _ in range(max(1, REPEAT)):
        r = timed_once(cmd, cwd, may_fail)
        if isinstance(r, str):
            return r
        runs.append(r)
    return min(r[0] for r in runs), min(r[1] for r in runs)


def timed_once(cmd, cwd, may_fail):
    start = time.monotonic()
    with open(os.devnull, "w") as null:
        p = subprocess.Popen(cmd, cwd=cwd, stdout=null, stderr=subprocess.PIPE)
        err = p.stderr.read().decode(errors="replace")
        _, status, ru = os.wait4(p.pid, 0)
    wall = time.monotonic() - start
    if os.waitstatus_to_exitcode(status) != 0:
        if may_fail:
            lines = [x for x in err.strip().splitlines() if x.strip()]
            return " ".join(lines[-2:]) or "exit status %d" % os.waitstatus_to_exitcode(status)
        sys.exit(f"bench: {' '.join(cmd)} failed:\n{err[-2000:]}")
    return wall, ru.ru_utime + ru.ru_stime


def derived(gcode):
    """Strand's `; derived key = value` header lines."""
    out = {}
    with open(gcode) as f:
        for line in f:
            if line.startswith("; derived "):
                key, _, value = line[len("; derived "):].partition(" = ")
                out[key] = value.strip()
            elif line.startswith("G") or line.startswith(";LAYER"):
                break
    return out


def prusa_density_pct(layer_mm, pitch_mm):
    """PrusaSlicer's rectilinear line distance is the flow spacing / density, the spacing of a
    0.6 mm wide bead of the layer's height being width - height (1 - pi/4) (Flow::spacing)."""
    spacing = NOZZLE_MM - layer_mm * (1.0 - math.pi / 4.0)
    return 100.0 * spacing / pitch_mm


def prusa_command(stl, out, layer_mm, pitch_mm):
    w = "%g" % NOZZLE_MM
    return ["prusa-slicer", "--export-gcode", stl, "--output", out, "--nozzle-diameter", w,
            "--layer-height", "%.4f" % layer_mm, "--first-layer-height", "%.4f" % layer_mm,
            "--extrusion-width", w, "--first-layer-extrusion-width", w, "--perimeter-extrusion-width", w,
            "--external-perimeter-extrusion-width", w, "--infill-extrusion-width", w,
            "--perimeters", "1", "--fill-pattern", "rectilinear", "--fill-angle", "0",
            "--fill-density", "%.2f%%" % prusa_density_pct(layer_mm, pitch_mm),
            "--top-solid-layers", "0", "--bottom-solid-layers", "0", "--solid-infill-below-area", "0",
            "--skirts", "0", "--brim-width", "0", "--center", "%g,%g" % PRUSA_CENTER, "--loglevel", "1"]


def measure(compare, stl, gcode, layer_mm, center):
    r = subprocess.run([compare, "measure", stl, gcode, "%.6f" % layer_mm, "%g" % NOZZLE_MM,
                        "%g,%g" % center], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"bench: strand_slice_compare measure {gcode} failed:\n{r.stderr}")
    return json.loads(r.stdout)


def compare_mesh(strand, compare, name, path, work, prusa):
    """One mesh: both tools' figures, or Strand's alone when PrusaSlicer is absent."""
    mesh = unpacked(path, work)
    s_gcode = os.path.join(work, name + ".strand.gcode")
    row = {"mesh": name}
    row["strand_wall_s"], row["strand_cpu_s"] = timed(
        [strand, "slice", mesh, "--scale-to-fit", BOX, "--pattern", "scaffold", "--nozzle", "%g" % NOZZLE_MM,
         "--gap", "%g" % GAP_MM, "--perimeters", "1", "--quiet", "-o", s_gcode]
        + (["--threads", str(THREADS)] if THREADS else []), work)
    d = derived(s_gcode)
    layer_mm, pitch_mm = float(d["layer_height_mm"]), float(d["pitch_mm"])
    row["layer_mm"], row["pitch_mm"] = layer_mm, pitch_mm
    stl = os.path.join(work, name + ".placed.stl")
    placed = json.loads(subprocess.run([compare, "place", mesh, BOX, stl], capture_output=True, text=True,
                                       check=True).stdout)
    strand_size = [float(x) for x in d["size_mm"].split(",")]
    if max(abs(a - b) for a, b in zip(placed["size_mm"], strand_size)) > 1e-3:
        sys.exit(f"bench: {name}: placed {placed['size_mm']} mm, strand slice placed {strand_size} mm")
    # The default machine (deltawasp-2040-clay) centres parts at x = y = 0.
    row["strand"] = measure(compare, stl, s_gcode, layer_mm, (0.0, 0.0))
    os.remove(s_gcode)
    if prusa:
        p_gcode = os.path.join(work, name + ".prusa.gcode")
        t = timed(prusa_command(stl, p_gcode, layer_mm, pitch_mm), work, may_fail=True)
        if isinstance(t, str):  # e.g. a part with nothing to print on its first layer
            row["prusa_error"] = t
        else:
            row["prusa_wall_s"], row["prusa_cpu_s"] = t
            row["prusa"] = measure(compare, stl, p_gcode, layer_mm, PRUSA_CENTER)
            os.remove(p_gcode)
    os.remove(stl)
    if mesh != path:
        os.remove(mesh)
    return row


def at_or_below(row):
    """Strand's strands per layer at or below PrusaSlicer's, both the worst layer and the mean."""
    s, p = row["strand"], row["prusa"]
    return s["strands_max"] <= p["strands_max"] and s["strands_mean"] <= p["strands_mean"] + 1e-9


def run_all(strand, compare, work, only=None):
    prusa = shutil.which("prusa-slicer") is not None
    rows = [compare_mesh(strand, compare, n, p, work, prusa) for n, p in corpus() if not only or n in only]
    return rows, prusa


def table_cells(r):
    """One mesh's row: Strand/PrusaSlicer pairs, "-" where PrusaSlicer gave no file."""
    s, p = r["strand"], r.get("prusa")
    pair = lambda key, fmt, src="": (fmt % (r if src else s)[src + key]) + "/" + (
        (fmt % (r if src else p)[src + key]) if p else "-")
    return [r["mesh"], str(s["layers"]), str(s["material_layers"]), pair("empty_material_layers", "%d"),
            pair("strands_max", "%d"), pair("strands_mean", "%.2f"), pair("inside_pct", "%.1f"),
            (("%.2f" % r["strand_wall_s"]) + "/" + ("%.2f" % r["prusa_wall_s"] if p else "-")),
            (("%.2f" % r["strand_cpu_s"]) + "/" + ("%.2f" % r["prusa_cpu_s"] if p else "-")),
            "%.2f" % (r["strand_wall_s"] / r["prusa_wall_s"]) if p else "-",
            ("yes" if at_or_below(r) else "NO") if p else "-"]


def print_table(rows, prusa):
    head = ["mesh", "layers", "material", "empty S/P", "strands max S/P", "mean S/P", "inside % S/P",
            "wall s S/P", "cpu s S/P", "wall ratio", "S <= P strands"]
    lines = [table_cells(r) for r in rows]
    widths = [max(len(x[i]) for x in lines + [head]) for i in range(len(head))]
    fmt = lambda cells: "  ".join(c.rjust(w) if i else c.ljust(w) for i, (c, w) in enumerate(zip(cells, widths)))
    print(fmt(head))
    print("  ".join("-" * w for w in widths))
    for line in lines:
        print(fmt(line))
    both = [r for r in rows if "prusa" in r]
    if both:
        ratios = [r["strand_wall_s"] / r["prusa_wall_s"] for r in both]
        print(f"wall-time ratio Strand/PrusaSlicer: {min(ratios):.2f} to {max(ratios):.2f} (target <= 0.33); "
              f"strands at or below PrusaSlicer's on {sum(at_or_below(r) for r in both)} of {len(both)} meshes")
    if not prusa:
        print("prusa-slicer not installed (apt-get install prusa-slicer): PrusaSlicer's columns left out")
    for r in rows:
        if prusa and "prusa" not in r:
            print(f"{r['mesh']}: PrusaSlicer wrote no file: {r['prusa_error']}")
        for tool in ("strand", "prusa"):
            if tool in r and r[tool]["empty_material_layers"]:
                print(f"{r['mesh']}: {tool} deposits nothing on layers {r[tool]['empty_layer_indices']}"
                      " where the part has material")


def bench_rows(table, strand, work):
    """`make bench` (bench_table.py): prints the side-by-side table as a section of its own and
    adds the summary rows to the bench table, with issue 30's targets."""
    compare = default_compare(strand)
    if not os.path.isfile(compare):
        print(f"side by side with PrusaSlicer: {compare} not built, left out")
        return
    rows, prusa = run_all(strand, compare, work)
    print(f"side by side with PrusaSlicer ({len(rows)} public meshes, 30 mm, nozzle 0.6 mm, one perimeter; "
          "S = strand slice, P = PrusaSlicer):")
    print_table(rows, prusa)
    print()
    label = f"slice vs PrusaSlicer, {len(rows)} meshes"
    empty = sum(r["strand"]["empty_material_layers"] for r in rows)
    table.add(label, "material, no deposit", empty, "layers", "0", empty == 0)
    both = [r for r in rows if "prusa" in r]
    if both:
        worst = max(r["strand_wall_s"] / r["prusa_wall_s"] for r in both)
        table.add(label, "wall time / P's, worst", round(worst, 2), "x", "<= 0.33", worst <= 1 / 3)
        below = sum(at_or_below(r) for r in both)
        table.add(label, "strands <= P's", f"{below}/{len(both)}", "meshes", "all", below == len(both))


def default_compare(strand):
    build = os.path.dirname(os.path.dirname(os.path.abspath(strand)))
    return os.path.join(build, "tests", "bench", "strand_slice_compare")


def main():
    global REPEAT, THREADS
    ap = argparse.ArgumentParser()
    ap.add_argument("strand")
    ap.add_argument("--compare")
    ap.add_argument("--work")
    ap.add_argument("--only", nargs="*")
    ap.add_argument("--json", help="also write the figures to this file")
    ap.add_argument("--repeat", type=int, default=REPEAT, help="runs per tool and mesh (least time kept)")
    ap.add_argument("--threads", type=int, help="strand slice --threads (default: every core)")
    a = ap.parse_args()
    REPEAT, THREADS = a.repeat, a.threads
    strand = os.path.abspath(a.strand)
    compare = os.path.abspath(a.compare or default_compare(strand))
    with tempfile.TemporaryDirectory(prefix="strand-vs-prusa-") as tmp:
        work = a.work or tmp
        os.makedirs(work, exist_ok=True)
        rows, prusa = run_all(strand, compare, work, a.only)
    print_table(rows, prusa)
    if a.json:
        with open(a.json, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
