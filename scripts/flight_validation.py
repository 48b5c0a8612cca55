#!/usr/bin/env python3
"""Validate smash's flight models on real shots: a TrackMan export in, a held-out report out.

Usage:
    python3 scripts/flight_validation.py EXPORT.csv [EXPORT2.csv ...] [--smash PATH] [--out DIR]

Each export is a TrackMan "normalized" CSV (the `sep=,` line, a header, a units row; the
columns Ball Speed, Launch Angle, Launch Direction, Spin Rate, Spin Axis and Carry Flat -
Length, Carry Flat - Side, Carry Flat - Land. Angle, Max Height - Height). The script

1. reads every shot with a measured launch and carry, and its session (the export file and the
   shot's date, day resolution); no name, e-mail or player column is written anywhere;
2. sorts each shot into a club class (driver, wood/hybrid, iron, wedge) by its Club cell and
   into "outdoor" (the ball was tracked to at least 80 % of its carry: `Last data Point -
   Length`) or "indoor" (TrackMan's own flight model supplies the carry);
3. splits the sessions into a fit/choose part and a held-out part by the parity of the first
   byte of the SHA-256 of the session key (fixed before any model was flown, independent of
   the results);
4. flies both parts with every built-in aero model (`smash flight --json`, the launch columns
   as measured, the export's stated normalization conditions: 77 °F at sea level unless
   --temperature-c / --elevation-m are given), and prints the per-class median and 90th
   percentile of |carry error| in %, the bias in % and the RMSE in yards, indoor and outdoor
   apart.

Only standard-library Python. The held-out figures are the ones to report; the fit/choose
part is what a choice of model may look at.
"""

import argparse
import csv
import hashlib
import json
import math
import os
import subprocess
import sys
import tempfile

MODELS = ["fmm2022", "fmm2022-tour", "fmm2022-re", "nathan-lyu"]
CLASSES = ["driver", "wood/hybrid", "iron", "wedge"]


def club_class(club):
    """The class of a TrackMan Club cell, or None for putters and unknown clubs."""
    c = club.strip().lower()
    if "driver" in c or c in ("dr", "1w"):
        return "driver"
    if "wood" in c or "hybrid" in c or c.endswith("w") and c[:-1].isdigit() or c.endswith("h"):
        return "wood/hybrid"
    if "wedge" in c or c in ("pw", "gw", "sw", "lw", "aw") or c.endswith("°"):
        return "wedge"
    if "iron" in c or (c.endswith("i") and c[:-1].isdigit()):
        return "iron"
    return None


def number(cell):
    try:
        x = float(cell.strip().strip('"'))
    except (ValueError, AttributeError):
        return None
    return x if math.isfinite(x) else None


def read_export(path):
    """Shots of one export: dicts with launch, measured flight, class, session, place."""
    with open(path, encoding="utf-8-sig", newline="") as f:
        lines = f.read().lstrip("\ufeff").splitlines()
    while lines and lines[0].lstrip("\ufeff").startswith("sep="):
        lines = lines[1:]
    rows = list(csv.reader(lines))
    if not rows:
        return []
    head = [h.strip() for h in rows[0]]
    body = rows[1:]
    if body and not any(number(c) for c in body[0]):
        body = body[1:]  # units row
    col = {h: i for i, h in enumerate(head)}

    def get(row, name):
        i = col.get(name)
        return number(row[i]) if i is not None and i < len(row) else None

    shots = []
    for row in body:
        club = row[col["Club"]] if "Club" in col and col["Club"] < len(row) else ""
        cls = club_class(club)
        speed, launch = get(row, "Ball Speed"), get(row, "Launch Angle")
        spin, axis = get(row, "Spin Rate"), get(row, "Spin Axis")
        carry = get(row, "Carry Flat - Length")
        if cls is None or None in (speed, launch, spin, carry) or speed <= 0 or carry <= 0:
            continue
        axis = axis or 0.0
        date = row[col["Date"]][:10] if "Date" in col and col["Date"] < len(row) else ""
        tracked = get(row, "Last data Point - Length")
        outdoor = tracked is not None and tracked >= 0.8 * carry
        shots.append(
            {
                "class": cls,
                "session": f"{os.path.basename(path)}|{date}",
                "place": "outdoor" if outdoor else "indoor",
                "ball_speed_mph": speed,
                "launch_angle_deg": launch,
                "azimuth_deg": get(row, "Launch Direction") or 0.0,
                # Spin axis tilt (+ right): backspin and sidespin components.
                "backspin_rpm": spin * math.cos(math.radians(axis)),
                "sidespin_rpm": spin * math.sin(math.radians(axis)),
                "carry_yd": carry,
                "offline_yd": get(row, "Carry Flat - Side"),
                "apex_yd": (lambda h: h / 3.0 if h is not None else None)(
                    get(row, "Max Height - Height")
                ),
                "land_angle_deg": get(row, "Carry Flat - Land. Angle"),
            }
        )
    return shots


def held_out(session):
    return hashlib.sha256(session.encode()).digest()[0] % 2 == 1


COLUMNS = [
    "shot_id",
    "group",
    "ball_speed_mph",
    "launch_angle_deg",
    "azimuth_deg",
    "backspin_rpm",
    "sidespin_rpm",
    "carry_yd",
    "offline_yd",
    "apex_yd",
    "land_angle_deg",
]


def write_launch(path, shots):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(COLUMNS)
        for k, s in enumerate(shots):
            cells = [f"s{k}", s["class"]]
            for c in COLUMNS[2:]:
                v = s[c]
                cells.append("" if v is None else repr(float(v)))
            w.writerow(cells)


def fly(smash, launch, model, extra):
    out = launch + f".{model}.out.csv"
    cmd = [smash, "flight", "--shots", launch, "--out", out, "--aero", model, "--json"] + extra
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"{' '.join(cmd)}: {r.stderr.strip()}")
    return json.loads(r.stdout)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("exports", nargs="+")
    ap.add_argument("--smash", default="smash")
    ap.add_argument("--temperature-c", default="25")
    ap.add_argument("--elevation-m", default="0")
    a = ap.parse_args()
    shots = [s for p in a.exports for s in read_export(p)]
    if not shots:
        sys.exit("no shot with a measured launch and carry")
    extra = ["--temperature-c", a.temperature_c, "--elevation-m", a.elevation_m]
    with tempfile.TemporaryDirectory() as d:
        for part in ["fit", "held-out"]:
            for place in ["outdoor", "indoor"]:
                sel = [
                    s
                    for s in shots
                    if (held_out(s["session"]) == (part == "held-out")) and s["place"] == place
                ]
                if not sel:
                    continue
                sessions = len({s["session"] for s in sel})
                print(f"\n## {part}, {place}: {len(sel)} shots, {sessions} sessions\n")
                print("| model | class | n | median % | P90 % | bias % | RMSE yd |")
                print("|---|---|---|---|---|---|---|")
                launch = os.path.join(d, f"{part}-{place}.csv")
                write_launch(launch, sel)
                for m in MODELS:
                    rows = fly(a.smash, launch, m, extra)["rows"]
                    for r in rows:
                        carry = dict(r["errors"]).get("carry_yd")
                        if carry is None:
                            continue
                        print(
                            f"| {m} | {r['group']} | {carry['n']} | {carry['median_abs_pct']:.2f}"
                            f" | {carry['p90_abs_pct']:.2f} | {carry['bias_pct']:+.2f}"
                            f" | {carry['rmse']:.2f} |"
                        )


if __name__ == "__main__":
    main()
