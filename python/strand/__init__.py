"""Strand from Python: toolpaths for Direct Ink Writing and pen plotting.

    import strand
    r = strand.scaffold(nozzle=0.84, gap=1.6, size=(36, 36), height=13)
    r.summary            # footprint, layers, porosity, ink, time
    r.moves              # NumPy structured array of every move
    r                    # in a notebook: the summary and the interactive 3D preview

One function per generator (strand.generators() lists them with their parameter tables),
strand.job(), strand.sweep(), strand.plot(), strand.read_gcode(). Keyword names are the CLI's
long flags with "_" for "-"; values are numbers in the table's unit or text with a unit
("840um"), read exactly as the CLI reads them: a bad value raises ValueError with the CLI's
one-line message, a wrong type TypeError. Long calls release the GIL, report progress to
`progress(phase, done, steps)` and stop on Ctrl-C (KeyboardInterrupt), writing nothing.
See docs/python.md.
"""

import copy
import csv
import io
import json
import math
import os
import tempfile
from inspect import Parameter, Signature

from . import _strand
from ._convert import doc_for, param_texts, path_text, py_name
from ._result import DEPOSIT, DWELL, FEATURES, KINDS, RAW, TRAVEL, Html, Png, Result

__all__ = ["generators", "machines", "job", "sweep", "plot", "slice", "read_gcode", "Result",
           "TRAVEL", "DEPOSIT", "DWELL", "RAW", "KINDS", "FEATURES"]

_TABLES = json.loads(_strand.tables_json())


def generators():
    """Every generator: name, summary and its parameter table (key, type, unit, help, min,
    max, default, choices, rule) - the table the CLI builds its flags from."""
    return copy.deepcopy(_TABLES["generators"])


def machines():
    """Every machine profile --machine can name (shipped and your own): name, description,
    origin ("shipped" or the file) and the profile itself."""
    return json.loads(_strand.machines_json())


def _progress(progress):
    if progress is not None and not callable(progress):
        raise TypeError("progress: expected a callable (phase, done, steps) or None")
    return progress


def _text(where, value, default=""):
    if value is None:
        return default
    if isinstance(value, (str, os.PathLike)):
        return os.fspath(value)
    raise TypeError(f"{where}: expected text, got {type(value).__name__}")


def _substrate_texts(substrate):
    if substrate is None:
        return {}
    if not isinstance(substrate, dict):
        raise TypeError("substrate: expected a dict like {'type': 'cylinder', 'radius': 20, 'length': 100}")
    return param_texts("substrate", "substrate", _TABLES["substrate"], substrate)


_COMMON = [
    "Also: machine (profile name or .json path, default deltawasp-2040-clay), arc_tolerance",
    "(mm or text with a unit), substrate (dict of the curved-substrate flags: type, radius,",
    "length, wrap, arc_length_at, mesh, extrusion), material (ink profile name or .json path, as",
    "--material), tools ('node=1,ligament=0', 'layers=0,1' or {'by_feature': {'node': 1}} as",
    "--tools), progress (callable(phase, done, steps)).",
    "Returns a strand.Result; nothing is written until Result.write().",
]


def _make_generator(spec):
    name, params = spec["name"], spec["params"]
    function = py_name(name)

    def run(*, machine=None, arc_tolerance=None, substrate=None, material=None, tools=None,
            progress=None, **values):
        texts = param_texts(function, name, params, values)
        arc = arc_tolerance if isinstance(arc_tolerance, str) or arc_tolerance is None \
            else param_texts(function, name, [{"key": "arc-tolerance", "type": "number"}],
                             {"arc-tolerance": arc_tolerance})["arc-tolerance"]
        tools_text = _json_text(tools) if isinstance(tools, dict) else _text("tools", tools)
        raw = _strand.run_generator(name, texts, _substrate_texts(substrate),
                                    _text("machine", machine), _text("arc_tolerance", arc),
                                    _text("material", material), tools_text, _progress(progress))
        return Result(raw)

    run.__name__ = run.__qualname__ = function
    run.__doc__ = doc_for(f"{function}(**params) -> strand.Result", spec["summary"], params, _COMMON)
    keywords = [Parameter(py_name(p["key"]), Parameter.KEYWORD_ONLY, default=None) for p in params]
    keywords += [Parameter(k, Parameter.KEYWORD_ONLY, default=None)
                 for k in ("machine", "arc_tolerance", "substrate", "material", "tools", "progress")]
    run.__signature__ = Signature(keywords)
    return run


for _spec in _TABLES["generators"]:
    globals()[py_name(_spec["name"])] = _make_generator(_spec)
    __all__.append(py_name(_spec["name"]))


def _json_text(value):
    """JSON of a job or sweep given as a dict: a non-finite number becomes its text ("nan"),
    which the parameter tables refuse by name as the CLI does."""
    def finite(v):
        if isinstance(v, float) and (math.isnan(v) or math.isinf(v)):
            return "nan" if math.isnan(v) else ("inf" if v > 0 else "-inf")
        if isinstance(v, dict):
            return {k: finite(x) for k, x in v.items()}
        if isinstance(v, (list, tuple)):
            return [finite(x) for x in v]
        return v
    try:
        return json.dumps(finite(value))
    except TypeError as e:
        raise TypeError(f"job: {e}") from None


def job(spec, *, progress=None):
    """A job file's content (a dict) or its path, run as `strand job FILE` runs it (a path's
    relative substrate mesh is found beside it, the output named after it)."""
    if isinstance(spec, dict):
        return Result(_strand.run_job(_json_text(spec), "", _progress(progress)))
    return Result(_strand.run_job("", path_text("job", spec), _progress(progress)))


def _typed(text):
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return None if text == "" else text


def sweep(spec, *, jobs=0, dir=None, previews=None, progress=None, frame=None):
    """A sweep file's content (dict) or path, run as `strand sweep FILE -o DIR`: every point's
    G-code (and with previews, its thumbnail and viewer) in `dir`, manifest.json/.csv and
    index.html. Without `dir` the files go to a temporary folder that is removed afterwards
    (and previews default to off). Returns the rows of manifest.csv - a pandas DataFrame when
    pandas is installed (frame=False: a list of dicts) - with the manifest's columns: index,
    name, status, the varied parameters, figures, derived.*, check_ok, crossings, output,
    content_hash, error."""
    if isinstance(spec, dict):
        text = _json_text(spec)
    else:
        with open(path_text("sweep", spec), encoding="utf-8") as f:
            text = f.read()
    if not isinstance(jobs, int) or isinstance(jobs, bool):
        raise TypeError("jobs: expected an int (0: every core)")
    if dir is None:
        with tempfile.TemporaryDirectory(prefix="strand-sweep-") as tmp:
            _, table = _strand.run_sweep(text, tmp, jobs, bool(previews), _progress(progress))
    else:
        _, table = _strand.run_sweep(text, path_text("dir", dir), jobs,
                                     True if previews is None else bool(previews), _progress(progress))
    if frame is not False:
        try:
            import pandas
            return pandas.read_csv(io.StringIO(table))
        except ImportError:
            if frame:
                raise
    return [{k: _typed(v) for k, v in row.items()} for row in csv.DictReader(io.StringIO(table))]


def _plot(svg, *, machine="xy-plotter-servo", mirror=False, order=True, progress=None, **values):
    texts = param_texts("plot", "plot", _TABLES["plot"], values)
    raw = _strand.run_plot(path_text("svg", svg), texts, _text("machine", machine), bool(mirror),
                           bool(order), _progress(progress))
    return Result(raw)


plot = _plot
plot.__name__ = plot.__qualname__ = "plot"
plot.__doc__ = doc_for(
    "plot(svg, *, machine='xy-plotter-servo', mirror=False, order=True, **params) -> strand.Result",
    "An SVG drawing as pen-plotter G-code, as `strand plot DRAWING.svg` makes it.",
    _TABLES["plot"], ["Also: progress (callable(phase, done, steps))."])


def slice(mesh=None, *, onto=None, pattern="scaffold", perimeters=0, repair=False, strict=False,
          mesh_units=None, place=None, rotate=None, scale=None, scale_to_fit=None, up=None,
          machine=None, arc_tolerance=None, threads=None, progress=None, **pattern_params):
    """A mesh (STL, OBJ, PLY, OFF, glTF, 3MF) filled with `pattern` in non-crossing strands
    per layer, or with onto=SUBSTRATE the pattern's specimen laid on a curved mesh, as
    `strand slice` does (docs/slicing.md). The pattern's own keywords (nozzle, gap, ...) as
    for its generator function; rotate=(x, y, z) degrees, scale_to_fit=(w, d, h) mm or text
    ("3 x 3 x 1 cm"), up="y" for +Y-up exports, threads=N (default every core)."""
    tables = {g["name"]: g["params"] for g in _TABLES["generators"]}
    name = _text("pattern", pattern).lower()
    texts = param_texts("slice", name, tables[name], pattern_params) if name in tables else {}
    if name not in tables and pattern_params:
        raise TypeError(f"slice: pattern {pattern!r} takes no keywords until it is a generator name")
    options = {}
    for key, value, kind in (("mesh-units", mesh_units, "text"), ("place", place, "text"),
                             ("up", up, "text"), ("machine", machine, "text"),
                             ("rotate", rotate, "number list"), ("scale", scale, "number"),
                             ("scale-to-fit", scale_to_fit, "size"),
                             ("arc-tolerance", arc_tolerance, "number")):
        if value is not None:
            options.update(param_texts("slice", "slice", [{"key": key, "type": kind}], {key: value}))
    for key, value in (("perimeters", perimeters), ("threads", threads)):
        if value is not None and (not isinstance(value, int) or isinstance(value, bool)):
            raise TypeError(f"slice.{key}: expected an int, got {type(value).__name__}")
    if threads is not None:
        options["threads"] = str(threads)
    raw = _strand.run_slice("" if mesh is None else path_text("mesh", mesh),
                            "" if onto is None else path_text("onto", onto), pattern, texts, options,
                            perimeters, bool(repair), bool(strict), _progress(progress))
    return Result(raw)


def read_gcode(path, *, machine=None):
    """Any G-code file (Strand's, PrusaSlicer's, Cura's ...) read as `strand check` reads it:
    .moves, .layers(), .e (E per move), .check() (with `machine`: build volume, arcs) and
    .preview()."""
    return Result(_strand.read_gcode(path_text("path", path), _text("machine", machine)))
