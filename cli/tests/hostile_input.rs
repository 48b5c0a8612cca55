//! Defects a hostile tester found: inputs of any flag overwritten by outputs, outputs that are
//! not regular files, and values the checks let through. One function per theme, to keep the
//! number of process launches (and CI time) small.

use crate::cli_support;
use crate::common;

use std::path::{Path, PathBuf};
use std::process::Command;

use cli_support::{assert_kept, club, measured_shots, repo, s, smash};

/// Copy `from` (relative to the repository) into `dir` as `name`; returns the path and text.
fn copy(from: &str, dir: &Path, name: &str) -> (PathBuf, String) {
    let path = dir.join(name);
    std::fs::copy(repo(from), &path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    (path, text)
}

/// Every input a command reads is protected, not only the flags a command's own check lists:
/// effect definitions, an atmosphere file, an aero table, an import mapping.
#[test]
fn no_input_of_any_flag_is_overwritten() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let shots = measured_shots(d);
    let (defs, defs_text) = copy("configs/effects/example_effects.toml", d, "defs.toml");
    let (mapping, mapping_text) = copy("configs/import/trackman.toml", d, "map.toml");
    let atm = d.join("atm.toml");
    let atm_text = "[atmosphere]\ntemperature_c = 20.0\n";
    std::fs::write(&atm, atm_text).unwrap();
    let table = d.join("aero.csv");
    let table_text = "spin_factor,cd,cl\n0.0,0.25,0.0\n0.2,0.28,0.2\n0.4,0.32,0.3\n";
    std::fs::write(&table, table_text).unwrap();
    let launch = d.join("launch.csv");
    std::fs::write(
        &launch,
        "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\nd1,150,12,2600\n",
    )
    .unwrap();
    let refused = |args: &[&str], kept: &Path, text: &str| {
        let o = smash(args);
        common::assert_refused(&o, &["same file as one of this command's inputs"]);
        assert_kept(kept, text);
    };
    let (c, sh) = (club(), s(&shots).to_owned());
    let base = ["--club", c.as_str(), "--shots", sh.as_str()];
    let with = |cmd: &str, rest: &[&str]| -> Vec<String> {
        std::iter::once(cmd)
            .chain(base)
            .chain(rest.iter().copied())
            .map(str::to_owned)
            .collect()
    };
    let run = |v: Vec<String>, kept: &Path, text: &str| {
        let args: Vec<&str> = v.iter().map(String::as_str).collect();
        refused(&args, kept, text);
    };
    let defs_flag = ["--effect-defs", s(&defs)];
    run(
        with("predict", &[defs_flag[0], defs_flag[1], "--out", s(&defs)]),
        &defs,
        &defs_text,
    );
    run(
        with(
            "calibrate",
            &[
                defs_flag[0],
                defs_flag[1],
                "--effects",
                "added_mass",
                "--out-club",
                s(&defs),
            ],
        ),
        &defs,
        &defs_text,
    );
    run(
        with(
            "compare",
            &[defs_flag[0], defs_flag[1], "--report", s(&defs)],
        ),
        &defs,
        &defs_text,
    );
    run(
        with(
            "predict",
            &["--flight", "--atmosphere", s(&atm), "--out", s(&atm)],
        ),
        &atm,
        atm_text,
    );
    let aero = format!("table:{}", s(&table));
    refused(
        &[
            "flight",
            "--shots",
            s(&launch),
            "--aero",
            &aero,
            "--out",
            s(&table),
        ],
        &table,
        table_text,
    );
    let export = d.join("tm.csv");
    std::fs::write(
        &export,
        "Date,Player,Club,Club Speed,Attack Angle,Club Path,Dyn. Loft,Face Angle,Impact Offset,\
         Impact Height,Ball Speed,Smash Factor,Launch Angle,Launch Direction,Spin Rate,Spin Axis\n\
         ,,,[mph],[deg],[deg],[deg],[deg],[mm],[mm],[mph],[],[deg],[deg],[rpm],[deg]\n\
         2026-01-01,G01,Driver,100,-1,0,12,0,0,0,145,1.45,11,0,2600,0\n",
    )
    .unwrap();
    refused(
        &[
            "predict",
            "--club",
            &c,
            "--shots",
            s(&export),
            "--format",
            s(&mapping),
            "--impact-offset-positive",
            "toe",
            "--out",
            s(&mapping),
        ],
        &mapping,
        &mapping_text,
    );
}

/// An existing output that is not a regular file (a FIFO, a symbolic link) is refused, named,
/// and left as it was.
#[cfg(unix)]
#[test]
fn outputs_that_are_not_regular_files_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let shots = measured_shots(d);
    let fifo = d.join("pipe");
    assert!(Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success());
    let target = d.join("target.csv");
    std::fs::write(&target, "mine\n").unwrap();
    let link = d.join("link.csv");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    for (out, what) in [(&fifo, "a FIFO"), (&link, "a symbolic link")] {
        let o = smash(&[
            "predict",
            "--club",
            &club(),
            "--shots",
            s(&shots),
            "--out",
            s(out),
        ]);
        common::assert_refused(&o, &[what]);
        let t = std::fs::symlink_metadata(out).unwrap().file_type();
        assert!(!t.is_file(), "{} was replaced by a file", out.display());
    }
    assert_kept(&target, "mine\n");
}

/// Copy `from` into `dir` as `name` with `edits` (`(old, new)`) applied; each must apply.
fn edited(from: &str, dir: &Path, name: &str, edits: &[(&str, &str)]) -> PathBuf {
    let mut text = std::fs::read_to_string(repo(from)).unwrap();
    for (old, new) in edits {
        assert!(text.contains(old), "{old} not in {from}");
        text = text.replacen(old, new, 1);
    }
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// A fixed-length TOML list that is too long is refused with its key and expected length, not
/// silently cut to length.
#[test]
fn over_long_toml_lists_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let drv = "configs/clubs/paper_driver.toml";
    let one = ["--speed", "100", "--loft", "12"];
    for (edit, key, want) in [
        (
            (
                "com_mm = [-42.3, 2.9, 1.0]",
                "com_mm = [-42.3, 2.9, 1.0, 7.0]",
            ),
            "key club.com_mm",
            "expected a list of 3 numbers, got 4",
        ),
        (
            ("0.5, 4085.0]]", "0.5, 4085.0], [1.0, 2.0, 3.0]]"),
            "key club.inertia_gcm2",
            "expected a list of 3 rows of 3 numbers, got 4 rows",
        ),
        (
            ("0.5, 4085.0]]", "0.5, 4085.0, 9.0]]"),
            "key club.inertia_gcm2",
            "row 3: expected a list of 3 numbers, got 4",
        ),
    ] {
        let club = edited(drv, d, "club.toml", &[edit]);
        let mut args = vec!["predict", "--club", s(&club)];
        args.extend(one);
        common::assert_refused(&smash(&args), &[key, want]);
    }
    let club = s(&repo(drv)).to_owned();
    let study_club = (
        "club = \"../clubs/paper_driver.toml\"",
        &*format!("club = {club:?}"),
    );
    for (edit, key, want) in [
        (
            (
                "at_mm = [-70.0, -10.0, 0.0]",
                "at_mm = [-70.0, -10.0, 0.0, 1.0]",
            ),
            "key yards.mass.at_mm",
            "got 4",
        ),
        (
            (
                "impact_centre_mm = [0.0, 0.0]",
                "impact_centre_mm = [0.0, 0.0, 3.0]",
            ),
            "key distribution.impact_centre_mm",
            "expected a list of 2 numbers, got 3",
        ),
        (
            ("[-35.0, 35.0]]", "[-35.0, 35.0], [0.0, 1.0]]"),
            "key yards.mass.bounds_mm",
            "got 4 rows",
        ),
    ] {
        let study = edited(
            "configs/studies/yards_driver.toml",
            d,
            "study.toml",
            &[study_club, edit],
        );
        let out = d.join("out");
        let o = smash(&["run", s(&study), "--out", s(&out)]);
        common::assert_refused(&o, &[key, want]);
    }
}

/// Flight flags with values no flight needs: a spin-decay constant shorter than 1 s or than ten
/// steps, a step so small the flight never ends; huge values are printed short.
#[test]
fn flight_steps_and_spin_decay_are_bounded() {
    let tmp = tempfile::tempdir().unwrap();
    let launch = tmp.path().join("launch.csv");
    std::fs::write(
        &launch,
        "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\nd1,150,12,2600\n",
    )
    .unwrap();
    let out = tmp.path().join("f.csv");
    for (flags, want) in [
        (
            vec!["--spin-decay", "exp:1e-300"],
            "TAU must be within [3.5, 10000] s",
        ),
        (vec!["--spin-decay", "exp:0.1"], "TAU must be within"),
        (
            vec!["--spin-decay", "exp:2", "--dt-s", "0.35"],
            "10 time steps",
        ),
        (
            vec!["--dt-s", "1e-9"],
            "--dt-s 1e-9: must be within [0.0001, 0.5] s",
        ),
        (
            vec!["--max-time-s", "1e308"],
            "--max-time-s 1e308: must be within",
        ),
    ] {
        let mut args = vec!["flight", "--shots", s(&launch), "--out", s(&out)];
        args.extend(flags);
        common::assert_refused(&smash(&args), &[want]);
        assert!(!out.exists());
    }
    // A syntax error in the atmosphere file names its line and column.
    let atm = tmp.path().join("atm.toml");
    std::fs::write(&atm, "[atmosphere]\ntemperature_c = 20\nwind speed = 3\n").unwrap();
    let args = [
        "flight",
        "--shots",
        s(&launch),
        "--out",
        s(&out),
        "--atmosphere",
        s(&atm),
    ];
    common::assert_refused(&smash(&args), &["atm.toml:3: column"]);
    let mut ok = vec!["flight", "--shots", s(&launch), "--out", s(&out)];
    ok.extend(["--spin-decay", "exp:25"]);
    let o = smash(&ok);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// `club.toml` in `dir`: the paper driver with `extra` appended (effect tables).
fn club_with(dir: &Path, extra: &str) -> PathBuf {
    let path = dir.join("club.toml");
    let text = std::fs::read_to_string(repo("configs/clubs/paper_driver.toml")).unwrap();
    std::fs::write(&path, format!("{text}\n{extra}")).unwrap();
    path
}

/// The values a user-defined effect makes are bounded as the library's own are (COR in (0, 1],
/// e_t in [−1, 1], |loft| < 90°, the club mass range), a clubhead CoM at or in front of the face
/// is refused in a club file and in a study's variants, and a loft of 90° on a level swing does
/// not pass as an approach of 3e-15 m/s.
#[test]
fn effects_clubs_and_deliveries_beyond_the_physical_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let defs = d.join("defs.toml");
    let one = ["--speed", "100", "--loft", "12"];
    for (term, want) in [
        (
            "cor = \"cor + 10 * k\"",
            "cor = \"cor + 10 * k\" gave 5.83; it must be in (0, 1]",
        ),
        ("et = \"5\"", "it must be in [-1, 1]"),
        (
            "loft_deg = \"loft_deg + 1000\"",
            "gave 1012; it must be in (-90, 90) deg",
        ),
        ("club_mass_g = \"1e-9\"", "it must be in [1, 10000] g"),
    ] {
        std::fs::write(
            &defs,
            format!(
                "[[define_effect]]\nname = \"u\"\nparams = [{{ key = \"k\", unit = \"1\", \
                 default = 0.0, lower = -1.0, upper = 1.0 }}]\n{term}\n"
            ),
        )
        .unwrap();
        let club = club_with(d, "[[effect]]\nname = \"u\"\nk = 0.5\n");
        let mut args = vec!["predict", "--club", s(&club), "--effect-defs", s(&defs)];
        args.extend(one);
        common::assert_refused(&smash(&args), &["user-defined effect 'u'", want]);
    }
    for com in ["[0.0, 2.9, 1.0]", "[10.0, 2.9, 1.0]"] {
        let club = edited(
            "configs/clubs/paper_driver.toml",
            d,
            "front.toml",
            &[("[-42.3, 2.9, 1.0]", com)],
        );
        let mut args = vec!["predict", "--club", s(&club)];
        args.extend(one);
        common::assert_refused(
            &smash(&args),
            &[
                "key club.com_mm",
                "at or in front of the face",
                "[-500, 0) mm",
            ],
        );
    }
    // Effects that together move the CoM 60 mm forward, past the face.
    let shift = "[[effect]]\nname = \"com_offset\"\ndx_mm = 30\ndy_mm = 0\ndz_mm = 0\n";
    let club = club_with(d, &format!("{shift}{shift}"));
    let mut args = vec!["predict", "--club", s(&club)];
    args.extend(one);
    common::assert_refused(
        &smash(&args),
        &[
            "with the effects of group 'all'",
            "x = 17.",
            "in front of the face",
        ],
    );
    let club = s(&repo("configs/clubs/paper_driver.toml")).to_owned();
    let study = edited(
        "configs/studies/com_sweep.toml",
        d,
        "study.toml",
        &[
            (
                "club = \"../clubs/paper_driver.toml\"",
                &format!("club = {club:?}"),
            ),
            ("com_dx_mm = [-5.0, 0.0, 5.0]", "com_dx_mm = [0.0, 100.0]"),
        ],
    );
    let o = smash(&["run", s(&study), "--out", s(&d.join("out"))]);
    common::assert_refused(&o, &["com_dx_mm = 100", "at or in front of the face"]);
    let yards = edited(
        "configs/studies/yards_driver.toml",
        d,
        "yards.toml",
        &[
            (
                "club = \"../clubs/paper_driver.toml\"",
                &format!("club = {club:?}"),
            ),
            ("at_mm = [-70.0, -10.0, 0.0]", "at_mm = [50.0, -10.0, 0.0]"),
        ],
    );
    let o = smash(&["run", s(&yards), "--out", s(&d.join("out"))]);
    common::assert_refused(
        &o,
        &[
            "key yards.mass.at_mm",
            "discretionary mass x = 50 mm is at or in front",
        ],
    );
    let o = smash(&["predict", "--club", &club, "--speed", "100", "--loft", "90"]);
    common::assert_refused(
        &o,
        &["does not approach the ball", "must exceed 0.0001 m/s"],
    );
    let o = smash(&["predict", "--club", &club, "--speed", "100", "--loft", "89"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// Import errors name the export's own file line (past blank and average rows) and column
/// header; spin rate and axis are range-checked; a column named twice is refused as such.
#[test]
fn import_errors_name_the_exports_line_and_column() {
    let tmp = tempfile::tempdir().unwrap();
    let exp = tmp.path().join("tm.csv");
    let out = tmp.path().join("shots.csv");
    let head = "Club,Club Speed,Attack Angle,Club Path,Dyn. Loft,Face Angle,Impact Offset,\
                Impact Height,Ball Speed,Launch Angle,Launch Direction,Spin Rate,Spin Axis";
    let units = ",[mph],[deg],[deg],[deg],[deg],[mm],[mm],[mph],[deg],[deg],[rpm],[deg]";
    let row = |speed: &str, launch: &str, rate: &str, axis: &str| {
        format!("Driver,{speed},1,2,11,0.5,3,4,155,{launch},1.2,{rate},{axis}")
    };
    let good = row("105", "12", "2600", "-3");
    let import = |text: String, flags: &[&str]| {
        std::fs::write(&exp, text).unwrap();
        let mut args = vec!["import", "--format", "trackman", s(&exp), "--out", s(&out)];
        args.extend(["--impact-offset-positive", "toe"]);
        args.extend(flags);
        smash(&args)
    };
    let avg = good.replacen("Driver", "Average", 1);
    for (bad, want) in [
        (
            row("999", "12", "2600", "-3"),
            "tm.csv:7: column 'Club Speed': club speed 999 is outside",
        ),
        (
            row("105", "95", "2600", "-3"),
            "tm.csv:7: column 'Launch Angle': measured launch angle 95 is outside",
        ),
        (
            row("105", "12", "-2700", "-3"),
            "tm.csv:7: column 'Spin Rate': spin rate -2700 is outside the physical range [0, 30000] rpm",
        ),
        (
            row("105", "12", "2600", "200"),
            "tm.csv:7: column 'Spin Axis': spin axis 200 is outside the physical range [-180, 180] deg",
        ),
    ] {
        let text = format!("{head}\n{units}\n{good}\n\n{avg}\n{good}\n{bad}\n");
        common::assert_refused(&import(text.clone(), &["--strict"]), &[want]);
        assert!(!out.exists());
        // Without --strict a bad launch cell leaves the row out, counted and named; a bad
        // delivery cell is read as not measured, counted and named, and the shot keeps its
        // launch (for flight; compare leaves it out and says so).
        let o = import(text, &[]);
        let err = cli_support::unwrapped(&o);
        assert!(o.status.success(), "{err}");
        if want.contains("'Club Speed'") {
            assert!(
                err.contains("column 'Club Speed': outside its physical range (line(s) 7;")
                    && err.contains("club speed 999 is outside"),
                "{err}"
            );
            assert_eq!(std::fs::read_to_string(&out).unwrap().lines().count(), 4);
        } else {
            assert!(err.contains("left out 1 row(s)") && err.contains(want), "{err}");
            assert_eq!(std::fs::read_to_string(&out).unwrap().lines().count(), 3);
        }
        std::fs::remove_file(&out).unwrap();
    }
    // The same line with CRLF and with CR-only line ends (old Mac exports), a blank line and
    // an average row before it.
    let bad = row("999", "12", "2600", "-3");
    for end in ["\r\n", "\r"] {
        let text = [head, units, &good, "", &avg, &good, &bad, ""].join(end);
        common::assert_refused(
            &import(text, &["--strict"]),
            &["tm.csv:7: column 'Club Speed'"],
        );
    }
    for flags in [&[][..], &["--ignore-unknown-columns"][..]] {
        let o = import(
            format!("{head},Club Speed\n{units},[mph]\n{good},100\n"),
            flags,
        );
        common::assert_refused(
            &o,
            &["tm.csv:1: column 'Club Speed'", "twice (columns 2 and 14)"],
        );
    }
    std::fs::write(&exp, format!("{head}\n{units}\n{good}\n")).unwrap();
    let o = smash(&["import", "--format", "shots", s(&exp), "--out", s(&out)]);
    common::assert_refused(&o, &["nothing to convert", "trackman"]);
}

/// A group no effect of the club names, a sensitivity step lost in the numbers' precision, a
/// grid spacing of 1e-300 mm and significance levels or bins of 1e±300 are refused, and the
/// numbers are printed short.
#[test]
fn groups_steps_and_levels_are_checked() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let grouped = club_with(
        d,
        "[[effect]]\nname = \"cor_level\"\ndcor = 0.01\ngroup = \"A\"\n",
    );
    let in_group = |g: &str| {
        let one = ["--speed", "100", "--loft", "12", "--group", g];
        smash(&[&["predict", "--club", s(&grouped)][..], &one].concat())
    };
    common::assert_refused(
        &in_group("B"),
        &["group 'B' is not a group", "its groups are 'A'"],
    );
    let o = in_group("A");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let club = s(&repo("configs/clubs/paper_driver.toml")).to_owned();
    let study_club = (
        "club = \"../clubs/paper_driver.toml\"",
        &*format!("club = {club:?}"),
    );
    for (edit, want) in [
        (
            ("outputs = [", "group = \"nosuch\"\noutputs = ["),
            &["key study.group", "group 'nosuch'", "only 'all'"][..],
        ),
        (
            ("com_dx_mm = 0.5,", "com_dx_mm = 1e-300,"),
            &[
                "key sensitivity.steps.com_dx_mm",
                "1e-300 mm is below the smallest meaningful step 1e-6 mm",
            ][..],
        ),
        (
            (
                "y_mm = { from = -15.0, to = 15.0, count = 13 }",
                "y_mm = { from = 0, to = 1e-300, step = 5e-301 }",
            ),
            &["key grid.y_mm", "5e-301 apart", "at least 1e-6 apart"][..],
        ),
        (
            (
                "y_mm = { from = -15.0, to = 15.0, count = 13 }",
                "y_mm = { from = 0, to = 1e-300, count = 3 }",
            ),
            &["key grid.y_mm", "5e-301 apart"][..],
        ),
    ] {
        let study = edited(
            "configs/studies/com_sweep.toml",
            d,
            "study.toml",
            &[study_club, edit],
        );
        let o = smash(&["run", s(&study), "--out", s(&d.join("out"))]);
        common::assert_refused(&o, want);
    }
    let shots = measured_shots(d);
    let out = d.join("cmp");
    let levels = [
        (
            "--alpha 1e-308",
            "--alpha 1e-308: must be within [1e-9, 0.5]",
        ),
        ("--alpha 2e300", "--alpha 2e300: must be within"),
        (
            "--bin-mm 1e300",
            "--bin-mm 1e300: must be within [0.5, 100] mm",
        ),
        ("--bin-mm 1e-300", "--bin-mm 1e-300: must be within"),
    ];
    for (flag_value, want) in levels {
        let (flag, value) = flag_value.split_once(' ').unwrap();
        let o = smash(&[
            "compare",
            "--club",
            &club,
            "--shots",
            s(&shots),
            "--out-dir",
            s(&out),
            flag,
            value,
        ]);
        common::assert_refused(&o, &[want]);
        assert!(String::from_utf8_lossy(&o.stderr).len() < 300);
    }
}

/// A calibrated club is written with the decimals its file was read with (`mass_g = 204.0`, not
/// `204.00000000000003` from 0.204 kg × 1000), and reads back to the same club.
#[test]
fn a_written_club_keeps_the_decimals_it_was_read_with() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let shots = measured_shots(d);
    let out = d.join("cal.toml");
    let o = smash(&[
        "calibrate",
        "--club",
        &club(),
        "--shots",
        s(&shots),
        "--effects",
        "cor_level",
        "--out-club",
        s(&out),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&out).unwrap();
    for line in [
        "mass_g = 204.0",
        "com_mm = [-42.3, 2.9, 1.0]",
        "inertia_gcm2 = [[2843.0, -733.0, 530.2], [-733.0, 5679.0, 0.5], [530.2, 0.5, 4085.0]]",
        "inertia_gcm2 = 83.63",
    ] {
        assert!(
            text.lines().any(|l| l == line),
            "no line {line:?} in:\n{text}"
        );
    }
}
