"""read_export against `smash import`, and a Club's effect list and the effect library."""

from __future__ import annotations

import pytest

import smash_golf as sg
from conftest import ROOT, read_cli_csv
from test_predict_flight import assert_same_table

PAPER_DRIVER = ROOT / "configs" / "clubs" / "paper_driver.toml"

# A TrackMan export as the vendor writes it: byte-order mark, `sep=,`, a units row (km/h, mm),
# impact offset positive toward the heel (TrackMan does not say), a per-club average row.
TRACKMAN = (
    "\ufeffsep=,\r\n"
    "Date,Player,Club,Club Speed,Attack Angle,Club Path,Dyn. Loft,Face Angle,Impact Offset,"
    "Impact Height,Ball Speed,Smash Factor,Launch Angle,Launch Direction,Spin Rate,Spin Axis,Carry\r\n"
    ",,,[km/h],[deg],[deg],[deg],[deg],[mm],[mm],[km/h],[],[deg],[deg],[rpm],[deg],[m]\r\n"
    "2026-01-01,P1,Driver,169.0,-1.2,2.1,13.5,1.0,-4.0,3.0,250.0,1.48,12.1,1.5,2600,3.5,212.0\r\n"
    "2026-01-01,P1,Driver,172.5,0.4,-1.0,12.0,-0.5,6.5,-2.0,254.1,1.47,11.0,-0.7,2450,-6.0,220.4\r\n"
    "2026-01-02,P2,Driver,160.2,2.0,0.3,15.1,0.2,1.0,8.0,236.9,1.48,14.2,0.6,2900,1.0,201.3\r\n"
    ",Average,Average,150,0,0,10,0,0,0,220,1.47,10,0,2500,0,230\r\n"
)


def test_read_export_matches_cli_import(cli, tmp_path):
    exp = tmp_path / "session.csv"
    exp.write_bytes(TRACKMAN.encode("utf-8"))
    out = tmp_path / "shots.csv"
    cli.run("import", "--format", "trackman", exp, "--out", out, "--impact-offset-positive", "heel")
    with pytest.warns(sg.SmashWarning, match="average row"):
        got = sg.read_export(exp, "trackman", impact_offset_positive="heel")
    want = read_cli_csv(out)
    assert len(got) == 3
    assert_same_table(got, want)
    # And the shots predict as the CLI predicts the export read with --format.
    pred = tmp_path / "pred.csv"
    cli.run("predict", "--club", PAPER_DRIVER, "--shots", exp, "--format", "trackman",
            "--impact-offset-positive", "heel", "--out", pred)
    assert_same_table(
        sg.predict(PAPER_DRIVER, exp, format="trackman", impact_offset_positive="heel"),
        read_cli_csv(pred),
        rtol=1e-12,
    )


def test_read_export_refuses_as_the_cli(cli, tmp_path):
    exp = tmp_path / "session.csv"
    exp.write_bytes(TRACKMAN.encode("utf-8"))
    want = cli.error("import", "--format", "trackman", exp, "--out", tmp_path / "s.csv")
    with pytest.raises(sg.SmashError) as e:
        sg.read_export(exp, "trackman")
    assert str(e.value) == want


def test_effect_library_lists_parameters_with_units():
    lib = {e["name"]: e for e in sg.effect_library()}
    assert "added_mass" in lib and "ball_offset" in lib
    (dm,) = lib["added_mass"]["params"]
    assert dm["key"] == "dm_g" and dm["unit"] == "g"
    assert dm["lower"] <= dm["default"] <= dm["upper"]


def test_synth_matches_cli(cli, tmp_path, paper_world):
    shots, truth = sg.synth(ROOT / "configs" / "synth" / "paper_world.toml")
    assert_same_table(shots, read_cli_csv(paper_world))
    assert "added_mass" in truth
    other, _ = sg.synth(ROOT / "configs" / "synth" / "paper_world.toml", seed=7)
    assert not other["ball_speed_mph"].equals(shots["ball_speed_mph"])


def test_run_study_reads_the_cli_tables(cli, tmp_path):
    study = ROOT / "configs" / "studies" / "com_sweep.toml"
    out = tmp_path / "cli"
    cli.run("run", study, "--out", out)
    got = sg.run_study(study)
    want = {p.relative_to(out).with_suffix("").as_posix(): read_cli_csv(p)
            for p in sorted(out.rglob("*.csv"))}
    assert want and list(got) == list(want)
    for k in want:
        assert_same_table(got[k], want[k])
