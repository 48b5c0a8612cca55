//! The command line at its edges: output that cannot be written, outputs that would replace a
//! user's files or the command's own inputs, outputs that appear together or not at all, and
//! stale temporaries of killed runs.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

const SMASH: &str = env!("CARGO_BIN_EXE_smash");

fn repo(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(rel)
}

fn smash(args: &[&str]) -> Output {
    Command::new(SMASH).args(args).output().unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A failure with exactly one line on stderr (no panic), which contains `want`.
fn assert_one_line_error(o: &Output, want: &str) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(1), "exit status; stderr: {err}");
    assert_eq!(err.lines().count(), 1, "one line: {err:?}");
    assert!(err.starts_with("error: "), "{err}");
    assert!(err.contains(want), "expected {want:?} in {err:?}");
    assert!(!err.contains("panicked"), "{err}");
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn club() -> String {
    repo("configs/clubs/paper_driver.toml")
        .to_str()
        .unwrap()
        .to_owned()
}

/// A shots file with measured launch: the golden deliveries with their reference launch as the
/// measurement.
fn measured_shots(dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(repo("tests/data/golden/nominal.csv")).unwrap();
    let text = text.replacen("pred_", "", 5);
    let path = dir.join("shots.csv");
    std::fs::write(&path, text).unwrap();
    path
}

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
        assert_one_line_error(&o, "cannot write to standard output");
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

fn assert_kept(path: &Path, text: &str) {
    assert_eq!(
        std::fs::read_to_string(path).unwrap(),
        text,
        "{} was changed",
        path.display()
    );
}

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
    assert_one_line_error(&o, "notes.md");
    assert_kept(&out.join("notes.md"), "my notes");
    assert!(out.join("study.toml").is_file());
    // Without them, the earlier outputs are replaced as before.
    std::fs::remove_file(out.join("notes.md")).unwrap();
    let o = smash(&["run", s(&study), "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    // The folder holding the study itself is refused.
    let o = smash(&["run", s(&study), "--out", s(tmp.path())]);
    assert_one_line_error(&o, "STUDY.toml");
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
    assert_one_line_error(&o, "thesis.tex");
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
    assert_one_line_error(&o, "thesis.tex");
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
    assert_one_line_error(&o, "--shots");
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
    assert_one_line_error(&o, "--out is the same file as --shots");
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
        assert_one_line_error(&o, "--out-club is the same file as --club");
        assert_kept(&club_copy, &club_text);
    }
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
    assert_one_line_error(&o, "truth.toml");
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
    assert_one_line_error(&o, "same path");
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
