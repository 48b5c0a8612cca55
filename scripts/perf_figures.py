#!/usr/bin/env python3
"""Regenerate the figures of docs/performance.md from measurements on this machine.

What it does, in order:

1. reads the CPU model, core count and instruction sets (`/proc/cpuinfo`) and the load average;
2. with `--bench`, runs `cargo bench --bench flight`, `--bench diagnose` and `--bench study`
   (criterion; about 15 minutes on two cores), else uses the last results criterion left in
   `target/criterion/`;
3. times the whole-process commands a user runs, with the release binary `target/release/smash`
   (built first with `cargo build --release -p smash-cli`): `smash flight` on 200,000 drives,
   `smash diagnose` on the 600-shot paper world and on the 2,200-shot real-format season (with
   and without `added_mass`; without it `shaft_fraction` is offered, not selected: the export
   has no shaft column), on the 2,244-shot shaft-fitting season (three shafts, their masses
   joined by club: `shaft_fraction` and nine more effects selected, checked on the run's JSON),
   and a diagnose of the power-law COR world with `cor_power` against one with the
   user-defined `my_cor_power` (`tests/data/my_cor_power.toml`, offered `--without cor_power`);
   with `--libgolf DIR` (a checkout of https://github.com/gdifiore/libgolf, GPL-3.0, not part of
   this project), it also builds libgolf's shot runner (`tools/calibration/sim_runner.cpp`) with
   g++ -O3 and times it on the first 20,000 of the same drives, so that smash's flight rate is
   compared with it in the same run on the same machine;
4. rewrites the block between `<!-- perf:begin -->` and `<!-- perf:end -->` in docs/performance.md
   (the README links to that page).

Each whole-process figure is the median of `--runs` runs (default 3), wall and CPU (user + sys)
from `os.wait4`. Nothing is copied from an earlier run: a figure that could not be measured is
written as "not measured" with the reason.

Usage: python3 scripts/perf_figures.py [--bench] [--runs N] [--libgolf DIR] [--dry-run]
"""

import argparse
import csv
import json
import os
import random
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SMASH = ROOT / "target" / "release" / "smash"
CLUB = "configs/clubs/paper_driver.toml"
BEGIN, END = "<!-- perf:begin -->", "<!-- perf:end -->"


def cpu():
    info = Path("/proc/cpuinfo").read_text()
    model = re.search(r"model name\s*:\s*(.*)", info).group(1).strip()
    flags = re.search(r"flags\s*:\s*(.*)", info).group(1).split()
    isa = "AVX-512F" if "avx512f" in flags else ("AVX2" if "avx2" in flags else "no AVX2")
    return f"{model}, {os.cpu_count()} cores, {isa}"


def run(cmd, cwd, stdin_path=None):
    """Wall and CPU seconds of one run of `cmd` (which must succeed), reading `stdin_path`."""
    with open(stdin_path or os.devnull) as inp:
        t0 = time.perf_counter()
        p = subprocess.Popen(cmd, cwd=cwd, stdin=inp, stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE)
        _, status, usage = os.wait4(p.pid, 0)
        wall = time.perf_counter() - t0
    err = p.stderr.read().decode(errors="replace")
    p.stderr.close()
    if os.waitstatus_to_exitcode(status) != 0:
        raise RuntimeError(f"{' '.join(map(str, cmd))} failed:\n{err[-2000:]}")
    return wall, usage.ru_utime + usage.ru_stime


def timed(cmd, cwd, runs, stdin_path=None):
    walls, cpus = zip(*(run(cmd, cwd, stdin_path) for _ in range(runs)))
    return statistics.median(walls), statistics.median(cpus)


def criterion(group, name):
    """Median and 95 % interval (s) of a criterion bench's last run, or None."""
    slug = lambda s: re.sub(r"[^A-Za-z0-9_]+", "_", s).strip("_")
    for d in (ROOT / "target" / "criterion").glob("*"):
        if slug(d.name) != slug(group):
            continue
        for b in d.glob("*"):
            if slug(b.name) == slug(name):
                est = json.loads((b / "new" / "estimates.json").read_text())["median"]
                ci = est["confidence_interval"]
                return est["point_estimate"] / 1e9, ci["lower_bound"] / 1e9, ci["upper_bound"] / 1e9
    return None


def fmt_s(s):
    return f"{s * 1e3:.0f} ms" if s < 1 else f"{s:.2f} s"


def drives(path, n):
    rnd = random.Random(2026)
    with open(path, "w") as f:
        f.write("ball_speed_mph,launch_angle_deg,azimuth_deg,backspin_rpm,sidespin_rpm\n")
        for _ in range(n):
            f.write(
                f"{rnd.uniform(150, 180):.2f},{rnd.uniform(8, 14):.2f},{rnd.uniform(-3, 3):.2f},"
                f"{rnd.uniform(2000, 3200):.0f},{rnd.uniform(-600, 600):.0f}\n"
            )


LIBGOLF_DRIVES = 20_000


def libgolf_runner(checkout, tmp):
    """Build libgolf's `sim_runner` from a checkout with g++ -O3; its path and commit."""
    checkout = Path(checkout).resolve()
    cmake = (checkout / "CMakeLists.txt").read_text()
    version = re.search(r"project\(golf VERSION (\d+)\.(\d+)\.(\d+)", cmake)
    if version is None:
        raise RuntimeError(f"{checkout}/CMakeLists.txt: no `project(golf VERSION x.y.z`")
    gen = tmp / "libgolf_include"
    gen.mkdir()
    header = (checkout / "include" / "version.hpp.in").read_text()
    for key, value in zip(("MAJOR", "MINOR", "PATCH"), version.groups()):
        header = header.replace(f"@GOLF_VERSION_{key}@", value)
    header = header.replace("@GOLF_VERSION@", ".".join(version.groups()))
    (gen / "version.hpp").write_text(header)
    exe = tmp / "sim_runner"
    sources = sorted(str(p) for p in (checkout / "src").glob("*.cpp"))
    subprocess.run(["g++", "-O3", "-DNDEBUG", "-std=c++20", f"-I{checkout / 'include'}",
                    f"-I{gen}", *sources, str(checkout / "tools" / "calibration" / "sim_runner.cpp"),
                    "-o", str(exe)], check=True)
    commit = subprocess.run(["git", "-C", str(checkout), "rev-parse", "--short", "HEAD"],
                            capture_output=True, text=True)
    return exe, (commit.stdout.strip() if commit.returncode == 0 else "commit unknown")


def libgolf_input(drives_csv, out, n):
    """The first `n` drives in the runner's columns (its `direction_deg` is our azimuth)."""
    with open(drives_csv) as f, open(out, "w") as g:
        f.readline()
        g.write("shot_id,ball_speed_mph,launch_angle_deg,direction_deg,backspin_rpm,sidespin_rpm\n")
        for i in range(n):
            g.write(f"{i},{f.readline()}")


def real_format(s, tmp, config, name):
    """A synthetic world written as a TrackMan export (with a radar's derived face angle) and
    imported with the `trackman` preset: the world's shots and the imported shots file."""
    world = tmp / f"{name}_world.csv"
    subprocess.run([s, "synth", "--config", config, "--out", world], cwd=ROOT, check=True,
                   capture_output=True)
    tm = tmp / f"{name}_tm.csv"
    subprocess.run(["cargo", "run", "--release", "-q", "--example", "trackman_session", "--",
                    world, "cli/tests/fixtures/import/trackman_normalized.csv", CLUB, tm,
                    "--radar-face"], cwd=ROOT, check=True, capture_output=True)
    imported = tmp / f"{name}.csv"
    subprocess.run([s, "import", "--format", "trackman", tm, "--impact-offset-positive", "toe",
                    "--out", imported], cwd=ROOT, check=True, capture_output=True)
    return world, imported


def shaft_season(s, tmp):
    """The shaft-fitting season as `docs/performance-history.md` makes it, shaft masses joined."""
    world, imported = real_format(s, tmp, "configs/synth/trackman_shaft_season_world.toml",
                                  "shaft_season")
    with open(world) as f:
        mass = {r["group"]: r["shaft_mass_g"] for r in csv.DictReader(f)}
    shots = tmp / "shaft_shots.csv"
    with open(imported) as f, open(shots, "w", newline="") as g:
        rows = csv.reader(f)
        out = csv.writer(g, lineterminator="\n")
        header = next(rows)
        out.writerow(header + ["shaft_mass_g"])
        group = header.index("group")
        for row in rows:
            out.writerow(row + [mass[row[group]]])
    return shots


def measure(runs, tmp, libgolf):
    s = str(SMASH)
    rows = []
    flight_in = tmp / "drives.csv"
    drives(flight_in, 200_000)
    w, c = timed([s, "flight", "--shots", flight_in, "--out", tmp / "f.csv"], ROOT, runs)
    rate = 200_000 / w
    rows.append(("`smash flight`, 200,000 drives", w, c, f"{rate / 1e6:.2f} M drives/s", "≥ 1 M drives/s"))
    if libgolf:
        exe, commit = libgolf_runner(libgolf, tmp)
        lg_in = tmp / "libgolf_drives.csv"
        libgolf_input(flight_in, lg_in, LIBGOLF_DRIVES)
        lw, lc = timed([str(exe)], ROOT, runs, lg_in)
        lrate = LIBGOLF_DRIVES / lw
        rows.append((f"libgolf's `sim_runner` ({commit}, g++ -O3), the first 20,000 of the same drives",
                     lw, lc, f"{lrate / 1e3:.1f} k drives/s; smash {rate / lrate:.0f}× its rate",
                     "smash ≥ 100×"))
    paper = tmp / "paper.csv"
    subprocess.run([s, "synth", "--config", "configs/synth/paper_world.toml", "--out", paper],
                   cwd=ROOT, check=True, capture_output=True)
    w, c = timed([s, "diagnose", "--club", CLUB, "--shots", paper], ROOT, runs)
    rows.append(("`smash diagnose`, paper world, 600 shots", w, c, "", "≤ 0.15 s"))
    _, season = real_format(s, tmp, "configs/synth/trackman_real_scale_world.toml", "season")
    base = [s, "diagnose", "--club", CLUB, "--shots", season]
    w, c = timed(base, ROOT, runs)
    rows.append(("`smash diagnose`, real-format season, 2,200 shots", w, c, "", "≤ 10 s"))
    w, c = timed(base + ["--without", "added_mass"], ROOT, runs)
    rows.append(("the same `--without added_mass` (`shaft_fraction` offered)", w, c, "", "≤ 10 s"))
    shafts = shaft_season(s, tmp)
    diag = [s, "diagnose", "--club", CLUB, "--shots", shafts]
    report = json.loads(subprocess.run(diag + ["--json"], cwd=ROOT, check=True,
                                       capture_output=True, text=True).stdout)
    selected = report["selected"]
    if "shaft_fraction" not in selected or len(selected) < 7:
        raise RuntimeError(f"shaft-fitting season: expected shaft_fraction and six more selected, got {selected}")
    w, c = timed(diag, ROOT, runs)
    rows.append(("`smash diagnose`, shaft-fitting season, 2,244 shots", w, c,
                 f"{len(selected)} effects selected, `shaft_fraction` among them", "≤ 10 s"))
    cor = tmp / "cor_power.csv"
    subprocess.run([s, "synth", "--config", "configs/synth/cor_power_world.toml", "--out", cor],
                   cwd=ROOT, check=True, capture_output=True)
    lib = [s, "diagnose", "--club", CLUB, "--shots", cor]
    twin = lib + ["--effect-defs", "tests/data/my_cor_power.toml", "--without", "cor_power"]
    wl, cl = timed(lib, ROOT, runs)
    wt, ct = timed(twin, ROOT, runs)
    rows.append(("`smash diagnose`, power-law COR world, `cor_power` offered", wl, cl, "", ""))
    rows.append(("the same with `my_cor_power` in its place", wt, ct, f"{ct / cl:.2f}× the CPU", "≤ 1.5×"))
    return rows


def block(rows, bench_rows, machine, load):
    today = time.strftime("%d %b %Y")
    out = [BEGIN, "",
           f"Measured by `scripts/perf_figures.py` on {today}: {machine}; release build; load "
           f"average {load} before the runs. Whole process (median of the runs; CPU is user + sys):",
           "", "| command | wall | CPU | rate | target |", "|---|---:|---:|---:|---:|"]
    for name, w, c, rate, target in rows:
        out.append(f"| {name} | **{fmt_s(w)}** | {fmt_s(c)} | {rate} | {target} |")
    if bench_rows:
        out += ["", "Criterion, in process (median [95 % interval]):", "",
                "| bench | median |", "|---|---:|"]
        for name, r in bench_rows:
            cell = f"{fmt_s(r[0])} [{fmt_s(r[1])}, {fmt_s(r[2])}]" if r else "not measured (run with `--bench`)"
            out.append(f"| {name} | {cell} |")
    out += ["", END]
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bench", action="store_true")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--libgolf", metavar="DIR",
                    help="a libgolf checkout: time its shot runner on the same drives")
    ap.add_argument("--dry-run", action="store_true",
                    help="print the block, leave docs/performance.md")
    a = ap.parse_args()
    subprocess.run(["cargo", "build", "--release", "-q", "-p", "smash-cli"], cwd=ROOT, check=True)
    if a.bench:
        for b in ("flight", "diagnose", "study"):
            subprocess.run(["cargo", "bench", "--bench", b], cwd=ROOT, check=True)
    load = f"{os.getloadavg()[0]:.1f}"
    with tempfile.TemporaryDirectory() as t:
        rows = measure(a.runs, Path(t), a.libgolf)
    benches = [
        ("flight, 100,000 drives as a launch CSV (read, fly, write)", criterion("flight", "smash_flight_csv_100k")),
        ("diagnose, paper world, 600 shots", criterion("diagnose", "paper world, 600 shots, default options")),
        ("diagnose, real-format season, 2,200 shots", criterion("diagnose", "real-format TrackMan season, 2,200 shots, default options")),
        ("the same without added_mass", criterion("diagnose", "real-format TrackMan season, 2,200 shots, without added_mass")),
        ("diagnose, power-law COR world, cor_power", criterion("diagnose user law", "cor_power")),
        ("the same, my_cor_power", criterion("diagnose user law", "my_cor_power")),
        ("diagnose, shaft-fitting season, 2,244 shots", criterion("diagnose shaft season", "2,244 shots, three shafts, default options")),
        ("study, 9 variants × 801 × 801 impacts (5.8 M), default outputs, CSV long table",
         criterion("study_9x801x801", "smash run, default outputs, csv long table")),
        ("the same, Parquet long table", criterion("study_9x801x801", "smash run, default outputs, parquet long table")),
    ]
    text = block(rows, benches, cpu(), load)
    if a.dry_run:
        print(text)
        return 0
    page = ROOT / "docs" / "performance.md"
    s = page.read_text()
    if BEGIN not in s or END not in s:
        print(f"docs/performance.md has no {BEGIN} … {END} block", file=sys.stderr)
        return 1
    s = s[: s.index(BEGIN)] + text + s[s.index(END) + len(END):]
    page.write_text(s)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
