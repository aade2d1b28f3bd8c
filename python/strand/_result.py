"""Result: what every strand call returns (G-code text, report, moves as NumPy arrays, check,
previews) and the two small types that show themselves inline in a notebook."""

import html
import json
import os

import numpy as np

from . import _strand

# Move kinds and features as stored in .moves["kind"] and .moves["feature"].
KINDS = ("travel", "deposit", "dwell", "raw")
TRAVEL, DEPOSIT, DWELL, RAW = range(4)
FEATURES = ("infill", "wall", "ligament", "node", "grip", "frame", "link", "pen")


class Png(bytes):
    """PNG bytes that a notebook shows as the image."""

    def _repr_png_(self):
        return bytes(self)


class Html(str):
    """A self-contained HTML page that a notebook shows in a frame."""

    height_px = 520

    def _repr_html_(self):
        # srcdoc keeps the page's script apart from the notebook's (no shared globals).
        return (f'<iframe srcdoc="{html.escape(self, quote=True)}" style="width:100%;'
                f'height:{self.height_px}px;border:1px solid #ccc" sandbox="allow-scripts"></iframe>')


def _summary(report):
    derived = report.get("derived", {})
    totals = report.get("totals", {})
    machine = report.get("machine", {})
    row = {
        "generator": report.get("generator"),
        "machine": machine.get("name") if isinstance(machine, dict) else machine,
        "footprint_mm": derived.get("footprint_mm"),
        "height_mm": derived.get("height_mm"),
        "layers": totals.get("layers", derived.get("layers")),
        "porosity": derived.get("porosity"),
        "deposit_length_mm": totals.get("deposit_length_mm"),
        "travel_length_mm": totals.get("travel_length_mm"),
        "ink_volume_ml": totals.get("ink_volume_ml"),
        "time_s": totals.get("time_trapezoid_s"),
    }
    return {k: v for k, v in row.items() if v is not None}


def _lengths(moves, start):
    """Length of every move in mm (arcs along the arc, helical z included)."""
    end = np.stack([moves["x"], moves["y"], moves["z"]], axis=1)
    prev = np.vstack([np.asarray(start, dtype=float).reshape(1, 3), end[:-1]]) if len(end) else end
    # Raw and dwell rows repeat no position: they keep the previous one.
    moving = (moves["kind"] == TRAVEL) | (moves["kind"] == DEPOSIT)
    length = np.where(moving, np.linalg.norm(end - prev, axis=1), 0.0)
    arcs = np.flatnonzero(moving & moves["arc"])
    if arcs.size:
        c = np.stack([moves["cx"][arcs], moves["cy"][arcs]], axis=1)
        a0 = np.arctan2(prev[arcs, 1] - c[:, 1], prev[arcs, 0] - c[:, 0])
        a1 = np.arctan2(end[arcs, 1] - c[:, 1], end[arcs, 0] - c[:, 0])
        sweep = np.where(moves["ccw"][arcs], a1 - a0, a0 - a1) % (2 * np.pi)
        sweep = np.where(sweep == 0, 2 * np.pi, sweep)  # same start and end: a full circle
        radius = np.linalg.norm(prev[arcs, :2] - c, axis=1)
        dz = end[arcs, 2] - prev[arcs, 2]
        length[arcs] = np.hypot(radius * sweep, dz)
    return length


class Result:
    """A toolpath made by strand: its G-code, report and moves.

    .gcode      the file's text, byte for byte what the CLI writes
    .summary    footprint, layers, porosity, ink, time ... (dict)
    .report     the JSON report of `--report` (dict)
    .moves      every move: NumPy structured array over the program itself (read-only)
    .layers()   the moves of each layer
    .check()    `strand check --json` of the file (dict)
    .preview()  the CLI's previews: kind="png" (image) or "html" (interactive 3D page)
    .write(p)   the file written atomically (all or nothing), as the CLI writes it
    """

    def __init__(self, raw):
        self._raw = raw
        self._report = None
        self._moves = None

    # --- text and figures -------------------------------------------------------------
    @property
    def name(self):
        """The file name the CLI would write by default ("scaffold.gcode")."""
        return self._raw.name

    @property
    def gcode(self):
        return self._raw.gcode

    @property
    def files(self):
        """{name: text} of every file the job writes (robot cells write several)."""
        return dict(self._raw.files)

    @property
    def report(self):
        if self._report is None:
            self._report = json.loads(self._raw.report_json)
        return self._report

    @property
    def summary(self):
        return _summary(self.report)

    @property
    def text(self):
        """The summary as the CLI prints it."""
        return self._raw.summary_text

    # --- arrays -----------------------------------------------------------------------
    @property
    def moves(self):
        """Fields x, y, z (end, mm), feed (mm/min), volume (mm3 deposited), width (mm),
        cx, cy (arc centre), layer, tool, kind (strand.TRAVEL, DEPOSIT, DWELL, RAW),
        feature (index into strand.FEATURES), arc, ccw, coast. No copy: the array views the
        program, which it keeps alive."""
        if self._moves is None:
            self._moves = self._raw.moves()
        return self._moves

    @property
    def e(self):
        """E per move as the file counts it (relative); 0 where the machine takes no E."""
        return self._raw.e()

    @property
    def travel(self):
        """True for travel moves (no deposit)."""
        return self.moves["kind"] == TRAVEL

    def lengths(self):
        """Length of every move, mm (arcs measured along the arc)."""
        return _lengths(self.moves, self._raw.start())

    def deposited_length(self):
        """Sum of the deposit moves' lengths, mm (the report's deposit_length_mm)."""
        m = self.moves
        return float(self.lengths()[m["kind"] == DEPOSIT].sum())

    def layers(self):
        """One array per layer (layer index 0, 1, ...), views where the layers are contiguous."""
        m = self.moves
        n = len(self._raw.layer_z())
        layer = m["layer"]
        if len(layer) and np.all(np.diff(layer) >= 0):
            bounds = np.searchsorted(layer, np.arange(n + 1))
            return [m[bounds[i]:bounds[i + 1]] for i in range(n)]
        return [m[layer == i] for i in range(n)]

    @property
    def layer_z(self):
        return self._raw.layer_z()

    # --- checks, previews, files --------------------------------------------------------
    def check(self):
        """`strand check FILE --machine MACHINE --json` on this file (dict; "ok" says pass)."""
        c = json.loads(self._raw.check_json())
        return c

    def preview(self, kind="png", *, width=1200, height=700, view="both", layer=-1,
                travel=False, colour="feature"):
        """kind="png": the image `strand preview -o x.png` draws (bytes; shown inline);
        kind="html": the interactive page `strand preview -o x.html` writes (str)."""
        if self.name.endswith(".csv"):
            raise ValueError(f"preview: {self.name} is a robot cell's pose CSV; write the files "
                             f"(.write(folder)) and draw it with strand preview {self.name}")
        if kind == "html":
            return Html(self._raw.preview_html(self.name))
        if kind == "png":
            if colour not in ("feature", "layer"):
                raise ValueError(f"colour = {colour}: must be feature or layer")
            return Png(self._raw.preview_png(int(width), int(height), view, int(layer),
                                             bool(travel), colour == "layer"))
        raise ValueError(f"kind = {kind}: must be png or html")

    def _repr_html_(self):
        rows = "".join(f"<tr><td>{html.escape(str(k))}</td><td>{html.escape(str(v))}</td></tr>"
                       for k, v in self.summary.items())
        # the light canvas page (a job's preview.html), not the 0.6 MB 3D viewer, in every frame
        return (f"<b>{html.escape(self.name)}</b><table>{rows}</table>"
                + Html(self._raw.preview_page_html(self.name))._repr_html_())

    def __repr__(self):
        s = self.summary
        return f"<strand.Result {self.name}: {s.get('layers', '?')} layers, {len(self.gcode)} bytes>"

    def write(self, path=None, *, report=None):
        """Writes the G-code to `path` (default: self.name) and, if given, the report, as one
        transaction: all files or none. A robot cell's several files go into the folder
        `path` under their own names (their texts name each other)."""
        files = self._raw.files
        if len(files) > 1:
            folder = os.fspath(path or ".")
            out = [(os.path.join(folder, n), t) for n, t in files]
        else:
            out = [(os.fspath(path or self.name), self.gcode)]
        if report is not None:
            out.append((os.fspath(report), self._raw.report_json + "\n"))
        _strand.write_files(out, [])
        return out[0][0]
