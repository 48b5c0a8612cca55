"""predict and flight against the CLI: the golden shots, a shipped world, a launch file."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import smash_golf as sg
from conftest import ROOT, read_cli_csv

GOLDEN = ROOT / "tests" / "data" / "golden"
GOLDEN_CLUBS = ROOT / "tests" / "data" / "golden_clubs"
CASES = sorted(p.stem for p in GOLDEN_CLUBS.glob("*.toml"))
PAPER_DRIVER = ROOT / "configs" / "clubs" / "paper_driver.toml"


def assert_same_table(got: pd.DataFrame, want: pd.DataFrame, rtol: float = 0.0, atol: float = 0.0):
    """Same columns in the same order, text columns equal, numbers within the tolerances."""
    assert list(got.columns) == list(want.columns)
    assert len(got) == len(want)
    for c in want.columns:
        g, w = got[c], want[c]
        if pd.api.types.is_numeric_dtype(w):
            assert pd.api.types.is_numeric_dtype(g), c
            np.testing.assert_allclose(g.to_numpy(float), w.to_numpy(float), rtol=rtol, atol=atol, err_msg=c)
        else:
            assert g.astype(str).tolist() == w.astype(str).tolist(), c


def test_cases_are_there():
    # The comparison below must not pass by finding nothing.
    assert len(CASES) >= 10
    assert all((GOLDEN / f"{c}.csv").exists() for c in CASES)


@pytest.mark.parametrize("case", CASES)
def test_predict_golden_matches_cli(cli, tmp_path, case):
    club, shots = GOLDEN_CLUBS / f"{case}.toml", GOLDEN / f"{case}.csv"
    out = tmp_path / "pred.csv"
    cli.run("predict", "--club", club, "--shots", shots, "--out", out)
    want = read_cli_csv(out)
    df = read_cli_csv(shots)
    got = sg.predict(sg.Club.load(club), df)
    assert_same_table(got, want, rtol=1e-12)
    # A path is read as the CLI reads it.
    assert_same_table(sg.predict(club, shots), want, rtol=1e-12)
    # And the golden values themselves (what cli/tests/golden.rs checks, to 1e-6).
    pred = [c for c in df.columns if c.startswith("pred_")]
    np.testing.assert_allclose(got[pred].to_numpy(), df[pred].to_numpy(), rtol=1e-6, atol=1e-6)


def test_predict_world_matches_cli(cli, tmp_path, paper_world):
    out = tmp_path / "pred.csv"
    cli.run("predict", "--club", PAPER_DRIVER, "--shots", paper_world, "--out", out)
    want = read_cli_csv(out)
    got = sg.predict(PAPER_DRIVER, read_cli_csv(paper_world))
    assert any(c.startswith("err_") for c in got.columns)
    assert_same_table(got, want, rtol=1e-12)


def test_club_variant_predicts_as_its_file(cli, tmp_path):
    base = sg.Club.load(GOLDEN_CLUBS / "nominal.toml")
    variant = base.with_effect("added_mass", dm_g=2.54)
    assert variant.effects == [{"name": "added_mass", "group": None, "params": {"dm_g": 2.54}}]
    path = tmp_path / "variant.toml"
    path.write_text(variant.to_toml("a variant"))
    out = tmp_path / "pred.csv"
    shots = GOLDEN / "added_mass.csv"
    cli.run("predict", "--club", path, "--shots", shots, "--out", out)
    assert_same_table(sg.predict(variant, shots), read_cli_csv(out), rtol=1e-12)
    # The variant is the golden club file's club.
    assert variant.to_toml() == sg.Club.load(GOLDEN_CLUBS / "added_mass.toml").to_toml()
    assert variant.without_effects().effects == []
    two = variant.with_effect("ball_offset", group="A", dy_mm=0.48, dz_mm=-0.07)
    assert [e["name"] for e in two.effects] == ["added_mass", "ball_offset"]
    assert two.effects[1] == {"name": "ball_offset", "group": "A",
                              "params": {"dy_mm": 0.48, "dz_mm": -0.07}}
    assert sg.Club.from_toml(two.to_toml()).to_toml() == two.to_toml()


def test_club_refuses_what_a_club_file_refuses():
    base = sg.Club.load(PAPER_DRIVER)
    with pytest.raises(sg.SmashError, match="dm_g"):
        base.with_effect("added_mass")
    with pytest.raises(sg.SmashError, match="no_such_effect"):
        base.with_effect("no_such_effect", x=1.0)


def test_predict_error_is_the_cli_line(cli, tmp_path):
    df = pd.read_csv(GOLDEN / "nominal.csv", dtype={"shot_id": str}).drop(columns=["impact_y_mm"])
    bad = tmp_path / "bad.csv"
    df.to_csv(bad, index=False)
    want = cli.error("predict", "--club", PAPER_DRIVER, "--shots", bad, "--out", tmp_path / "p.csv")
    with pytest.raises(sg.SmashError) as e:
        sg.predict(PAPER_DRIVER, bad)
    assert str(e.value) == want
    with pytest.raises(sg.SmashError) as e:
        sg.predict(PAPER_DRIVER, df)
    assert str(e.value) == want.replace(str(bad), "<shots DataFrame>")


def flight_cli(cli, tmp_path, shots: Path, *args: str) -> pd.DataFrame:
    out = tmp_path / "flight.csv"
    cli.run("flight", "--shots", shots, "--out", out, *args)
    return read_cli_csv(out)


YD = 1e-9  # yd: flight distances must agree to this


def test_flight_launch_file_matches_cli(cli, tmp_path, paper_world):
    want = flight_cli(cli, tmp_path, paper_world)
    got = sg.flight(read_cli_csv(paper_world))
    assert "pred_carry_yd" in got.columns
    assert_same_table(got, want, rtol=1e-12, atol=YD)
    assert_same_table(sg.flight(paper_world), want, rtol=1e-12, atol=YD)


def test_flight_atmosphere_matches_cli(cli, tmp_path, paper_world):
    opts = dict(elevation_m=1600.0, temperature_c=28.0, humidity_pct=20.0, wind_speed_m_s=4.0,
                wind_direction_deg=45.0, total=True, ground_restitution=0.3)
    args = ["--elevation-m", "1600", "--temperature-c", "28", "--humidity-pct", "20",
            "--wind-speed-m-s", "4", "--wind-direction-deg", "45", "--total",
            "--ground-restitution", "0.3"]
    want = flight_cli(cli, tmp_path, paper_world, *args)
    got = sg.flight(read_cli_csv(paper_world), **opts)
    assert "pred_total_yd" in got.columns
    assert_same_table(got, want, rtol=1e-12, atol=YD)
    # The atmosphere matters (the comparison would not notice a dropped option otherwise).
    still = sg.flight(read_cli_csv(paper_world))
    assert np.abs(got["pred_carry_yd"] - still["pred_carry_yd"]).max() > 1.0


def test_flight_of_predictions_matches_cli(cli, tmp_path, paper_world):
    pred_path = tmp_path / "pred.csv"
    cli.run("predict", "--club", PAPER_DRIVER, "--shots", paper_world, "--out", pred_path)
    want = flight_cli(cli, tmp_path, pred_path, "--launch", "predicted")
    pred = sg.predict(PAPER_DRIVER, read_cli_csv(paper_world))
    got = sg.flight(pred, columns="predicted")
    assert_same_table(got, want, rtol=1e-12, atol=YD)


def test_flight_errors_are_the_cli_lines(cli, tmp_path, paper_world):
    want = cli.error("flight", "--shots", paper_world, "--out", tmp_path / "f.csv", "--dt-s", "7")
    with pytest.raises(sg.SmashError) as e:
        sg.flight(paper_world, dt_s=7.0)
    assert str(e.value) == want
    df = read_cli_csv(paper_world).drop(columns=["backspin_rpm"])
    bad = tmp_path / "bad.csv"
    df.to_csv(bad, index=False)
    want = cli.error("flight", "--shots", bad, "--out", tmp_path / "f.csv")
    with pytest.raises(sg.SmashError) as e:
        sg.flight(df)
    assert str(e.value) == want.replace(str(bad), "<launch DataFrame>")


def test_zero_solver_iterations_are_refused_by_the_library(paper_world):
    with pytest.raises(sg.SmashError, match="--max-iters must be at least 1"):
        sg.diagnose(PAPER_DRIVER, paper_world, max_iters=0)
    with pytest.raises(sg.SmashError, match="--max-iters must be at least 1"):
        sg.calibrate(PAPER_DRIVER, paper_world, "added_mass", max_iters=0)
