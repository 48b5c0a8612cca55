//! The project file's layer (`smash.toml`, docs/commands.md, "Project defaults"): what it
//! states fills the flags left unset, a flag given wins, every value taken is named on stderr,
//! paths are the file's, a nearer file or `SMASH_CONFIG` chooses, and a bad file is refused in
//! one line.

use crate::cli_support;

use std::path::Path;
use std::process::{Command, Output};

use cli_support::{repo, s, stderr, SMASH};

/// `smash ARGS` run in `dir`, with `SMASH_CONFIG` set to `config` (or unset).
fn smash_in(dir: &Path, config: Option<&str>, args: &[&str]) -> Output {
    let mut c = Command::new(SMASH);
    c.args(args).current_dir(dir).env_remove("SMASH_CONFIG");
    if let Some(v) = config {
        c.env("SMASH_CONFIG", v);
    }
    c.output().unwrap()
}

const EXPORT: &str = "tests/data/real/rapsodo_mlm2pro_7i.csv";

#[test]
fn the_file_fills_what_the_flags_leave_unset_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let export = repo(EXPORT);
    // The reference: the format given as a flag, no project file.
    let flagged = dir.path().join("flagged.csv");
    let o = smash_in(
        dir.path(),
        Some("none"),
        &[
            "import",
            "--format",
            "rapsodo",
            s(&export),
            "--out",
            s(&flagged),
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!stderr(&o).contains("defaults from"), "{}", stderr(&o));
    // The same import with the format from the project file, run from a folder below it.
    std::fs::write(
        dir.path().join("smash.toml"),
        "[defaults]\nformat = \"rapsodo\"\n",
    )
    .unwrap();
    let sub = dir.path().join("session");
    std::fs::create_dir(&sub).unwrap();
    let o = smash_in(
        &sub,
        None,
        &["import", s(&export), "--out", "from_file.csv"],
    );
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("smash.toml: format = rapsodo"),
        "the value taken is named: {err}"
    );
    assert_eq!(
        std::fs::read(&flagged).unwrap(),
        std::fs::read(sub.join("from_file.csv")).unwrap()
    );
    // SMASH_CONFIG=none: no file, so import's own default, --format auto, which recognises the
    // layout and writes the same shots.
    let o = smash_in(
        &sub,
        Some("none"),
        &["import", s(&export), "--out", "x.csv"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("--format auto: read as rapsodo"),
        "{}",
        stderr(&o)
    );
    assert_eq!(
        std::fs::read(&flagged).unwrap(),
        std::fs::read(sub.join("x.csv")).unwrap()
    );
}

#[test]
fn a_flag_wins_over_the_file() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("smash.toml"),
        "[defaults]\ninstrument = \"radar\"\n",
    )
    .unwrap();
    let club = repo("configs/clubs/paper_driver.toml");
    let shots = cli_support::measured_shots(dir.path());
    let instrument = |extra: &[&str]| {
        let mut args = vec![
            "diagnose",
            "--club",
            s(&club),
            "--shots",
            s(&shots),
            "--json",
            "--max-steps",
            "1",
        ];
        args.extend_from_slice(extra);
        let o = smash_in(dir.path(), None, &args);
        assert!(o.status.success(), "{}", stderr(&o));
        let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        (
            j["noise_floor"]["instrument"]["name"]
                .as_str()
                .unwrap()
                .to_owned(),
            stderr(&o),
        )
    };
    let (name, err) = instrument(&[]);
    assert!(name.contains("radar"), "{name}");
    assert!(err.contains("instrument = radar"), "{err}");
    let (name, err) = instrument(&["--instrument", "camera"]);
    assert!(name.contains("camera"), "{name}");
    assert!(!err.contains("defaults from"), "nothing taken: {err}");
}

#[test]
fn paths_in_the_file_are_the_files_and_a_named_file_wins() {
    let dir = tempfile::tempdir().unwrap();
    let conf = dir.path().join("conf");
    std::fs::create_dir(&conf).unwrap();
    std::fs::copy(
        repo("configs/effects/example_effects.toml"),
        conf.join("effects.toml"),
    )
    .unwrap();
    let file = conf.join("project.toml");
    std::fs::write(&file, "[defaults]\neffect_defs = \"effects.toml\"\n").unwrap();
    // Run elsewhere with SMASH_CONFIG naming the file: the effects file is found beside it.
    let o = smash_in(dir.path(), Some(s(&file)), &["effects", "--json"]);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("effect_defs = "), "{err}");
    assert!(
        err.contains(&conf.join("effects.toml").display().to_string()),
        "{err}"
    );
}

#[test]
fn a_bad_file_is_refused_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            "[defaults]\nformatt = \"trackman\"\n",
            &["smash.toml:2", "formatt", "did you mean `format`"][..],
        ),
        (
            "[defaults]\ninstrument = \"lidar\"\n",
            &["smash.toml", "defaults.instrument", "allowed: camera"][..],
        ),
        (
            "[defaults]\nimpact_offset_positive = \"up\"\n",
            &["smash.toml:2", "impact_offset_positive", "toe"][..],
        ),
        (
            "[defaults]\nimpact_noise_mm = [3.0, -1.0]\n",
            &["smash.toml", "defaults.impact_noise_mm"][..],
        ),
        (
            "[default]\nformat = \"x\"\n",
            &["smash.toml:1", "defaults"][..],
        ),
    ];
    let club = repo("configs/clubs/paper_driver.toml");
    let shots = cli_support::measured_shots(dir.path());
    for (text, says) in cases {
        std::fs::write(dir.path().join("smash.toml"), text).unwrap();
        let o = smash_in(
            dir.path(),
            None,
            &["compare", "--club", s(&club), "--shots", s(&shots)],
        );
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{text}: {err}");
        assert_eq!(err.lines().count(), 1, "{text}: {err}");
        for w in says {
            assert!(err.contains(w), "{text}: {w:?} not in {err}");
        }
    }
}
