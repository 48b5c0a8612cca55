"""diagnose, compare and calibrate against the CLI's --json on a shipped world."""

from __future__ import annotations

import math

import pandas as pd
import pytest

import smash_golf as sg
from conftest import ROOT, read_cli_csv

PAPER_DRIVER = ROOT / "configs" / "clubs" / "paper_driver.toml"
NOISE = ROOT / "configs" / "noise" / "paper_world.toml"


def assert_json_close(got, want, rtol=1e-12, path="$"):
    """The same structure, strings and booleans equal, numbers within `rtol`."""
    if isinstance(want, dict):
        assert isinstance(got, dict), path
        assert list(got.keys()) == list(want.keys()), path
        for k in want:
            assert_json_close(got[k], want[k], rtol, f"{path}.{k}")
    elif isinstance(want, list):
        assert isinstance(got, list) and len(got) == len(want), path
        for i, (g, w) in enumerate(zip(got, want)):
            assert_json_close(g, w, rtol, f"{path}[{i}]")
    elif isinstance(want, float) or (isinstance(want, int) and not isinstance(want, bool)
                                     and isinstance(got, float)):
        assert isinstance(got, (int, float)) and not isinstance(got, bool), path
        assert math.isclose(got, want, rel_tol=rtol, abs_tol=0.0), f"{path}: {got} != {want}"
    else:
        assert got == want, f"{path}: {got!r} != {want!r}"


def uncommented(toml: str) -> str:
    return "\n".join(l for l in toml.splitlines() if not l.startswith("#")).strip()


@pytest.fixture(scope="module")
def world(paper_world):
    return read_cli_csv(paper_world)


def test_diagnose_matches_cli(cli, tmp_path, paper_world, world):
    out_club = tmp_path / "selected.toml"
    want = cli.json("diagnose", "--club", PAPER_DRIVER, "--shots", paper_world,
                    "--out-club", out_club)
    got = sg.diagnose(PAPER_DRIVER, world, tables=False, progress=False)
    club = got.pop("club")
    assert want["selected"], "the paper world's effects are found"
    assert got["selected"] == want["selected"]
    assert_json_close(got, want)
    assert uncommented(club.to_toml()) == uncommented(out_club.read_text())


def test_diagnose_noise_file_and_tables(cli, paper_world, world):
    want = cli.json("diagnose", "--club", PAPER_DRIVER, "--shots", paper_world, "--noise", NOISE,
                    "--max-steps", "2")
    got = sg.diagnose(PAPER_DRIVER, world, NOISE, max_steps=2, progress=False)
    assert got["selected"] == want["selected"]
    assert isinstance(got["estimates"], pd.DataFrame)
    assert list(got["estimates"]["effect"]) == [e["effect"] for e in want["estimates"]]
    after = got["after"]
    for group, comps in want["after"].items():
        for comp, stats in comps.items():
            for stat, v in stats.items():
                assert math.isclose(after.loc[group, (comp, stat)], v, rel_tol=1e-12)


class Recorder:
    def __init__(self):
        self.steps, self.done = [], 0

    def step(self, step, jobs):
        self.steps.append((step, jobs))

    def job_done(self):
        self.done += 1


def test_diagnose_reports_progress(world):
    r = Recorder()
    got = sg.diagnose(PAPER_DRIVER, world, max_steps=1, progress=r)
    assert r.steps and r.steps[0][0] == 1
    assert r.steps[0][1] > 0 and r.done > 0
    assert len(got["selected"]) <= 1


def test_diagnose_error_is_the_cli_line(cli, paper_world, world):
    want = cli.error("diagnose", "--club", PAPER_DRIVER, "--shots", paper_world, "--folds", "1")
    with pytest.raises(sg.SmashError) as e:
        sg.diagnose(PAPER_DRIVER, world, folds=1)
    assert str(e.value) == want


def test_compare_matches_cli(cli, paper_world, world):
    want = cli.json("compare", "--club", PAPER_DRIVER, "--shots", paper_world,
                    "--impact-noise-mm", "3,2.5", "--alpha", "0.05")
    got = sg.compare(PAPER_DRIVER, world, impact_noise_mm=(3.0, 2.5), alpha=0.05, tables=False)
    text = got.pop("text")
    assert "vs <shots DataFrame>" in text
    assert_json_close(got, want)


def test_calibrate_matches_cli(cli, tmp_path, paper_world, world):
    out_club = tmp_path / "cal.toml"
    want = cli.json("calibrate", "--club", PAPER_DRIVER, "--shots", paper_world,
                    "--effects", "added_mass@group,ball_offset", "--out-club", out_club)
    got = sg.calibrate(PAPER_DRIVER, world, ["added_mass@group", "ball_offset"], tables=False,
                       progress=False)
    club = got.pop("club")
    assert_json_close(got, want)
    assert uncommented(club.to_toml()) == uncommented(out_club.read_text())
    tables = sg.calibrate(PAPER_DRIVER, world, "added_mass@group,ball_offset", progress=False)
    assert list(tables["params"]["param"]) == [p["param"] for p in want["params"]]


def test_compare_refuses_another_clubs_shots_as_the_cli(cli, tmp_path, world):
    lofted = world.copy()
    lofted["dynamic_loft_deg"] += 11.0
    path = tmp_path / "lofted.csv"
    lofted.to_csv(path, index=False)
    want = cli.error("compare", "--club", PAPER_DRIVER, "--shots", path)
    assert "club file's loft is 9.8°" in want
    with pytest.raises(sg.SmashError) as e:
        sg.compare(PAPER_DRIVER, path)
    assert str(e.value) == want
    got = sg.compare(PAPER_DRIVER, lofted, ignore_club_mismatch=True, tables=False)
    assert got["findings"] == []
    assert "loft" in got["club_mismatch"]
    assert got["text"].startswith("NO FINDINGS: the shots do not match the club")


def test_a_synth_worlds_hidden_definition_is_no_candidate_of_a_later_diagnose():
    # The twisted-face world hides `face_twist`, defined in its own file: a diagnosis run after
    # its synth in the same session ranks the library's effects only, as `smash diagnose` does.
    shots, truth = sg.synth(ROOT / "configs" / "synth" / "twisted_face_world.toml", seed=1)
    assert "face_twist" in truth
    got = sg.diagnose(PAPER_DRIVER, shots, max_steps=1, tables=False, progress=False)
    offered = {c["effect"] for s in got["steps"] for c in s["candidates"]}
    assert "com_offset" in offered
    assert "face_twist" not in offered
