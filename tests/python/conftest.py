"""Shared fixtures of the Python module's tests: the repository, the CLI beside the module."""

import json
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SAMPLES = ROOT / "samples"


def cli_path():
    return os.environ.get("STRAND_CLI", str(ROOT / "build" / "cli" / "strand"))


def run_cli(args, cwd):
    """Runs the strand program; returns (exit code, stdout + stderr)."""
    p = subprocess.run([cli_path(), *map(str, args)], cwd=cwd, capture_output=True, text=True)
    return p.returncode, p.stdout + p.stderr


def sample_jobs():
    """Every samples/*.json job file."""
    return sorted(SAMPLES.glob("*.json"))


def flags_of(params):
    """A job's "params" as CLI flags: {"size": [36, 36]} -> ["--size", "36x36"]."""
    out = []
    for key, value in params.items():
        if isinstance(value, bool):  # an on/off parameter is a bare flag: {"stagger": true}
            out += [f"--{key}"] if value else []
            continue
        if isinstance(value, list):
            sep = "x" if key == "size" else ","
            value = sep.join(json.dumps(v) for v in value)
        out += [f"--{key}", str(value) if not isinstance(value, float) else repr(value)]
    return out


@pytest.fixture
def cli():
    return run_cli
