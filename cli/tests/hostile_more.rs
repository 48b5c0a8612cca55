//! Defects of a later hostile pass: cells and numbers so long the error line became as long,
//! objective weights that overflowed a study's objective, and shots that silently missed their
//! club's per-group effects. One function per theme, to keep the process launches few.

use crate::cli_support;
use crate::common;

use std::path::Path;

use cli_support::{club, measured_shots, repo, s, smash, stderr, write};

const SHOTS_HEAD: &str = "shot_id,club_speed_mph,attack_angle_deg,club_path_deg,\
                          dynamic_loft_deg,face_angle_deg,impact_y_mm,impact_z_mm";

/// A 100 000-character cell is quoted by its first characters and its length, not in full, by
/// the shots reader, the launch reader of `flight` and the import; a float of 309 digits in a
/// TOML file is written short.
#[test]
fn a_huge_cell_or_number_makes_a_short_error_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let huge = "x".repeat(100_000);
    let short = |o: &std::process::Output, needles: &[&str]| {
        common::assert_refused(o, needles);
        assert!(stderr(o).len() < 400, "{} characters", stderr(o).len());
    };
    let shots = write(
        d,
        "shots.csv",
        &format!("{SHOTS_HEAD}\ns1,{huge},0,0,12,0,0,0\n"),
    );
    let out = d.join("out.csv");
    let (c, o) = (club(), s(&out).to_owned());
    short(
        &smash(&["predict", "--club", &c, "--shots", s(&shots), "--out", &o]),
        &[
            "shots.csv:2: column 'club_speed_mph': 'xxxx",
            "…' (100000 characters) is not a number",
        ],
    );
    let launch = write(
        d,
        "launch.csv",
        &format!("shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\nd1,150,{huge},2600\n"),
    );
    short(
        &smash(&["flight", "--shots", s(&launch), "--out", &o]),
        &[
            "launch.csv:2: column 'launch_angle_deg'",
            "(100000 characters) is not a finite number",
        ],
    );
    // The import: a TrackMan export with a huge club speed.
    let export = write(
        d,
        "export.csv",
        &format!(
            "Club,Club Speed,Attack Angle,Club Path,Dyn. Loft,Face Angle,Impact Offset,\
             Impact Height,Ball Speed,Launch Angle,Launch Direction,Spin Rate,Spin Axis\n\
             ,[mph],[deg],[deg],[deg],[deg],[mm],[mm],[mph],[deg],[deg],[rpm],[deg]\n\
             Driver,{huge},1,2,11,0.5,3,4,155,12,1.2,2600,-3\n"
        ),
    );
    short(
        &smash(&[
            "import",
            "--format",
            "trackman",
            s(&export),
            "--out",
            &o,
            "--impact-offset-positive",
            "toe",
        ]),
        &["column 'Club Speed'", "(100000 characters) is not a number"],
    );
    assert!(!out.exists());
    // serde writes 1e308 with all its digits.
    let cfg = std::fs::read_to_string(repo("configs/synth/paper_world.toml"))
        .unwrap()
        .replace("seed = 2019", "seed = 1e308")
        .replace(
            "../clubs/paper_driver.toml",
            s(&repo("configs/clubs/paper_driver.toml")),
        );
    let cfg = write(d, "world.toml", &cfg);
    short(
        &smash(&["synth", "--config", s(&cfg), "--out", &o]),
        &["key seed", "floating point `1e308`"],
    );
}

/// An objective weight so large that weight × metric overflows (1e308, -1e7) is refused at its
/// key, not written as an infinite objective; 1e6 still runs.
#[test]
fn objective_weights_that_overflow_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let study = |w: &str| {
        format!(
            "[study]\nname = \"w\"\nclub = {:?}\n[delivery]\nclub_speed_mph = 100.0\n\
             dynamic_loft_deg = 12.0\n[grid]\ny_mm = {{ from = -2.0, to = 2.0, count = 3 }}\n\
             z_mm = {{ from = -2.0, to = 2.0, count = 3 }}\n[design]\ncom_dx_mm = [0.0]\n\
             [optimise]\ngoal = \"maximise\"\nobjective = {{ cof_ball_speed_mph = {w} }}\n\
             bounds = {{ com_dx_mm = [-1.0, 1.0] }}\nmax_iters = 5\n",
            s(&repo("configs/clubs/paper_driver.toml"))
        )
    };
    for w in ["1e308", "-1e7", "1.7976931348623157e308"] {
        let path = write(d, "study.toml", &study(w));
        let out = d.join("out");
        common::assert_refused(
            &smash(&["run", s(&path), "--out", s(&out)]),
            &[
                "study.toml:14",
                "key optimise.objective.cof_ball_speed_mph",
                "is too large: allowed within [-1000000, 1000000]",
            ],
        );
        assert!(!out.exists());
    }
    let path = write(d, "study.toml", &study("1e6"));
    let out = d.join("ok");
    let o = smash(&["run", s(&path), "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    for f in ["optimise/path.csv", "optimise/result.csv"] {
        let text = std::fs::read_to_string(out.join(f)).unwrap();
        assert!(!common::has_non_finite(&text), "{f}: {text}");
    }
}

/// A club calibrated per group (`group = "A"`) applied to shots of other groups: one warning
/// naming them, on stderr, for each command that reads a club and shots; none when every group
/// has its effects.
#[test]
fn shots_of_groups_without_the_clubs_group_effects_are_named_once() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let text = std::fs::read_to_string(repo("configs/clubs/paper_driver.toml")).unwrap();
    let club = write(
        d,
        "club.toml",
        &format!("{text}\n[[effect]]\nname = \"added_mass\"\ndm_g = 2.0\ngroup = \"A\"\n"),
    );
    let measured = std::fs::read_to_string(measured_shots(d)).unwrap();
    // Half the shots in group A, half in B (a `group` column after `shot_id`).
    let mut lines = measured.lines();
    let head = lines
        .next()
        .unwrap()
        .replacen("shot_id,", "shot_id,group,", 1);
    let mut mixed = vec![head.clone()];
    let mut only_a = vec![head];
    for (i, l) in lines.enumerate() {
        let (id, rest) = l.split_once(',').unwrap();
        let g = if i % 2 == 0 { "A" } else { "B" };
        mixed.push(format!("{id},{g},{rest}"));
        only_a.push(format!("{id},A,{rest}"));
    }
    let mixed = write(d, "mixed.csv", &(mixed.join("\n") + "\n"));
    let only_a = write(d, "only_a.csv", &(only_a.join("\n") + "\n"));
    let no_group = measured_shots(d);
    let out = d.join("pred.csv");
    let runs = |shots: &Path| -> Vec<Vec<String>> {
        vec![
            vec!["predict", "--out", s(&out)],
            vec!["compare"],
            vec!["calibrate", "--effects", "ball_offset"],
        ]
        .into_iter()
        .map(|extra| {
            let mut args = vec![extra[0], "--club", s(&club), "--shots", s(shots)];
            args.extend(&extra[1..]);
            args.into_iter().map(str::to_owned).collect()
        })
        .collect()
    };
    let warnings = |shots: &Path| -> Vec<String> {
        runs(shots)
            .iter()
            .map(|args| {
                let args: Vec<&str> = args.iter().map(String::as_str).collect();
                let o = smash(&args);
                assert!(o.status.success(), "{args:?}: {}", stderr(&o));
                let w: Vec<String> = stderr(&o)
                    .lines()
                    .filter(|l| l.starts_with("warning:") && l.contains("per-group"))
                    .map(str::to_owned)
                    .collect();
                assert!(w.len() <= 1, "{args:?}: {w:?}");
                w.join("")
            })
            .collect()
    };
    for w in warnings(&mixed) {
        assert!(
            w.contains(
                "club.toml: the club's per-group effects are for group(s) 'A'; shots of \
                        group(s) 'B' get none of them"
            ),
            "{w}"
        );
    }
    for w in warnings(&no_group) {
        assert!(
            w.contains("group(s) 'all' get none") && w.contains("without a `group` column"),
            "{w}"
        );
    }
    for w in warnings(&only_a) {
        assert_eq!(w, "");
    }
}

/// A shard's point must hold what `smash run --shard` writes: five numbers on a valid point,
/// empty cells on an invalid one. A damaged file (1e308 m/s, which became an infinite mph and a
/// smash factor of 307 digits; an empty speed on a valid point, merged as a valid point without
/// a speed; values on an invalid point) is refused at its line and column.
#[test]
fn merge_refuses_points_a_shard_never_writes() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let study = write(
        d,
        "tiny.toml",
        &format!(
            "[study]\nname = \"tiny\"\nclub = {:?}\n[delivery]\nclub_speed_mph = 100.0\n\
             dynamic_loft_deg = 12.0\n[grid]\ny_mm = {{ from = -2.0, to = 2.0, count = 3 }}\n\
             z_mm = {{ from = -2.0, to = 2.0, count = 3 }}\n",
            s(&repo("configs/clubs/paper_driver.toml"))
        ),
    );
    let shard = d.join("shard");
    let o = smash(&["run", s(&study), "--shard", "0/1", "--out", s(&shard)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let rows = std::fs::read_to_string(shard.join("rows.csv")).unwrap();
    let line3: Vec<&str> = rows.lines().nth(2).unwrap().split(',').collect();
    assert_eq!(line3[3], "1", "{line3:?}");
    let out = d.join("merged");
    for (edit, needles) in [
        (
            (4, "1e308"),
            &[
                "rows.csv:3: column ball_speed_m_s: '1e308' on a valid point",
                "±1000000",
            ][..],
        ),
        (
            (7, ""),
            &["rows.csv:3: column backspin_rad_s: '' on a valid point"][..],
        ),
        (
            (3, "0"),
            &[
                "rows.csv:3: column ball_speed_m_s: '",
                "on a point marked invalid",
            ][..],
        ),
    ] {
        let mut cells = line3.clone();
        cells[edit.0] = edit.1;
        let edited: Vec<String> = rows
            .lines()
            .enumerate()
            .map(|(i, l)| {
                if i == 2 {
                    cells.join(",")
                } else {
                    l.to_owned()
                }
            })
            .collect();
        std::fs::write(shard.join("rows.csv"), edited.join("\n") + "\n").unwrap();
        common::assert_refused(&smash(&["merge", s(&shard), "--out", s(&out)]), needles);
        assert!(!out.exists());
    }
    std::fs::write(shard.join("rows.csv"), &rows).unwrap();
    let o = smash(&["merge", s(&shard), "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
}

/// A club name, shot id, group or golfer holding a control character (an escape sequence that
/// recolours the terminal, a line break that splits a table row) is refused at its key or cell:
/// these names were printed raw on stdout.
#[test]
fn names_with_control_characters_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let text = std::fs::read_to_string(repo("configs/clubs/paper_driver.toml")).unwrap();
    let name = text.lines().find(|l| l.starts_with("name = ")).unwrap();
    let line = text.lines().position(|l| l == name).unwrap() + 1;
    for bad in ["\\u001b[31mred", "two\\nlines", "tab\\there"] {
        let club = write(
            d,
            "club.toml",
            &text.replacen(name, &format!("name = \"{bad}\""), 1),
        );
        common::assert_refused(
            &smash(&[
                "predict",
                "--club",
                s(&club),
                "--speed",
                "100",
                "--loft",
                "12",
            ]),
            &[
                &format!("club.toml:{line}"),
                "key club.name",
                "holds a control character",
            ],
        );
    }
    let c = club();
    let out = d.join("out.csv");
    for (col, row) in [
        ("shot_id", "s\u{1b}[2J,A,g1"),
        ("group", "s1,A\u{1b}[31m,g1"),
        ("golfer", "s1,A,\"g\r1\""),
    ] {
        let shots = write(
            d,
            "shots.csv",
            &format!("shot_id,group,golfer,club_speed_mph,attack_angle_deg,club_path_deg,dynamic_loft_deg,face_angle_deg,impact_y_mm,impact_z_mm\n{row},100,0,0,12,0,0,0\n"),
        );
        let o = smash(&[
            "predict",
            "--club",
            &c,
            "--shots",
            s(&shots),
            "--out",
            s(&out),
        ]);
        common::assert_refused(
            &o,
            &[
                &format!("shots.csv:2: column '{col}'"),
                "holds a control character",
            ],
        );
        assert!(!o.stderr.contains(&0x1b), "{}", stderr(&o));
        assert!(!out.exists());
    }
}
