//! The command line at its edges: output that cannot be written, outputs that would replace a
//! user's files or the command's own inputs, outputs that appear together or not at all, and
//! stale temporaries of killed runs.

use crate::cli_support;
use crate::common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

use cli_support::{assert_kept, club, measured_shots, repo, s, smash, stderr, SMASH};

fn study_file(dir: &Path) -> PathBuf {
    let path = dir.join("study.toml");
    std::fs::write(
        &path,
        format!(
            "[study]\nname = \"t\"\nclub = {:?}\n\n[delivery]\nclub_speed_mph = 100.0\n\
             dynamic_loft_deg = 12.0\n\n[grid]\ny_mm = {{ from = -10.0, to = 10.0, count = 5 }}\n\
             z_mm = {{ from = -10.0, to = 10.0, count = 5 }}\n",
            club()
        ),
    )
    .unwrap();
    path
}

// ---- 1. output that cannot be written ------------------------------------------------------

#[test]
fn a_full_disk_on_stdout_is_one_line_and_exit_1() {
    let commands: [&[&str]; 3] = [
        &["effects"],
        &["effects", "--json"],
        &[
            "predict",
            "--club",
            &club(),
            "--speed",
            "100",
            "--loft",
            "12",
        ],
    ];
    for args in commands {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let o = Command::new(SMASH)
            .args(args)
            .stdout(Stdio::from(full))
            .output()
            .unwrap();
        common::assert_refused(&o, &["cannot write to standard output"]);
    }
}

#[test]
fn a_closed_pipe_ends_the_command_silently_with_the_sigpipe_status() {
    // The reader (`true`) is gone well before smash starts writing.
    let club = club();
    for args in [
        "effects",
        "effects --json",
        &format!("predict --club '{club}' --speed 100 --loft 12"),
    ] {
        let o = Command::new("sh")
            .arg("-c")
            .arg(format!(
                "{{ sleep 0.3; '{SMASH}' {args}; echo \"status=$?\" >&2; }} | true"
            ))
            .output()
            .unwrap();
        assert_eq!(stderr(&o), "status=141\n", "smash {args}");
    }
}

// ---- 4. a user's files are never deleted or replaced -----------------------------------------

#[test]
fn run_refuses_a_folder_of_its_outputs_beside_a_users_file() {
    let tmp = tempfile::tempdir().unwrap();
    let study = study_file(tmp.path());
    let out = tmp.path().join("out");
    let o = smash(&["run", s(&study), "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    // The user adds notes beside the outputs: a re-run must not delete them.
    std::fs::write(out.join("notes.md"), "my notes").unwrap();
    let o = smash(&["run", s(&study), "--out", s(&out)]);
    common::assert_refused(&o, &["notes.md"]);
    assert_kept(&out.join("notes.md"), "my notes");
    assert!(out.join("study.toml").is_file());
    // Without them, the earlier outputs are replaced as before.
    std::fs::remove_file(out.join("notes.md")).unwrap();
    let o = smash(&["run", s(&study), "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    // The folder holding the study itself is refused.
    let o = smash(&["run", s(&study), "--out", s(tmp.path())]);
    common::assert_refused(&o, &["STUDY.toml"]);
    assert!(study.is_file());
}

#[test]
fn merge_refuses_a_folder_with_a_users_file() {
    let tmp = tempfile::tempdir().unwrap();
    let study = study_file(tmp.path());
    let shards: Vec<PathBuf> = (0..2).map(|k| tmp.path().join(format!("sh{k}"))).collect();
    for (k, d) in shards.iter().enumerate() {
        let o = smash(&[
            "run",
            s(&study),
            "--shard",
            &format!("{k}/2"),
            "--out",
            s(d),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    let out = tmp.path().join("merged");
    let o = smash(&["merge", s(&shards[0]), s(&shards[1]), "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    std::fs::write(out.join("thesis.tex"), "chapter 1").unwrap();
    let o = smash(&["merge", s(&shards[0]), s(&shards[1]), "--out", s(&out)]);
    common::assert_refused(&o, &["thesis.tex"]);
    assert_kept(&out.join("thesis.tex"), "chapter 1");
}

#[test]
fn compare_refuses_a_folder_with_a_users_file_and_one_holding_its_input() {
    let tmp = tempfile::tempdir().unwrap();
    let shots = measured_shots(tmp.path());
    let out = tmp.path().join("cmp");
    let o = smash(&[
        "compare",
        "--club",
        &club(),
        "--shots",
        s(&shots),
        "--out-dir",
        s(&out),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(out.join("compare.json").is_file());
    std::fs::write(out.join("thesis.tex"), "chapter 2").unwrap();
    let o = smash(&[
        "compare",
        "--club",
        &club(),
        "--shots",
        s(&shots),
        "--out-dir",
        s(&out),
    ]);
    common::assert_refused(&o, &["thesis.tex"]);
    assert_kept(&out.join("thesis.tex"), "chapter 2");
    let o = smash(&[
        "compare",
        "--club",
        &club(),
        "--shots",
        s(&shots),
        "--out-dir",
        s(tmp.path()),
    ]);
    common::assert_refused(&o, &["--shots"]);
    assert!(shots.is_file());
}

#[test]
fn an_output_that_is_an_input_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let shots = measured_shots(tmp.path());
    let before = std::fs::read_to_string(&shots).unwrap();
    // The same file under another spelling.
    std::fs::create_dir(tmp.path().join("sub")).unwrap();
    let alias = tmp.path().join("sub/../shots.csv");
    let o = smash(&[
        "predict",
        "--club",
        &club(),
        "--shots",
        s(&shots),
        "--out",
        s(&alias),
    ]);
    common::assert_refused(&o, &["--out is the same file as --shots"]);
    assert_kept(&shots, &before);

    let club_copy = tmp.path().join("club.toml");
    std::fs::copy(club(), &club_copy).unwrap();
    let club_text = std::fs::read_to_string(&club_copy).unwrap();
    for cmd in ["calibrate", "diagnose"] {
        let mut args = vec![cmd, "--club", s(&club_copy), "--shots", s(&shots)];
        if cmd == "calibrate" {
            args.extend(["--effects", "added_mass"]);
        }
        args.extend(["--out-club", s(&club_copy)]);
        let o = smash(&args);
        common::assert_refused(&o, &["--out-club is the same file as --club"]);
        assert_kept(&club_copy, &club_text);
    }
    // An HTML report may not replace an input either.
    for cmd in ["compare", "calibrate", "diagnose"] {
        let mut args = vec![cmd, "--club", s(&club_copy), "--shots", s(&shots)];
        if cmd == "calibrate" {
            args.extend(["--effects", "added_mass"]);
        }
        args.extend(["--report", s(&alias)]);
        let o = smash(&args);
        common::assert_refused(&o, &["--report is the same file as --shots"]);
        assert_kept(&shots, &before);
    }
    let study = study_file(tmp.path());
    let study_text = std::fs::read_to_string(&study).unwrap();
    let out = tmp.path().join("out");
    let o = smash(&["run", s(&study), "--out", s(&out), "--report", s(&study)]);
    common::assert_refused(&o, &["--report is the same file as STUDY.toml"]);
    assert_kept(&study, &study_text);
    let o = smash(&[
        "run",
        s(&study),
        "--out",
        s(&out),
        "--report",
        s(&out.join("r.html")),
    ]);
    common::assert_refused(&o, &["inside the study's output folder"]);
}

#[test]
fn synth_writes_both_outputs_or_neither() {
    let tmp = tempfile::tempdir().unwrap();
    let shots = tmp.path().join("shots.csv");
    // The truth path is a folder: nothing may be written, not even the shots.
    let truth = tmp.path().join("truth.toml");
    std::fs::create_dir(&truth).unwrap();
    let config = repo("configs/synth/null_world.toml");
    let o = smash(&[
        "synth",
        "--config",
        s(&config),
        "--out",
        s(&shots),
        "--truth",
        s(&truth),
    ]);
    common::assert_refused(&o, &["truth.toml"]);
    assert!(!shots.exists(), "the shots file was left behind");
    let left: Vec<_> = std::fs::read_dir(tmp.path()).unwrap().collect();
    assert_eq!(left.len(), 1, "only the user's folder remains: {left:?}");
    // The same path for both outputs is refused up front.
    let o = smash(&[
        "synth",
        "--config",
        s(&config),
        "--out",
        s(&shots),
        "--truth",
        s(&shots),
    ]);
    common::assert_refused(&o, &["same path"]);
    assert!(!shots.exists());
}

#[test]
fn stale_temporaries_of_dead_runs_are_removed_and_live_ones_kept() {
    let tmp = tempfile::tempdir().unwrap();
    let study = study_file(tmp.path());
    // A process that has certainly exited.
    let mut child = Command::new("true").spawn().unwrap();
    let dead = child.id();
    child.wait().unwrap();
    let live = std::process::id();
    let stale = tmp.path().join(format!(".out.tmp-{dead}"));
    let running = tmp.path().join(format!(".out.tmp-{live}"));
    let not_ours = tmp.path().join(format!(".other.tmp-{dead}"));
    for d in [&stale, &running, &not_ours] {
        std::fs::create_dir(d).unwrap();
        std::fs::write(d.join("rows.csv"), "x").unwrap();
    }
    let o = smash(&["run", s(&study), "--out", s(&tmp.path().join("out"))]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!stale.exists(), "stale temporary of a dead run kept");
    assert!(running.exists(), "a live run's temporary was removed");
    assert!(not_ours.exists(), "another output's temporary was removed");
}

// ---- 6. shards prove they belong together ------------------------------------------------------

/// A study on its own copy of the club, and its two shards.
fn sharded(dir: &Path) -> (PathBuf, PathBuf, Vec<PathBuf>) {
    let club_copy = dir.join("club.toml");
    std::fs::copy(club(), &club_copy).unwrap();
    let study = dir.join("study.toml");
    std::fs::write(
        &study,
        "[study]\nname = \"t\"\nclub = \"club.toml\"\n\n[delivery]\nclub_speed_mph = 100.0\n\
         dynamic_loft_deg = 12.0\n\n[grid]\ny_mm = { from = -10.0, to = 10.0, count = 4 }\n\
         z_mm = { from = -10.0, to = 10.0, count = 3 }\n",
    )
    .unwrap();
    let shards: Vec<PathBuf> = (0..2).map(|k| dir.join(format!("sh{k}"))).collect();
    for (k, d) in shards.iter().enumerate() {
        run_shard(&study, k, d);
    }
    (study, club_copy, shards)
}

fn run_shard(study: &Path, k: usize, out: &Path) {
    let o = smash(&[
        "run",
        s(study),
        "--shard",
        &format!("{k}/2"),
        "--out",
        s(out),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
}

fn merge(shards: &[PathBuf], out: &Path) -> Output {
    let mut args = vec!["merge"];
    args.extend(shards.iter().map(|p| s(p)));
    args.extend(["--out", s(out)]);
    smash(&args)
}

fn edit(path: &Path, from: &str, to: &str) {
    let text = std::fs::read_to_string(path).unwrap();
    assert!(text.contains(from), "{from:?} not in {}", path.display());
    std::fs::write(path, text.replacen(from, to, 1)).unwrap();
}

#[test]
fn shards_of_different_clubs_are_not_merged() {
    let tmp = tempfile::tempdir().unwrap();
    let (study, club_copy, shards) = sharded(tmp.path());
    let out = tmp.path().join("merged");
    let o = merge(&shards, &out);
    assert!(o.status.success(), "{}", stderr(&o));
    // The club changes between the shards: refused, naming both.
    edit(&club_copy, "cor = 0.83", "cor = 0.80");
    run_shard(&study, 1, &shards[1]);
    let o = merge(&shards, &tmp.path().join("m2"));
    common::assert_refused(&o, &["different club files"]);
    let err = stderr(&o);
    assert!(err.contains("sh0") && err.contains("sh1"), "{err}");
    assert!(!tmp.path().join("m2").exists());
    // Both shards of the new club, but the club changed again before the merge.
    run_shard(&study, 0, &shards[0]);
    edit(&club_copy, "cor = 0.80", "cor = 0.81");
    let o = merge(&shards, &tmp.path().join("m3"));
    common::assert_refused(&o, &["changed since the shards were computed"]);
}

#[test]
fn every_field_read_back_from_a_shard_is_checked() {
    let tmp = tempfile::tempdir().unwrap();
    let (_, _, shards) = sharded(tmp.path());
    let rows = shards[1].join("rows.csv");
    let original = std::fs::read_to_string(&rows).unwrap();
    let first = original.lines().nth(1).unwrap().to_owned();
    let fields: Vec<&str> = first.split(',').collect();
    let with = |i: usize, v: &str| {
        let mut f = fields.clone();
        f[i] = v;
        original.replacen(&first, &f.join(","), 1)
    };
    let cases = [
        (with(1, "18446744073709551615"), "rows.csv:2: column row"),
        (with(0, "7"), "rows.csv:2: column variant"),
        (with(2, "99"), "rows.csv:2: column col"),
        (with(3, "2"), "rows.csv:2: column valid"),
        (with(4, "1e999"), "rows.csv:2: column ball_speed_m_s"),
        (
            original.replacen(&first, &format!("{first},9"), 1),
            "rows.csv:2",
        ),
        (with(0, "\u{1b}[2J"), "\\u{1b}[2J"),
    ];
    for (k, (text, want)) in cases.iter().enumerate() {
        std::fs::write(&rows, text).unwrap();
        let o = merge(&shards, &tmp.path().join(format!("m{k}")));
        common::assert_refused(&o, &[want]);
        assert!(!stderr(&o).contains('\u{1b}'), "raw ESC echoed");
    }
    std::fs::write(&rows, &original).unwrap();

    let meta = shards[1].join("shard.toml");
    let text = std::fs::read_to_string(&meta).unwrap();
    for (from, to, want) in [
        ("shards = 2", "shards = 0", "at least 1 shard"),
        ("shard = 1", "shard = 5", "shards are numbered 0 to 1"),
        (
            "first_item = ",
            "first_item = 1",
            "are not those of shard 1 of 2",
        ),
    ] {
        std::fs::write(&meta, text.replacen(from, to, 1)).unwrap();
        let o = merge(&shards, &tmp.path().join("mm"));
        common::assert_refused(&o, &[want]);
        assert!(!stderr(&o).contains("shard 0 of 0"), "{}", stderr(&o));
    }
    // A shard without the hashes (an older smash) is refused with what to do.
    let no_hash: String = text
        .lines()
        .filter(|l| !l.starts_with("club_sha256"))
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(&meta, no_hash).unwrap();
    let o = merge(&shards, &tmp.path().join("mm"));
    common::assert_refused(&o, &["run the shards again"]);
}

// ---- 8. messages --------------------------------------------------------------------------------

const SHOTS_HEADER: &str = "shot_id,club_speed_mph,attack_angle_deg,club_path_deg,\
                            dynamic_loft_deg,face_angle_deg,impact_y_mm,impact_z_mm\n";

#[test]
fn control_characters_from_input_are_escaped() {
    let tmp = tempfile::tempdir().unwrap();
    let shots = tmp.path().join("s.csv");
    // ESC in a number cell, CR inside a quoted id cell.
    for (body, want) in [
        ("s1,1\u{1b}[2J00,0,0,12,0,0,0\n", "1\\u{1b}[2J00"),
        ("\"s\r1\",100,0,60,12,-60,0,0\n", "s\\r1"),
    ] {
        std::fs::write(&shots, format!("{SHOTS_HEADER}{body}")).unwrap();
        let o = smash(&[
            "predict",
            "--club",
            &club(),
            "--shots",
            s(&shots),
            "--out",
            s(&tmp.path().join("p.csv")),
        ]);
        common::assert_refused(&o, &[want]);
        let err = stderr(&o);
        assert!(!err.contains('\u{1b}') && !err.contains('\r'), "{err:?}");
    }
}

#[test]
fn negative_numbers_are_values_not_flags() {
    let o = smash(&[
        "predict",
        "--club",
        &club(),
        "--speed",
        "-5",
        "--loft",
        "12",
    ]);
    common::assert_refused(
        &o,
        &["--speed: club speed -5 is outside the physical range"],
    );
    let o = smash(&[
        "predict",
        "--club",
        &club(),
        "--speed",
        "100",
        "--loft",
        "-2",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = smash(&[
        "predict",
        "--club",
        &club(),
        "--speed",
        "-1e300",
        "--loft",
        "12",
    ]);
    common::assert_refused(&o, &["club speed -1e300 is outside"]);
    // Values of other forms that start with a minus sign reach their own checks too.
    let o = smash(&[
        "compare",
        "--club",
        &club(),
        "--shots",
        "x.csv",
        "--impact-noise-mm",
        "-3,2",
    ]);
    let err = stderr(&o);
    assert!(!o.status.success() && err.contains("-3"), "{err}");
    assert!(!err.contains("unexpected argument"), "{err}");
    let o = smash(&["run", "study.toml", "--shard", "-1/4"]);
    let err = stderr(&o);
    assert!(err.contains("--shard '-1/4'"), "{err}");
}

#[test]
fn huge_values_are_shown_in_scientific_notation() {
    let tmp = tempfile::tempdir().unwrap();
    let study = tmp.path().join("neg.toml");
    std::fs::write(
        &study,
        format!(
            "[study]\nname = \"t\"\nclub = {:?}\n\n[delivery]\nclub_speed_mph = -1e300\n\
             dynamic_loft_deg = 12.0\n\n[grid]\ny_mm = {{ from = -10.0, to = 10.0, count = 5 }}\n\
             z_mm = {{ from = -10.0, to = 10.0, count = 5 }}\n",
            club()
        ),
    )
    .unwrap();
    let o = smash(&["run", s(&study), "--out", s(&tmp.path().join("o"))]);
    common::assert_refused(&o, &["club speed -1e300 is outside"]);
    assert!(stderr(&o).len() < 200, "{}", stderr(&o));
}

#[test]
fn a_study_whose_club_misses_the_ball_names_the_file_and_line() {
    let tmp = tempfile::tempdir().unwrap();
    let study = tmp.path().join("away.toml");
    std::fs::write(
        &study,
        format!(
            "[study]\nname = \"t\"\nclub = {:?}\n\n[delivery]\nclub_speed_mph = 100.0\n\
             dynamic_loft_deg = 12.0\nclub_path_deg = 60.0\nface_angle_deg = -60.0\n\n[grid]\n\
             y_mm = {{ from = -10.0, to = 10.0, count = 5 }}\n\
             z_mm = {{ from = -10.0, to = 10.0, count = 5 }}\n",
            club()
        ),
    )
    .unwrap();
    let o = smash(&["run", s(&study), "--out", s(&tmp.path().join("o"))]);
    common::assert_refused(
        &o,
        &["away.toml:5: table [delivery]: the club does not approach"],
    );
}

#[test]
fn shot_errors_name_file_line_and_columns_like_parse_errors() {
    let tmp = tempfile::tempdir().unwrap();
    let shots = tmp.path().join("s.csv");
    let out = tmp.path().join("p.csv");
    // Line 3 (the second shot) is far off the face (refused by its range); then line 3 swings away
    // from the ball (refused by the impact solve): both name file, line and column.
    for (second, want) in [
        (
            "s2,100,0,0,12,0,500,0",
            "s.csv:3: column 'impact_y_mm': impact location 500 is outside the physical range",
        ),
        (
            "s2,100,0,60,12,-60,0,0",
            "s.csv:3: columns club_speed_mph, attack_angle_deg",
        ),
    ] {
        std::fs::write(
            &shots,
            format!("{SHOTS_HEADER}s1,100,0,0,12,0,0,0\n{second}\n"),
        )
        .unwrap();
        let o = smash(&[
            "predict",
            "--club",
            &club(),
            "--shots",
            s(&shots),
            "--out",
            s(&out),
            // Without --strict the first is left out and counted (`bad_rows.rs`).
            "--strict",
        ]);
        common::assert_refused(&o, &[want]);
        assert!(!stderr(&o).contains("row "), "{}", stderr(&o));
        assert!(!out.exists());
    }
}
