"""The module's tables, help and stubs, and bad input: the CLI's one-line messages as
ValueError, wrong types as TypeError, never a crash, nothing written."""

import inspect
import math
import os
import pathlib

import pytest

import strand
from conftest import run_cli

THESIS = dict(nozzle=0.84, gap=1.6, size=(36, 36), height=13)
THESIS_FLAGS = ["--nozzle", "0.84", "--gap", "1.6", "--size", "36x36", "--height", "13"]


def test_generators_and_machines_are_the_clis(tmp_path):
    names = [g["name"] for g in strand.generators()]
    code, out = run_cli(["--help"], tmp_path)
    for name in names:
        assert f"\n  {name} " in out
        assert callable(getattr(strand, name.replace("-", "_")))
    code, out = run_cli(["machines", "--json"], tmp_path)
    import json
    assert [m["name"] for m in strand.machines()] == [m["name"] for m in json.loads(out)]


def test_help_lists_every_parameter_with_its_unit(tmp_path):
    scaffold = next(g for g in strand.generators() if g["name"] == "scaffold")
    doc = strand.scaffold.__doc__
    for p in scaffold["params"]:
        line = next(l for l in doc.splitlines() if l.strip().startswith(p["key"].replace("-", "_") + " "))
        if p["unit"]:
            assert f"[{p['unit']}]" in line
    nozzle = next(p for p in scaffold["params"] if p["key"] == "nozzle")
    assert nozzle["unit"] == "mm" and nozzle["max"] == 10
    sig = inspect.signature(strand.scaffold)
    assert "layer_height" in sig.parameters and "machine" in sig.parameters


def test_stubs_name_every_keyword():
    stub = pathlib.Path(strand.__file__).with_name("__init__.pyi").read_text()
    for g in strand.generators():
        assert f"def {g['name'].replace('-', '_')}(" in stub
        for p in g["params"]:
            assert f"    {p['key'].replace('-', '_')}: " in stub
    compile(stub, "__init__.pyi", "exec")


@pytest.mark.parametrize("value,flag", [(-1, "-1"), (math.nan, "nan"), ("3mm/s", "3mm/s"),
                                        (math.inf, "inf"), (1e300, "1e+300")])
def test_bad_values_raise_the_clis_message(value, flag, tmp_path):
    os.chdir(tmp_path)
    code, out = run_cli(["scaffold", "--nozzle", flag, *THESIS_FLAGS[2:]], tmp_path)
    assert code == 2
    with pytest.raises(ValueError) as e:
        strand.scaffold(**{**THESIS, "nozzle": value})
    assert out.strip() == "strand: error: " + str(e.value)
    assert list(tmp_path.iterdir()) == []


def test_huge_sizes_and_unknown_machines_raise_before_any_work(tmp_path):
    os.chdir(tmp_path)
    with pytest.raises(ValueError, match=r"^scaffold.size = .*must each be in"):
        strand.scaffold(**{**THESIS, "size": (1e6, 1e6)})
    # Within each parameter's range but beyond the work bound: refused before it is built.
    with pytest.raises(ValueError, match=r"^scaffold.layers = \d+: the specimen would have about \d+ moves, more than the limit"):
        strand.scaffold(nozzle=0.05, gap=0.05, size=(1000, 1000), height=500, machine="marlin-xyz-200")
    with pytest.raises(ValueError, match=r"^machine = nope: unknown machine"):
        strand.scaffold(**THESIS, machine="nope")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("value", [True, None, {"a": 1}, [0.84], object()])
def test_wrong_types_raise_type_error(value):
    if value is None:  # None is "not given": the required parameter is then missing
        with pytest.raises(ValueError, match="scaffold.nozzle: missing"):
            strand.scaffold(**{**THESIS, "nozzle": value})
        return
    with pytest.raises(TypeError, match="scaffold.nozzle"):
        strand.scaffold(**{**THESIS, "nozzle": value})


def test_unknown_keywords_and_bad_arguments_raise_type_error():
    with pytest.raises(TypeError, match="unexpected keyword argument 'nozle'"):
        strand.scaffold(nozle=0.84, gap=1.6, size=(36, 36), height=13)
    with pytest.raises(TypeError):
        strand.scaffold(0.84)
    with pytest.raises(TypeError, match="machine"):
        strand.scaffold(**THESIS, machine=3)
    with pytest.raises(TypeError, match="progress"):
        strand.scaffold(**THESIS, progress=1)
    with pytest.raises(TypeError, match="job"):
        strand.job(42)


def test_bad_jobs_raise_the_clis_message(tmp_path):
    job = tmp_path / "bad.json"
    job.write_text('{"generator": "scafold", "params": {}}')
    code, out = run_cli(["job", job], tmp_path)
    with pytest.raises(ValueError) as e:
        strand.job(job)
    assert out.strip() == "strand: error: " + str(e.value)
    with pytest.raises(ValueError, match=r"^scaffold.nozzle = nan: must be a number \(mm\)"):
        strand.job({"generator": "scaffold", "params": {"nozzle": math.nan}})
    with pytest.raises(ValueError, match="cannot read|No such|missing.json"):
        strand.job(tmp_path / "missing.json")
