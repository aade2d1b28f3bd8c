"""Every examples/*.ipynb executes without error (jupyter nbconvert --execute, as a reader
would run it), and shows what it is there to show."""

import json
import os
import subprocess
import sys

import pytest

from conftest import ROOT

NOTEBOOKS = sorted((ROOT / "examples").glob("*.ipynb"))


def execute(notebook, out_dir):
    # The kernel's inline backend (matplotlib-inline, drawn with Agg) puts the figures into
    # the notebook; a plain Agg backend from the environment would draw them nowhere.
    env = {k: v for k, v in os.environ.items() if k != "MPLBACKEND"}
    # The kernel runs in examples/: the module's folder must not be relative.
    env["PYTHONPATH"] = os.pathsep.join(os.path.abspath(p) for p in env.get("PYTHONPATH", "").split(os.pathsep) if p)
    p = subprocess.run([sys.executable, "-m", "jupyter", "nbconvert", "--to", "notebook", "--execute",
                        "--ExecutePreprocessor.timeout=120", "--output-dir", str(out_dir), str(notebook)],
                       cwd=notebook.parent, env=env, capture_output=True, text=True)
    assert p.returncode == 0, p.stderr[-3000:]
    return json.loads((out_dir / notebook.name).read_text())


def outputs(nb, mime):
    return [o["data"][mime] for c in nb["cells"] if c["cell_type"] == "code"
            for o in c.get("outputs", []) if mime in o.get("data", {})]


def test_there_are_notebooks_and_none_is_committed_with_outputs():
    assert len(NOTEBOOKS) >= 4
    for path in NOTEBOOKS:
        nb = json.loads(path.read_text())
        assert all(not c.get("outputs") for c in nb["cells"] if c["cell_type"] == "code"), path.name


@pytest.mark.parametrize("notebook", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_executes(notebook, tmp_path):
    nb = execute(notebook, tmp_path)
    errors = [o for c in nb["cells"] for o in c.get("outputs", []) if o.get("output_type") == "error"]
    assert not errors
    assert outputs(nb, "image/png"), "every example draws something"
    if notebook.stem == "tetrachiral_preview":
        frames = outputs(nb, "text/html")
        assert any("<iframe srcdoc=" in "".join(f) for f in frames), "the inline 3D preview"
