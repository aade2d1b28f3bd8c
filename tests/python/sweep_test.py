"""strand.sweep returns the rows of the manifest.csv the CLI writes for the same file."""

import csv
import json

import strand
from conftest import SAMPLES, run_cli

SWEEP = SAMPLES / "sweeps" / "scaffold-nozzle-gap.json"


def test_rows_equal_the_clis_manifest(tmp_path):
    code, out = run_cli(["sweep", SWEEP, "-o", tmp_path / "cli"], tmp_path)
    assert code == 0, out
    rows = strand.sweep(SWEEP, dir=tmp_path / "py", jobs=2, frame=False)
    with open(tmp_path / "cli" / "manifest.csv", newline="") as f:
        expected = list(csv.DictReader(f))
    assert [list(r) for r in rows] == [list(r) for r in expected]
    for row, want in zip(rows, expected):
        for key, text in want.items():
            value = row[key]
            assert (value is None and text == "") or str(value) == text or float(value) == float(text), key
    assert (tmp_path / "py" / "manifest.csv").read_text() == (tmp_path / "cli" / "manifest.csv").read_text()


def test_frame_and_temporary_folder():
    spec = json.loads(SWEEP.read_text())
    frame = strand.sweep(spec)
    # 2 nozzles x 3 gaps; "gap >= nozzle" drops 0.84 x 0.8.
    assert list(frame["status"]) == ["ok", "dropped", "ok", "ok", "ok", "ok"]
    assert {"nozzle", "gap", "porosity", "check_ok", "crossings"} <= set(frame.columns)
    ok = frame[frame["status"] == "ok"]
    assert ok["check_ok"].eq(True).all() and ok["crossings"].eq(0).all()


def test_a_bad_sweep_is_a_value_error():
    spec = json.loads(SWEEP.read_text())
    spec["vary"]["gap"]["step"] = -1
    try:
        strand.sweep(spec)
    except ValueError as e:
        assert str(e).startswith("sweep.vary.gap")
    else:
        raise AssertionError("no error")
