"""The module writes what the CLI writes: byte-identical G-code (and every file of a curved
job) for every generator and every sample job."""

import json

import pytest

import strand
from conftest import SAMPLES, flags_of, run_cli, sample_jobs


def flat_samples():
    return [p for p in sample_jobs() if "substrate" not in json.loads(p.read_text())]


def test_every_generator_has_a_flat_sample():
    covered = {json.loads(p.read_text())["generator"] for p in flat_samples()}
    assert covered == {g["name"] for g in strand.generators()}


@pytest.mark.parametrize("path", flat_samples(), ids=lambda p: p.stem)
def test_generator_function_gives_the_cli_bytes(path, tmp_path):
    job = json.loads(path.read_text())
    # A sample's printheads by feature: --tools as text, the module takes the job file's dict.
    tools = job.get("tools", {}).get("by_feature", {})
    tool_flags = ["--tools", ",".join(f"{k}={v}" for k, v in tools.items())] if tools else []
    code, out = run_cli([job["generator"], *flags_of(job["params"]), "--machine", job["machine"],
                         *tool_flags, "-o", "cli.gcode"], tmp_path)
    assert code == 0, out
    function = getattr(strand, job["generator"].replace("-", "_"))
    params = {k.replace("-", "_"): v for k, v in job["params"].items()}
    r = function(machine=job["machine"], tools=job.get("tools"), **params)
    assert r.gcode == (tmp_path / "cli.gcode").read_text()
    assert r.text.splitlines()[1:] == out.splitlines()[1:]  # the summary, but the file name


@pytest.mark.parametrize("path", sample_jobs(), ids=lambda p: p.stem)
def test_job_gives_the_cli_files(path, tmp_path):
    code, out = run_cli(["job", path], tmp_path)
    assert code == 0, out
    r = strand.job(path)
    assert r.files, "a job writes at least one file"
    for name, text in r.files.items():
        assert (tmp_path / name).read_text() == text, name
    assert r.gcode == (tmp_path / r.name).read_text()


def test_job_dict_equals_job_file(tmp_path):
    path = next(p for p in flat_samples() if p.stem == "scaffold-thesis")
    spec = json.loads(path.read_text())
    assert strand.job(spec).gcode == strand.job(path).gcode


def test_values_with_units_read_as_the_cli_reads_them(tmp_path):
    code, out = run_cli(["scaffold", "--nozzle", "840um", "--gap", "0.16cm", "--size", "36x36mm",
                         "--height", "13", "-o", "cli.gcode"], tmp_path)
    assert code == 0, out
    r = strand.scaffold(nozzle="840um", gap="0.16cm", size="36x36mm", height=13)
    assert r.gcode == (tmp_path / "cli.gcode").read_text()
    assert strand.scaffold(nozzle=0.84, gap=1.6, size=(36, 36), height=13).gcode == r.gcode


def test_plot_gives_the_cli_bytes(tmp_path):
    svg = SAMPLES / "plot" / "shapes.svg"
    code, out = run_cli(["plot", svg, "--fit", "A5", "-o", "cli.gcode"], tmp_path)
    assert code == 0, out
    r = strand.plot(svg, fit="A5")
    assert r.gcode == (tmp_path / "cli.gcode").read_text()


@pytest.mark.parametrize("args,kwargs", [
    (["samples/meshes/spot.obj", "--up", "y", "--scale-to-fit", "30x30x30", "--pattern", "scaffold",
      "--nozzle", "0.6", "--gap", "1", "--perimeters", "1"],
     dict(mesh="samples/meshes/spot.obj", up="y", scale_to_fit=(30, 30, 30), pattern="scaffold",
          nozzle=0.6, gap=1, perimeters=1)),
    (["samples/meshes/bone-plug.stl", "--pattern", "tetrachiral", "--nozzle", "0.4", "--cell", "5"],
     dict(mesh="samples/meshes/bone-plug.stl", pattern="tetrachiral", nozzle=0.4, cell=5)),
    (["--onto", "samples/meshes/curved-plate.obj", "--pattern", "scaffold", "--nozzle", "0.6",
      "--gap", "1", "--size", "30x20", "--layers", "2"],
     dict(onto="samples/meshes/curved-plate.obj", pattern="scaffold", nozzle=0.6, gap=1,
          size=(30, 20), layers=2)),
], ids=["spot", "bone-plug-tetrachiral", "onto-curved-plate"])
def test_slice_gives_the_cli_bytes(args, kwargs, tmp_path):
    root = SAMPLES.parent
    args = [str(root / a) if a.startswith("samples/") else a for a in args]
    kwargs = {k: str(root / v) if isinstance(v, str) and v.startswith("samples/") else v
              for k, v in kwargs.items()}
    code, out = run_cli(["slice", *args, "-o", "cli.gcode"], tmp_path)
    assert code == 0, out
    r = strand.slice(**kwargs)
    assert r.gcode == (tmp_path / "cli.gcode").read_text()


def test_material_gives_the_cli_bytes(tmp_path, monkeypatch):
    (tmp_path / "materials").mkdir()
    (tmp_path / "materials" / "paste.json").write_text(json.dumps(
        {"name": "paste", "nozzle_mm": 0.6, "measurements": ["m.json"],
         "print": {"speed_mm_min": 320, "flow": 1.2, "layer_height_mm": 0.5}}))
    monkeypatch.chdir(tmp_path)  # materials/ is found from the working directory, as the CLI's
    flags = ["--nozzle", "0.6", "--gap", "1", "--size", "10x10", "--layers", "2"]
    code, out = run_cli(["scaffold", *flags, "--machine", "deltawasp-2040-clay-ldm", "--material", "paste",
                         "-o", "cli.gcode"], tmp_path)
    assert code == 0, out
    r = strand.scaffold(nozzle=0.6, gap=1, size="10x10", layers=2, machine="deltawasp-2040-clay-ldm",
                        material="paste")
    assert r.gcode == (tmp_path / "cli.gcode").read_text()
    assert r.report["material"]["flow"] == 1.2
