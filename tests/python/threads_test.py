"""Long calls release the GIL, report progress and stop on Ctrl-C without writing anything."""

import os
import signal
import threading
import time

import pytest

import strand

# Half a million moves in 284 layers: a good half second of work, well inside the bounds.
BIG = dict(nozzle=0.1, gap=0.1, size=(190, 190), height=25, machine="marlin-xyz-200")


def test_a_second_thread_runs_while_a_job_works():
    done = threading.Event()
    worker = threading.Thread(target=lambda: (strand.scaffold(**BIG), done.set()))
    ticks = 0
    worker.start()
    while worker.is_alive():
        ticks += 1
        time.sleep(0.001)
    assert done.is_set()
    # Holding the GIL for the whole job would leave this loop a tick or two.
    assert ticks >= 20


def test_progress_reports_the_phases_on_the_calling_thread():
    calls = []
    strand.scaffold(nozzle=0.84, gap=1.6, size=(36, 36), height=13,
                    progress=lambda phase, done, steps: calls.append((phase, done, steps, threading.get_ident())))
    phases = [c[0] for c in calls]
    assert phases[0] == "generating" and "checking" in phases
    assert any(steps > 0 and done == steps for _, done, steps, _ in calls), "a counted phase finishes"
    assert {c[3] for c in calls} == {threading.get_ident()}


def test_an_error_in_the_progress_callback_stops_the_job():
    def boom(phase, done, steps):
        raise RuntimeError("stop here")
    with pytest.raises(RuntimeError, match="stop here"):
        strand.scaffold(nozzle=0.84, gap=1.6, size=(36, 36), height=13, progress=boom)


def test_ctrl_c_raises_keyboard_interrupt_and_writes_nothing(tmp_path):
    # SIGINT arrives from another thread while the job plans (the GIL released, no Python
    # running): the next layer's progress hook sees it and the job unwinds.
    planning = threading.Event()
    steps = []

    def progress(phase, done, total):
        if phase.startswith("planning"):
            steps.append((done, total))
            if done == 5:
                planning.set()

    sender = threading.Thread(target=lambda: (planning.wait(30), os.kill(os.getpid(), signal.SIGINT)))
    os.chdir(tmp_path)
    sender.start()
    with pytest.raises(KeyboardInterrupt):
        strand.scaffold(**BIG, progress=progress)
    sender.join()
    done, total = steps[-1]
    assert total == 284 and done < total, "stopped before the last layer"
    assert list(tmp_path.iterdir()) == []
    # The module still works afterwards.
    assert strand.scaffold(nozzle=0.84, gap=1.6, size=(20, 20), layers=2).summary["layers"] == 2


def test_ctrl_c_stops_a_sweep_before_its_manifest(tmp_path):
    spec = {"job": {"generator": "scaffold", "machine": "deltawasp-2040-clay",
                    "params": {"size": "20x20", "height": 3}},
            "vary": {"nozzle": [0.6, 0.84], "gap": {"from": 1.0, "to": 3.0, "step": 0.1}}}
    def interrupt(phase, done, total):
        if done == 2:
            os.kill(os.getpid(), signal.SIGINT)
    with pytest.raises(KeyboardInterrupt):
        strand.sweep(spec, dir=tmp_path / "sweep", jobs=1, previews=False, progress=interrupt)
    assert not (tmp_path / "sweep" / "manifest.csv").exists()
