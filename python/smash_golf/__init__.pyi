"""Type stubs of smash_golf. Units: speeds mph, angles deg, spin rpm, impact locations mm,
masses g, flight distances yd, times s (the shots-file conventions, docs/conventions.md)."""

import os
from typing import Any, Dict, List, Optional, Sequence, Tuple, TypedDict, Union

import pandas as pd

_Path = Union[str, os.PathLike[str]]
ClubLike = Union[_Path, "Club"]
TableLike = Union[_Path, pd.DataFrame]

class SmashError(Exception):
    """The CLI's one-line error message (file, line, column or key, what was wrong, what is
    allowed)."""

class SmashWarning(UserWarning):
    """A CLI warning line or an import note."""

class EffectEntry(TypedDict):
    name: str
    group: Optional[str]
    params: Dict[str, float]
    """Parameter key -> value in the unit the key names (dm_g: g, dy_mm: mm, deg: deg, ...)."""

class ParamSpec(TypedDict):
    key: str
    unit: str
    default: float
    lower: float
    upper: float
    plausible: Tuple[float, float]
    doc: str

class EffectSpec(TypedDict):
    name: str
    params: List[ParamSpec]

class Club:
    """A club: clubhead, ball and effects (a club file held in memory)."""

    @staticmethod
    def load(path: _Path) -> Club:
        """Read a club file (TOML) as `smash --club PATH` does."""
    @staticmethod
    def from_toml(text: str, label: str = "<club>") -> Club:
        """A club from club-file text; `label` names it in messages."""
    @property
    def name(self) -> str: ...
    @property
    def label(self) -> str: ...
    @property
    def effects(self) -> List[EffectEntry]: ...
    def with_effect(self, name: str, group: Optional[str] = None, **params: float) -> Club:
        """This club plus one effect, parameters by key in their units (e.g. dm_g=2.5, grams)."""
    def without_effects(self) -> Club: ...
    def to_toml(self, comment: str = "") -> str:
        """Club-file text that reads back to this club bit for bit."""

def effect_library() -> List[EffectSpec]:
    """The library's effects with their parameters' keys, units, neutral values and bounds."""

def load_effect_defs(path: _Path) -> List[str]:
    """Register user-defined effects ([[define_effect]] tables); returns their names."""

def predict(
    club: ClubLike,
    shots: TableLike,
    *,
    format: Optional[str] = None,
    impact_offset_positive: Optional[str] = None,
    ignore_unknown_columns: bool = False,
) -> pd.DataFrame:
    """`smash predict`: input columns, pred_ball_speed_mph (mph), pred_launch_angle_deg (deg),
    pred_azimuth_deg (deg), pred_backspin_rpm (rpm), pred_sidespin_rpm (rpm),
    pred_smash_factor (1), err_* (predicted - measured) where measured. Each row keeps the
    index label of its input row; rows left out (a NaN delivery cell) are absent, so assigning
    a column back to the input aligns by label (NaN there)."""

def flight(
    launch: TableLike,
    *,
    columns: Optional[str] = None,
    aero: Optional[str] = None,
    spin_decay: Optional[str] = None,
    atmosphere: Optional[_Path] = None,
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
    """`smash flight`: input columns, pred_carry_yd (yd), pred_offline_yd (yd, + right),
    pred_apex_yd (yd), pred_flight_time_s (s), pred_land_angle_deg (deg)
    [, pred_total_yd (yd)], err_* where measured."""

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
    """`smash compare --json` as a dict (tables as DataFrames), plus "text"."""

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
    """`smash calibrate --json` as a dict (tables as DataFrames), plus "club": the calibrated
    Club."""

def diagnose(
    club: ClubLike,
    shots: TableLike,
    noise: Optional[_Path] = None,
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
    """`smash diagnose --json` as a dict (tables as DataFrames), plus "club": the club with the
    selected effects."""

def read_export(
    path: _Path,
    format: str,
    *,
    impact_offset_positive: Optional[str] = None,
    ignore_unknown_columns: bool = False,
) -> pd.DataFrame:
    """`smash import`: the export as a shots table (mph, deg, rpm, mm)."""

def run_study(
    study: _Path, *, out_dir: Optional[_Path] = None, format: Optional[str] = None
) -> Dict[str, pd.DataFrame]:
    """`smash run`: every CSV table of the study's output, keyed by its path without .csv."""

def synth(config: _Path, *, seed: Optional[int] = None) -> Tuple[pd.DataFrame, str]:
    """`smash synth`: the world's shots (mph, deg, rpm, mm) and its truth file's text."""
