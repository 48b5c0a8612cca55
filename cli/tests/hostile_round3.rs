//! The third hostile pass (issue 41): the project file's paths, outputs over the project file,
//! balls that never leave the ground, club files and what-if heads out of range, and messages
//! that were too loud or gave no hint. One function per theme, to keep process launches few.

mod cli_support;
#[path = "../../tests/common/mod.rs"]
mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use cli_support::{assert_kept, club, measured_shots, repo, s, smash, stderr, SMASH};

/// `smash ARGS` run in `dir` with whatever project file is found there (`SMASH_CONFIG` unset).
fn smash_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(SMASH)
        .args(args)
        .current_dir(dir)
        .env_remove("SMASH_CONFIG")
        .output()
        .unwrap()
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

const EXPORT: &str = "tests/data/real/rapsodo_mlm2pro_7i.csv";

/// Item 1: `format = "mon.toml"` in a project file is the mapping beside the project file, from
/// a subfolder and next to another monitor's `mon.toml` alike; so are `noise` and
/// `effect_defs`.
#[test]
fn the_project_files_paths_are_relative_to_the_project_file() {
    let tmp = tempfile::tempdir().unwrap();
    let proj = tmp.path().join("proj");
    let sub = proj.join("session");
    std::fs::create_dir_all(&sub).unwrap();
    let export = repo(EXPORT);
    // The reference: the preset as a flag, no project file.
    let want = tmp.path().join("want.csv");
    let o = smash(&[
        "import",
        "--format",
        "rapsodo",
        s(&export),
        "--out",
        s(&want),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let want = std::fs::read_to_string(&want).unwrap();
    std::fs::copy(repo("configs/import/rapsodo.toml"), proj.join("mon.toml")).unwrap();
    write(&proj, "smash.toml", "[defaults]\nformat = \"mon.toml\"\n");
    // From a subfolder: it used to look for ./mon.toml there and fail.
    let o = smash_in(&sub, &["import", s(&export), "--out", "a.csv"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let mapping = proj.join("mon.toml");
    assert!(
        stderr(&o).contains(&format!("format = {}", mapping.display())),
        "{}",
        stderr(&o)
    );
    assert_eq!(std::fs::read_to_string(sub.join("a.csv")).unwrap(), want);
    // Beside another monitor's mon.toml: that one used to be used silently.
    std::fs::copy(repo("configs/import/trackman.toml"), sub.join("mon.toml")).unwrap();
    let o = smash_in(&sub, &["import", s(&export), "--out", "b.csv"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(sub.join("b.csv")).unwrap(), want);
    // A preset name stays a preset, whatever file of that name lies about.
    write(&proj, "smash.toml", "[defaults]\nformat = \"rapsodo\"\n");
    let o = smash_in(&sub, &["import", s(&export), "--out", "c.csv"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("format = rapsodo"), "{}", stderr(&o));
    // The other path-valued keys: named on stderr as the project file's.
    write(
        &proj,
        "smash.toml",
        "[defaults]\nnoise = \"noise.toml\"\neffect_defs = \"fx.toml\"\n",
    );
    let o = smash_in(
        &sub,
        &[
            "diagnose",
            "--club",
            &club(),
            "--shots",
            "no_such_shots.csv",
        ],
    );
    let err = stderr(&o);
    for key in ["noise", "effect_defs"] {
        let file = if key == "noise" {
            "noise.toml"
        } else {
            "fx.toml"
        };
        assert!(
            err.contains(&format!("{key} = {}", proj.join(file).display())),
            "{err}"
        );
    }
}

/// Item 3: no output of any command may be the project file the command read (or any other
/// input); the file is left as it was and the refusal names it.
#[test]
fn no_output_may_replace_the_project_file() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let project = "[defaults]\nimpact_noise_mm = [3.0, 2.5]\n";
    let file = write(d, "smash.toml", project);
    let shots = measured_shots(d);
    let sh = s(&shots).to_owned();
    let c = club();
    let launch = write(
        d,
        "launch.csv",
        "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\nd1,150,12,2600\n",
    );
    let world = repo("configs/synth/paper_world.toml");
    let study = repo("configs/studies/face_map.toml");
    let one = ["--speed", "100", "--loft", "12"];
    let cases: Vec<Vec<&str>> = vec![
        vec![
            "predict",
            "--club",
            &c,
            "--shots",
            &sh,
            "--out",
            "smash.toml",
        ],
        vec![
            "predict",
            "--club",
            &c,
            "--shots",
            &sh,
            "--out",
            "./smash.toml",
        ],
        vec!["synth", "--config", s(&world), "--out", "smash.toml"],
        vec![
            "synth",
            "--config",
            s(&world),
            "--out",
            "w.csv",
            "--truth",
            "smash.toml",
        ],
        vec![
            "calibrate",
            "--club",
            &c,
            "--shots",
            &sh,
            "--effects",
            "added_mass",
            "--out-club",
            "smash.toml",
        ],
        vec![
            "diagnose",
            "--club",
            &c,
            "--shots",
            &sh,
            "--out-club",
            "smash.toml",
        ],
        vec![
            "compare",
            "--club",
            &c,
            "--shots",
            &sh,
            "--report",
            "smash.toml",
        ],
        vec!["flight", "--shots", s(&launch), "--out", "smash.toml"],
        vec!["import", "--format", "rapsodo", "X", "--out", "smash.toml"],
        vec![
            "whatif",
            "--club",
            &c,
            "--speed",
            "95",
            "--moi-scale",
            "1.1",
            "--out",
            "smash.toml",
        ],
        vec![
            "whatif",
            "--club",
            &c,
            "--speed",
            "95",
            "--moi-scale",
            "1.1",
            "--report",
            "smash.toml",
        ],
        vec!["run", s(&study), "--report", "smash.toml"],
    ];
    let export = repo(EXPORT);
    for args in cases {
        let args: Vec<&str> = args
            .iter()
            .map(|a| if *a == "X" { s(&export) } else { a })
            .collect();
        let o = smash_in(d, &args);
        let err = stderr(&o);
        let line = err
            .lines()
            .find(|l| l.starts_with("error: "))
            .unwrap_or_else(|| panic!("{args:?} was not refused: {err}"));
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
        assert!(
            line.contains("smash.toml") && line.contains("the project file"),
            "{args:?}: {line}"
        );
        assert_kept(&file, project);
    }
    // An output folder that holds the project file would replace it with the folder.
    let o = smash_in(
        d,
        &["compare", "--club", &c, "--shots", &sh, "--out-dir", "."],
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert_kept(&file, project);
    // A one-delivery predict writes nothing and is not refused.
    let mut args = vec!["predict", "--club", c.as_str()];
    args.extend_from_slice(&one);
    let o = smash_in(d, &args);
    assert!(o.status.success(), "{}", stderr(&o));
}
