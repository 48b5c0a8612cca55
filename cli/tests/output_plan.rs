//! Every command checks all of its outputs together before any work and writes all or nothing
//! (issue 32, items 1–3 and 11–13): two outputs that are the same path or one inside the other
//! are refused, an unwritable output stops the command before it replaces any other, a
//! write-protected previous output folder is refused instead of hidden away, a failed merge names
//! its output folder, and shards run with `--effect-defs` merge.

use crate::cli_support;
use crate::common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use cli_support::{assert_kept, club, measured_shots, repo, s, smash, stderr, write, SMASH};

/// Names in `dir` starting with a dot (the commands' temporaries and kept-aside outputs).
fn hidden_in(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.'))
        .collect()
}

/// A small study of `outputs` with the paper's club.
fn study(dir: &Path, name: &str, outputs: &str) -> PathBuf {
    write(
        dir,
        name,
        &format!(
            "[study]\nname = \"t\"\nclub = {:?}\noutputs = [{outputs}]\n\n[delivery]\n\
             club_speed_mph = 100.0\ndynamic_loft_deg = 12.0\n\n[grid]\n\
             y_mm = {{ from = -10.0, to = 10.0, count = 5 }}\n\
             z_mm = {{ from = -10.0, to = 10.0, count = 5 }}\n",
            s(&repo("configs/clubs/paper_driver.toml"))
        ),
    )
}

/// Item 1: `--out-club` and `--report` the same path: refused before any work (it used to exit
/// 0 with the HTML report in place of the calibrated club).
#[test]
fn the_same_path_for_two_outputs_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let shots = measured_shots(d);
    let c = d.join("c.toml");
    for cmd in ["calibrate", "diagnose"] {
        let mut args = vec![cmd, "--club", "CLUB", "--shots", s(&shots)];
        if cmd == "calibrate" {
            args.extend(["--effects", "loft_bias"]);
        }
        args.extend(["--out-club", s(&c), "--report", s(&c)]);
        let club = club();
        let args: Vec<&str> = args
            .iter()
            .map(|a| if *a == "CLUB" { club.as_str() } else { a })
            .collect();
        let o = smash(&args);
        common::assert_refused(&o, &["c.toml", "--report and --out-club are the same path"]);
        assert!(!c.exists(), "{cmd} wrote {}", c.display());
    }
}

/// Item 2: an output that cannot be written (its parent is a file) stops `calibrate`,
/// `diagnose` and `run` before they replace their other output; `compare` refuses a report
/// inside, or at, its output folder before writing either.
#[test]
fn an_unwritable_output_leaves_every_other_output_as_it_was() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let shots = measured_shots(d);
    let blocker = write(d, "blocker", "a file, not a folder\n");
    let bad_report = blocker.join("r.html");
    let c = write(d, "c.toml", "# the user's earlier club\n");
    for cmd in ["calibrate", "diagnose"] {
        let club = club();
        let mut args = vec![cmd, "--club", &club, "--shots", s(&shots)];
        if cmd == "calibrate" {
            args.extend(["--effects", "loft_bias"]);
        }
        args.extend(["--out-club", s(&c), "--report", s(&bad_report)]);
        let o = smash(&args);
        common::assert_refused(&o, &["--report", "cannot"]);
        assert_kept(&c, "# the user's earlier club\n");
    }
    // run: the earlier outputs stay when the report cannot be written.
    let s1 = study(d, "s1.toml", "\"ball_speed_mph\", \"backspin_rpm\"");
    let s2 = study(d, "s2.toml", "\"ball_speed_mph\"");
    let out = d.join("od");
    let o = smash(&["run", s(&s1), "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let manifest = std::fs::read_to_string(out.join(".smash-outputs")).unwrap();
    assert!(manifest.contains("backspin"));
    let o = smash(&["run", s(&s2), "--out", s(&out), "--report", s(&bad_report)]);
    common::assert_refused(&o, &["--report", "cannot"]);
    assert_kept(&out.join(".smash-outputs"), &manifest);
    assert_eq!(hidden_in(d), Vec::<String>::new());
    // compare: a report inside the folder it replaces, or the folder itself.
    let od = d.join("cmp");
    for report in [od.join("r.html"), od.clone()] {
        let o = smash(&[
            "compare",
            "--club",
            &club(),
            "--shots",
            s(&shots),
            "--report",
            s(&report),
            "--out-dir",
            s(&od),
        ]);
        common::assert_refused(&o, &["--report"]);
        assert!(!od.exists(), "{} was written", od.display());
    }
}

/// The effective user id (from `/proc`): tests run as root cannot see write protection, so the
/// commands of [`write_protected_previous_outputs_are_refused_not_hidden`] then run as `nobody`.
fn euid() -> Option<u32> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("Uid:"))?;
    line.split_whitespace().nth(2)?.parse().ok()
}

fn smash_unprivileged(args: &[&str]) -> Output {
    let mut cmd = Command::new(SMASH);
    cmd.args(args);
    if euid() == Some(0) {
        use std::os::unix::process::CommandExt;
        cmd.uid(65534).gid(65534);
    }
    cmd.output().unwrap()
}

/// Item 3: a write-protected previous output folder was moved to a hidden `.od.old-PID` that
/// was never removed (exit 0, no word). It is refused before the work, and left as it was.
#[test]
fn write_protected_previous_outputs_are_refused_not_hidden() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::set_permissions(d, std::fs::Permissions::from_mode(0o777)).unwrap();
    let s1 = study(d, "s1.toml", "\"ball_speed_mph\", \"backspin_rpm\"");
    let s2 = study(d, "s2.toml", "\"ball_speed_mph\"");
    let out = d.join("od");
    let o = smash_unprivileged(&["run", s(&s1), "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let manifest = std::fs::read_to_string(out.join(".smash-outputs")).unwrap();
    std::fs::set_permissions(&out, std::fs::Permissions::from_mode(0o555)).unwrap();
    let o = smash_unprivileged(&["run", s(&s2), "--out", s(&out)]);
    std::fs::set_permissions(&out, std::fs::Permissions::from_mode(0o755)).unwrap();
    common::assert_refused(&o, &["od", "cannot be removed", "chmod"]);
    assert_kept(&out.join(".smash-outputs"), &manifest);
    assert_eq!(hidden_in(d), Vec::<String>::new());
}

/// Items 11 and 13: shards run with `--effect-defs` merge with `--effect-defs` into the
/// unsharded result; a merge that cannot write (a file-size limit standing in for a full disk)
/// names its output folder, not a hidden temporary, and leaves none.
#[test]
fn shards_with_user_effects_merge_and_a_failed_merge_names_its_output() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let defs = repo("configs/effects/example_effects.toml");
    let paper = std::fs::read_to_string(repo("configs/clubs/paper_driver.toml")).unwrap();
    let club_file = write(
        d,
        "club.toml",
        &format!("{paper}\n[[effect]]\nname = \"speed_loft\"\nk_deg = 0.5\n"),
    );
    let study_file = write(
        d,
        "study.toml",
        &format!(
            "[study]\nname = \"u\"\nclub = {:?}\noutputs = [\"ball_speed_mph\"]\n\n[delivery]\n\
             club_speed_mph = 100.0\ndynamic_loft_deg = 12.0\n\n[grid]\n\
             y_mm = {{ from = -10.0, to = 10.0, count = 5 }}\n\
             z_mm = {{ from = -10.0, to = 10.0, count = 5 }}\n",
            s(&club_file)
        ),
    );
    let whole = d.join("whole");
    let o = smash(&[
        "run",
        s(&study_file),
        "--effect-defs",
        s(&defs),
        "--out",
        s(&whole),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let shards: Vec<PathBuf> = (0..2).map(|k| d.join(format!("sh{k}"))).collect();
    for (k, sh) in shards.iter().enumerate() {
        let spec = format!("{k}/2");
        let o = smash(&[
            "run",
            s(&study_file),
            "--effect-defs",
            s(&defs),
            "--shard",
            &spec,
            "--out",
            s(sh),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    let merged = d.join("merged");
    let o = smash(&[
        "merge",
        s(&shards[0]),
        s(&shards[1]),
        "--effect-defs",
        s(&defs),
        "--out",
        s(&merged),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let map = "maps_long.csv";
    assert_eq!(
        std::fs::read(merged.join(map)).unwrap(),
        std::fs::read(whole.join(map)).unwrap()
    );
    // A write that fails part-way (RLIMIT_FSIZE, with SIGXFSZ ignored: EFBIG, as a full disk's
    // ENOSPC) names the output folder.
    let failed = d.join("failed");
    let o = Command::new("sh")
        .arg("-c")
        .arg(format!(
            "trap '' XFSZ; ulimit -f 1; exec '{SMASH}' merge '{}' '{}' --effect-defs '{}' --out '{}'",
            s(&shards[0]),
            s(&shards[1]),
            s(&defs),
            s(&failed)
        ))
        .output()
        .unwrap();
    common::assert_refused(&o, &["failed", "cannot write"]);
    assert!(!stderr(&o).contains(".failed."), "{}", stderr(&o));
    assert!(!failed.exists());
    assert!(
        !hidden_in(d).iter().any(|n| n.starts_with(".failed")),
        "{:?}",
        hidden_in(d)
    );
}

/// Item 13: a truth file of a world hiding a user-defined effect regenerates its shots byte for
/// byte without `--effect-defs` (configs/synth/README.md says it does).
#[test]
fn a_synth_truth_file_with_a_user_effect_regenerates_its_shots() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let config = write(
        d,
        "world.toml",
        &format!(
            "club = {:?}\nseed = 5\n[design]\ngolfers = 3\nswings_per_golfer = 2\n\n\
             [[hidden]]\nname = \"cor_oblique\"\nb_per_m_s = 0.003\n",
            s(&repo("configs/clubs/paper_driver.toml"))
        ),
    );
    let (a, truth, b) = (d.join("a.csv"), d.join("truth.toml"), d.join("b.csv"));
    let o = smash(&[
        "synth",
        "--config",
        s(&config),
        "--effect-defs",
        s(&repo("configs/effects/example_effects.toml")),
        "--out",
        s(&a),
        "--truth",
        s(&truth),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = smash(&["synth", "--config", s(&truth), "--out", s(&b)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
}
