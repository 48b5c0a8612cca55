"""smash for Python: the golf clubhead-ball impact engine over pandas DataFrames.

Every function returns exactly what the ``smash`` command line computes for the same inputs:
both fill the same settings of the library's commands (``smash::app``) and call the same
``run``, so the checks and the one-line error messages are the same (raised as
:class:`SmashError`); the reports come back as Python objects, not as text to parse. Units are
those of the shots file (``docs/conventions.md``): speeds in mph, angles in degrees, spin in
rpm, impact locations in mm, distances in yards.

A DataFrame goes to the library as CSV text (no file is written): floats are written with
their shortest round-trip decimal and read back with pandas' round-trip parser, so no number
changes on the way. A path instead of a DataFrame is read exactly as the CLI reads it.

compare, calibrate and diagnose first check the shots against the club (loft, speed, club names)
and raise the CLI's refusal for shots of another club; ``ignore_club_mismatch=True`` runs them
anyway, and the report then has no findings and says why under ``"club_mismatch"``.

Long work (diagnose, calibrate, flight, studies) releases the GIL and runs on rayon's worker
threads; in a notebook, diagnose and calibrate show a tqdm progress bar when tqdm is installed.
"""

from __future__ import annotations

import csv as _csv
import io
import os
import tempfile
import warnings
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import pandas as pd

from . import _native
from ._native import Club, SmashError, effect_library, load_effect_defs

__all__ = [
    "Club",
    "SmashError",
    "SmashWarning",
    "calibrate",
    "compare",
    "diagnose",
    "effect_library",
    "flight",
    "load_effect_defs",
    "predict",
    "read_export",
    "run_study",
    "synth",
]

ClubLike = Union[str, "os.PathLike[str]", Club]
TableLike = Union[str, "os.PathLike[str]", pd.DataFrame]

# Columns that hold names, not numbers: kept as text when a CSV comes back.
_TEXT_COLUMNS = ("shot_id", "group", "golfer")

# Reading floats exactly as written: pandas before 3 needs the round-trip parser asked for;
# from 3 on it is the default (and the argument is deprecated).
_EXACT_FLOATS: Dict[str, Any] = (
    {} if int(pd.__version__.split(".")[0]) >= 3 else {"float_precision": "round_trip"}
)


class SmashWarning(UserWarning):
    """A warning of smash (the lines the CLI prints as ``warning: …`` or import notes)."""


def _club(club: ClubLike) -> Club:
    return club if isinstance(club, Club) else Club.load(os.fspath(club))


def _table(shots: TableLike, what: str) -> Dict[str, Any]:
    """Keyword arguments naming a table for the native functions."""
    if isinstance(shots, pd.DataFrame):
        text = shots.to_csv(index=False, lineterminator="\n")
        return {"shots_csv": text.encode("utf-8"), "label": f"<{what} DataFrame>"}
    if isinstance(shots, (str, os.PathLike)):
        return {"shots_path": os.fspath(shots)}
    raise TypeError(f"{what}: expected a pandas DataFrame or a path, got {type(shots).__name__}")


def _read_csv(data: bytes) -> pd.DataFrame:
    """A CSV the library wrote, every float exactly as written."""
    head = data.split(b"\n", 1)[0].decode("utf-8").split(",")
    dtype = {c: str for c in _TEXT_COLUMNS if c in head}
    return pd.read_csv(
        io.BytesIO(data),
        **_EXACT_FLOATS,
        dtype=dtype,
        keep_default_na=False,
        na_values=[""],
    )


def _record_positions(text: str) -> Dict[int, int]:
    """For a CSV with a header line: the line where each data record starts (1-based, as the
    library counts lines) → the record's position among the data rows, blank lines skipped (as
    ``pd.read_csv`` skips them). A quoted cell may span lines."""
    reader = _csv.reader(io.StringIO(text, newline=""))
    positions: Dict[int, int] = {}
    previous = 0
    header = True
    for record in reader:
        start, previous = previous + 1, reader.line_num
        if not record:
            continue
        if header:
            header = False
            continue
        positions[start] = len(positions)
    return positions


def _with_input_index(frame: pd.DataFrame, index: Optional[pd.Index], text: str,
                      lines: Sequence[int]) -> pd.DataFrame:
    """``frame`` (one row per predicted shot, ``lines`` the line of ``text`` where each shot's
    row starts) with the index labels of the input rows they came from (``index``; ``None``:
    the rows' positions, as ``pd.read_csv`` numbers them)."""
    positions = _record_positions(text)
    if index is None:
        index = pd.RangeIndex(len(positions))
    frame.index = index.take([positions[line] for line in lines])
    return frame


def _settings(**options: Any) -> Dict[str, Any]:
    """A command's settings from keyword options: None is left out (the setting's default), a
    path becomes its string, a tuple a list. The library checks every value and names the
    setting it refuses."""
    out: Dict[str, Any] = {}
    for name, value in options.items():
        if value is None:
            continue
        if isinstance(value, os.PathLike):
            value = os.fspath(value)
        elif isinstance(value, tuple):
            value = list(value)
        out[name] = value
    return out


def _warn(lines: Sequence[str]) -> None:
    for line in lines:
        warnings.warn(line, SmashWarning, stacklevel=3)


def _error_table(t: Dict[str, Dict[str, Dict[str, float]]]) -> pd.DataFrame:
    """``{group: {component: {"mean", "std"}}}`` as a DataFrame: a row per group, columns
    (component, statistic)."""
    rows = {
        g: {(c, s): v for c, stats in comps.items() for s, v in stats.items()}
        for g, comps in t.items()
    }
    df = pd.DataFrame.from_dict(rows, orient="index")
    df.columns = pd.MultiIndex.from_tuples(df.columns, names=["component", "statistic"])
    df.index.name = "group"
    return df


def _with_tables(report: Dict[str, Any]) -> Dict[str, Any]:
    """The JSON report with its tables as DataFrames: lists of records, and the error tables
    (``before``, ``after``)."""
    out: Dict[str, Any] = {}
    for key, value in report.items():
        if isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
            out[key] = pd.DataFrame.from_records(value)
        elif key in ("before", "after") and isinstance(value, dict):
            out[key] = _error_table(value)
        else:
            out[key] = value
    return out


def _format_settings(
    format: Optional[str], impact_offset_positive: Optional[str], ignore_unknown_columns: bool
) -> Dict[str, Any]:
    return _settings(
        format=format,
        impact_offset_positive=impact_offset_positive,
        ignore_unknown_columns=ignore_unknown_columns,
    )


class _Bar:
    """A tqdm bar (tqdm.auto: a widget in a notebook, text in a terminal) fed by the native
    progress callbacks, or nothing when tqdm is not installed."""

    def __init__(self, what: str) -> None:
        try:
            from tqdm.auto import tqdm
        except ImportError:
            self._bar = None
            return
        self._bar = tqdm(total=None, desc=what, leave=False)

    # diagnose
    def step(self, step: int, jobs: int) -> None:
        if self._bar is not None:
            self._bar.reset(total=jobs)
            self._bar.set_description(f"fits of step {step}")

    def job_done(self) -> None:
        if self._bar is not None:
            self._bar.update(1)

    # calibrate
    def iteration(self, stage: str, it: int, chi2: float, lambda_: float, evaluations: int) -> None:
        if self._bar is not None:
            self._bar.set_description(stage)
            self._bar.set_postfix(iter=it, chi2=f"{chi2:.6e}", evaluations=evaluations)
            self._bar.update(1)

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()


def _progress(progress: Any, what: str) -> Any:
    if progress is True:
        return _Bar(what)
    if progress is False or progress is None:
        return None
    return progress


def predict(
    club: ClubLike,
    shots: TableLike,
    *,
    format: Optional[str] = None,
    impact_offset_positive: Optional[str] = None,
    ignore_unknown_columns: bool = False,
) -> pd.DataFrame:
    """Predict the launch of every shot, as ``smash predict --shots … --out …``.

    ``club``: a :class:`Club` or a club file. ``shots``: a DataFrame in the shots-file columns
    (``shot_id``, ``club_speed_mph``, ``attack_angle_deg``, ``club_path_deg``,
    ``dynamic_loft_deg``, ``face_angle_deg``, ``impact_y_mm``, ``impact_z_mm``, …) or a path;
    ``format`` reads a launch-monitor export at a path (``trackman``, ``foresight``,
    ``flightscope``, ``uneekor`` or a mapping file).

    Returns the predictions file: the input columns, ``pred_ball_speed_mph`` (mph),
    ``pred_launch_angle_deg`` (deg), ``pred_azimuth_deg`` (deg), ``pred_backspin_rpm`` (rpm),
    ``pred_sidespin_rpm`` (rpm), ``pred_smash_factor`` (1) and, where the shots have measured
    launch, ``err_*`` = predicted − measured in the same units.

    Index: each row keeps the index label of the input row it predicts. Rows the reader leaves
    out, as the CLI does (an empty or NaN delivery cell, a value the monitor estimated), are
    absent from the result and named in a :class:`SmashWarning`; the other rows keep their
    labels, so ``df["p"] = pred["pred_ball_speed_mph"]`` aligns by label and puts NaN at the
    rows left out (never the next shot's prediction). For a shots-file path (``format`` unset
    or ``"shots"``) the labels are those ``pd.read_csv(path)`` gives (0, 1, … over the data
    rows); for an export read with ``format``, 0, 1, … over the predicted rows.
    """
    c = _club(club)
    table = _table(shots, "shots")
    csv, warns, lines = _native.predict(
        c,
        _format_settings(format, impact_offset_positive, ignore_unknown_columns),
        **table,
    )
    _warn(warns)
    out = _read_csv(csv)
    if isinstance(shots, pd.DataFrame):
        return _with_input_index(out, shots.index, table["shots_csv"].decode("utf-8"), lines)
    if format in (None, "shots"):
        text = Path(os.fspath(shots)).read_bytes().decode("utf-8", errors="replace")
        return _with_input_index(out, None, text.lstrip("\ufeff"), lines)
    return out


def flight(
    launch: TableLike,
    *,
    columns: Optional[str] = None,
    aero: Optional[str] = None,
    spin_decay: Optional[str] = None,
    atmosphere: Union[str, "os.PathLike[str]", None] = None,
    temperature_c: Optional[float] = None,
    pressure_hpa: Optional[float] = None,
    elevation_m: Optional[float] = None,
    humidity_pct: Optional[float] = None,
    wind_speed_m_s: Optional[float] = None,
    wind_direction_deg: Optional[float] = None,
    wind_height_m: Optional[float] = None,
    roughness_m: Optional[float] = None,
    total: bool = False,
    ground_restitution: Optional[float] = None,
    roll_decel_m_s2: Optional[float] = None,
    dt_s: Optional[float] = None,
    max_time_s: Optional[float] = None,
) -> pd.DataFrame:
    """Fly launch conditions to landing, as ``smash flight``.

    ``launch``: a DataFrame or CSV path with ``ball_speed_mph`` (mph), ``launch_angle_deg``
    (deg), ``backspin_rpm`` (rpm) and optionally ``azimuth_deg`` (deg), ``sidespin_rpm`` (rpm),
    or the same with ``pred_`` (what :func:`predict` returns); ``columns`` picks ``"measured"``
    or ``"predicted"`` (default: measured if present).

    Atmosphere: ``temperature_c`` (°C, default 15), ``pressure_hpa`` (hPa; default ISA at
    ``elevation_m``, m), ``humidity_pct`` (%, default 50), ``wind_speed_m_s`` (m/s at
    ``wind_height_m``, m, default 10), ``wind_direction_deg`` (deg the wind blows toward, from
    the target line to the right: 0 tailwind, 180 headwind), ``roughness_m`` (m), or an
    ``atmosphere`` TOML file (keywords override it). ``aero``: the coefficient model
    (``fmm2022`` by default); ``spin_decay``: ``moment``, ``none`` or ``exp:TAU`` (s).
    ``total``: add ``pred_total_yd`` (bounce and roll, with ``ground_restitution`` (1) and
    ``roll_decel_m_s2`` (m/s²)). ``dt_s``, ``max_time_s``: integration step and limit, s.

    Returns the input columns and ``pred_carry_yd`` (yd), ``pred_offline_yd`` (yd, + right),
    ``pred_apex_yd`` (yd), ``pred_flight_time_s`` (s), ``pred_land_angle_deg`` (deg)
    [, ``pred_total_yd`` (yd)], and ``err_*`` where the table has measured flight columns.
    """
    settings = _settings(
        launch=columns,
        aero=aero,
        spin_decay=spin_decay,
        atmosphere=atmosphere,
        temperature_c=temperature_c,
        pressure_hpa=pressure_hpa,
        elevation_m=elevation_m,
        humidity_pct=humidity_pct,
        wind_speed_m_s=wind_speed_m_s,
        wind_direction_deg=wind_direction_deg,
        wind_height_m=wind_height_m,
        roughness_m=roughness_m,
        total=total,
        ground_restitution=ground_restitution,
        roll_decel_m_s2=roll_decel_m_s2,
        dt_s=dt_s,
        max_time_s=max_time_s,
    )
    return _read_csv(_native.flight(settings, **_table(launch, "launch")))


def compare(
    club: ClubLike,
    shots: TableLike,
    *,
    alpha: Optional[float] = None,
    bin_mm: Optional[float] = None,
    min_bin_count: Optional[int] = None,
    impact_noise_mm: Optional[Tuple[float, float]] = None,
    format: Optional[str] = None,
    impact_offset_positive: Optional[str] = None,
    ignore_unknown_columns: bool = False,
    ignore_club_mismatch: bool = False,
    tables: bool = True,
) -> Dict[str, Any]:
    """Compare the model with measured launch, as ``smash compare --json``.

    ``alpha``: significance level (default 0.01); ``bin_mm``: face-map bin, mm (default 5);
    ``min_bin_count``: fewest shots a bin reports (default 5); ``impact_noise_mm``: 1σ noise of
    the measured impact location, mm, (vertical, heel–toe).

    Returns the ``--json`` report as a dict (with ``tables``, its lists of records and error
    tables as DataFrames) and its text report under ``"text"``.
    """
    settings = _settings(
        alpha=alpha,
        bin_mm=bin_mm,
        min_bin_count=min_bin_count,
        impact_noise_mm=impact_noise_mm,
        ignore_club_mismatch=ignore_club_mismatch,
        **_format_settings(format, impact_offset_positive, ignore_unknown_columns),
    )
    out, text, warns = _native.compare(_club(club), settings, **_table(shots, "shots"))
    _warn(warns)
    out = _with_tables(out) if tables else out
    out["text"] = text
    return out


def calibrate(
    club: ClubLike,
    shots: TableLike,
    effects: Union[str, Sequence[str]],
    *,
    method: Optional[str] = None,
    max_iters: Optional[int] = None,
    impact_noise_mm: Optional[Tuple[float, float]] = None,
    delivery_noise: Optional[str] = None,
    format: Optional[str] = None,
    impact_offset_positive: Optional[str] = None,
    ignore_unknown_columns: bool = False,
    ignore_club_mismatch: bool = False,
    progress: Any = True,
    tables: bool = True,
) -> Dict[str, Any]:
    """Fit effects' parameters to measured launch, as ``smash calibrate --json``.

    ``effects``: e.g. ``"added_mass@group,ball_offset"`` or a list of such names; ``method``:
    ``"lm"`` (default) or ``"paper"``; ``impact_noise_mm``: (vertical, heel–toe) 1σ, mm;
    ``delivery_noise``: as ``--delivery-noise``.

    Returns the ``--json`` report as a dict (parameter values in the units their ``unit`` names,
    with standard errors; χ², AIC, BIC, error tables before and after; with ``tables``, the
    lists of records and error tables as DataFrames) and the calibrated :class:`Club` under
    ``"club"`` (what ``--out-club`` writes).
    """
    if not isinstance(effects, str):
        effects = ",".join(effects)
    settings = _settings(
        effects=effects,
        ignore_club_mismatch=ignore_club_mismatch,
        method=method,
        max_iters=max_iters,
        impact_noise_mm=impact_noise_mm,
        delivery_noise=delivery_noise,
        **_format_settings(format, impact_offset_positive, ignore_unknown_columns),
    )
    bar = _progress(progress, "calibrate")
    try:
        out, calibrated, warns = _native.calibrate(
            _club(club), settings, progress=bar, **_table(shots, "shots")
        )
    finally:
        if isinstance(bar, _Bar):
            bar.close()
    _warn(warns)
    out = _with_tables(out) if tables else out
    out["club"] = calibrated
    return out


def diagnose(
    club: ClubLike,
    shots: TableLike,
    noise: Union[str, "os.PathLike[str]", None] = None,
    *,
    instrument: Optional[str] = None,
    folds: Optional[int] = None,
    max_steps: Optional[int] = None,
    candidates: Union[str, Sequence[str], None] = None,
    max_iters: Optional[int] = None,
    impact_noise_mm: Optional[Tuple[float, float]] = None,
    exact_impact_locations: bool = False,
    format: Optional[str] = None,
    impact_offset_positive: Optional[str] = None,
    ignore_unknown_columns: bool = False,
    ignore_club_mismatch: bool = False,
    progress: Any = True,
    tables: bool = True,
) -> Dict[str, Any]:
    """Find the missing physics, as ``smash diagnose --json``: rank the library's effects by
    how much each explains (cross-validated by golfer) and select them forward.

    ``noise``: an instrument noise file (``--noise``); ``instrument``: ``"camera"`` or
    ``"radar"``; ``folds`` (default 5), ``max_steps`` (default 10), ``candidates`` (effect list;
    default every library effect), ``max_iters`` (per fit, default 100); ``impact_noise_mm``:
    (vertical, heel–toe) 1σ, mm, or ``exact_impact_locations``.

    Returns the ``--json`` report as a dict (``selected``, ``estimates``, ``steps``, noise
    floor, error tables; with ``tables``, lists of records and error tables as DataFrames) and
    the club with the selected effects under ``"club"`` (what ``--out-club`` writes).

    Ctrl-C stops the run within a fraction of a second (the fits in progress finish, no other
    starts) and raises ``KeyboardInterrupt``.
    """
    if candidates is not None and not isinstance(candidates, str):
        candidates = ",".join(candidates)
    settings = _settings(
        noise=noise,
        ignore_club_mismatch=ignore_club_mismatch,
        instrument=instrument,
        folds=folds,
        max_steps=max_steps,
        candidates=candidates,
        max_iters=max_iters,
        impact_noise_mm=impact_noise_mm,
        exact_impact_locations=exact_impact_locations,
        **_format_settings(format, impact_offset_positive, ignore_unknown_columns),
    )
    bar = _progress(progress, "diagnose")
    try:
        out, selected, warns = _native.diagnose(
            _club(club), settings, progress=bar, **_table(shots, "shots")
        )
    finally:
        if isinstance(bar, _Bar):
            bar.close()
    _warn(warns)
    out = _with_tables(out) if tables else out
    out["club"] = selected
    return out


def read_export(
    path: Union[str, "os.PathLike[str]"],
    format: str,
    *,
    impact_offset_positive: Optional[str] = None,
    ignore_unknown_columns: bool = False,
) -> pd.DataFrame:
    """Convert a launch-monitor export to a shots table, as ``smash import``.

    ``format``: ``trackman``, ``foresight``, ``flightscope``, ``uneekor`` or a mapping file
    (TOML); ``impact_offset_positive``: ``"toe"`` or ``"heel"`` where the vendor does not say.
    Returns the shots table in the shots-file columns and units (mph, deg, rpm, mm); the
    import's notes (skipped rows, assumed units) are issued as :class:`SmashWarning`.
    """
    csv, notes = _native.read_export(
        os.fspath(path), _format_settings(format, impact_offset_positive, ignore_unknown_columns)
    )
    _warn(notes)
    return _read_csv(csv)


def run_study(
    study: Union[str, "os.PathLike[str]"],
    *,
    out_dir: Union[str, "os.PathLike[str]", None] = None,
    format: Optional[str] = None,
) -> Dict[str, pd.DataFrame]:
    """Run a design study, as ``smash run STUDY --out DIR``, and read its tables back.

    ``study``: a study file (TOML), or the text of one (its relative paths are then relative to
    the current directory). The files are written to ``out_dir`` (default: a temporary folder,
    removed afterwards); the CLI's summary goes to the process's standard output.

    Returns every CSV table of the output folder as a DataFrame, keyed by its path inside the
    folder without ``.csv`` (``"summary"``, ``"maps_long"``, …), columns in the units their
    names carry.
    """
    tmp_study = None
    if isinstance(study, str) and "\n" in study:
        tmp_study = tempfile.NamedTemporaryFile(
            "w", suffix=".toml", dir=".", prefix=".smash_study_", delete=False
        )
        with tmp_study:
            tmp_study.write(study)
        study = tmp_study.name
    try:
        if out_dir is not None:
            return _run_into(study, Path(out_dir), format)
        with tempfile.TemporaryDirectory(prefix="smash_study_") as d:
            return _run_into(study, Path(d) / "out", format)
    finally:
        if tmp_study is not None:
            os.unlink(tmp_study.name)


def _run_into(
    study: Union[str, "os.PathLike[str]"], out: Path, format: Optional[str]
) -> Dict[str, pd.DataFrame]:
    print(_native.run_study(os.fspath(study), os.fspath(out), format), end="")
    tables: Dict[str, pd.DataFrame] = {}
    for path in sorted(out.rglob("*.csv")):
        key = path.relative_to(out).with_suffix("").as_posix()
        tables[key] = _read_csv(path.read_bytes())
    return tables


def synth(
    config: Union[str, "os.PathLike[str]"], *, seed: Optional[int] = None
) -> Tuple[pd.DataFrame, str]:
    """Generate a synthetic experiment, as ``smash synth --config CONFIG --truth …``.

    ``config``: a world configuration (e.g. ``configs/synth/paper_world.toml``); ``seed``
    replaces its seed. Returns the shots (deliveries and measured launch, in the shots-file
    columns and units) and the truth file's text (the hidden effects and their parameters).
    """
    csv, truth = _native.synth(os.fspath(config), seed)
    return _read_csv(csv), truth
