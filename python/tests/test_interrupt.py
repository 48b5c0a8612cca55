"""Ctrl-C during a long diagnose (issue 41, item D): the run stops within a fraction of a second
with KeyboardInterrupt, instead of when it ends (it took 21.7 s after the signal), and the
package works afterwards."""

from __future__ import annotations

import os
import signal
import time

import pytest

import smash_golf as sg
from conftest import ROOT, read_cli_csv

PAPER_DRIVER = ROOT / "configs" / "clubs" / "paper_driver.toml"


class InterruptAtFirstFit:
    """A progress receiver that sends this process SIGINT (what Ctrl-C sends) when the first
    fit of the run is done: the signal comes in the middle of the work, whatever the
    machine's speed."""

    def __init__(self):
        self.sent_at = None
        self.fits_after = 0

    def step(self, step, jobs):
        pass

    def job_done(self):
        if self.sent_at is None:
            self.sent_at = time.monotonic()
            os.kill(os.getpid(), signal.SIGINT)
        else:
            self.fits_after += 1


@pytest.fixture
def sigint_raises():
    """Python's own SIGINT handler for the test: a process started in the background by a
    non-interactive shell inherits SIGINT ignored, and Python then installs no handler, so
    the signal would do nothing (a CI runner that starts its jobs that way failed the test)."""
    before = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, before)


def test_ctrl_c_stops_a_diagnose_at_once(paper_world, sigint_raises):
    world = read_cli_csv(paper_world)
    r = InterruptAtFirstFit()
    with pytest.raises(KeyboardInterrupt):
        sg.diagnose(PAPER_DRIVER, world, progress=r)
    took = time.monotonic() - r.sent_at
    assert r.sent_at is not None
    # The fits running when the signal came finish; no new one starts after the next check
    # (the whole run makes about 600, and took 21.7 s after the signal before).
    assert took < 5.0, f"KeyboardInterrupt {took:.1f} s after SIGINT"
    assert r.fits_after < 100, f"{r.fits_after} fits finished after SIGINT"
    # The package is usable afterwards (the interrupted run's threads have ended).
    got = sg.compare(PAPER_DRIVER, world, tables=False)
    assert got["n_shots"] > 0
