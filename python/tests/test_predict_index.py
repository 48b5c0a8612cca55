"""predict keeps the input's index (issue 41, item 5): a row the reader leaves out (a NaN
delivery cell) must not shift the predictions of the rows after it."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

import smash_golf as sg
from conftest import ROOT, read_cli_csv

GOLDEN = ROOT / "tests" / "data" / "golden"
PAPER_DRIVER = ROOT / "configs" / "clubs" / "paper_driver.toml"
PRED = "pred_ball_speed_mph"


def _golden() -> pd.DataFrame:
    df = read_cli_csv(GOLDEN / "nominal.csv")
    return df[[c for c in df.columns if not c.startswith("pred_")]]


def test_a_row_left_out_keeps_the_other_rows_labels(cli, tmp_path):
    whole = _golden()
    whole.index = pd.Index([f"shot-{i}" for i in range(len(whole))], name="label")
    want = sg.predict(PAPER_DRIVER, whole)
    # Every row predicted: the labels are the input's, in order.
    assert list(want.index) == list(whole.index)

    df = whole.copy()
    df.loc["shot-3", "club_speed_mph"] = np.nan
    with pytest.warns(sg.SmashWarning, match="left out 1 of"):
        pred = sg.predict(PAPER_DRIVER, df)
    assert len(pred) == len(df) - 1
    assert list(pred.index) == [label for label in df.index if label != "shot-3"]
    assert pred.index.name == "label"
    # Each shot has its own prediction, not the next shot's.
    np.testing.assert_array_equal(pred[PRED].to_numpy(), want.loc[pred.index, PRED].to_numpy())
    assert (pred["shot_id"] == df.loc[pred.index, "shot_id"]).all()

    # The pandas idiom aligns by label: NaN at the row left out, the rest in place.
    df["p"] = pred[PRED]
    assert np.isnan(df.loc["shot-3", "p"])
    kept = df.index != "shot-3"
    np.testing.assert_array_equal(df.loc[kept, "p"].to_numpy(), want.loc[kept, PRED].to_numpy())

    # The same numbers as the CLI's predictions file, which lists the kept rows in order.
    path = tmp_path / "with_gap.csv"
    df.drop(columns=["p"]).to_csv(path, index=False)
    out = tmp_path / "pred.csv"
    cli.run("predict", "--club", PAPER_DRIVER, "--shots", path, "--out", out)
    np.testing.assert_array_equal(pred[PRED].to_numpy(), read_cli_csv(out)[PRED].to_numpy())


def test_a_path_gets_the_labels_read_csv_gives(tmp_path):
    df = _golden()
    df.loc[5, "dynamic_loft_deg"] = np.nan
    path = tmp_path / "with_gap.csv"
    df.to_csv(path, index=False)
    # (A path's left-out note goes to stderr, as the CLI's does.)
    pred = sg.predict(PAPER_DRIVER, path)
    read = pd.read_csv(path)
    assert list(pred.index) == [i for i in read.index if i != 5]
    read["p"] = pred[PRED]
    assert np.isnan(read.loc[5, "p"])
    assert read["p"].notna().sum() == len(read) - 1


def test_a_default_index_with_a_gap_stays_aligned():
    # A frame already filtered (index 0, 2, 4, …), as after df[df.club == "driver"].
    df = _golden().iloc[::2].copy()
    df.loc[df.index[1], "face_angle_deg"] = np.nan
    with pytest.warns(sg.SmashWarning):
        pred = sg.predict(PAPER_DRIVER, df)
    assert list(pred.index) == [i for i in df.index if i != df.index[1]]
    assert (pred["shot_id"] == df.loc[pred.index, "shot_id"]).all()

