//! The third hostile pass (issue 41): the project file's paths, outputs over the project file,
//! balls that never leave the ground, club files and what-if heads out of range, and messages
//! that were too loud or gave no hint. One function per theme, to keep process launches few.

use crate::cli_support;
use crate::common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use cli_support::{assert_kept, club, measured_shots, repo, s, smash, stderr, write, SMASH};

/// `smash ARGS` run in `dir` with whatever project file is found there (`SMASH_CONFIG` unset).
fn smash_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(SMASH)
        .args(args)
        .current_dir(dir)
        .env_remove("SMASH_CONFIG")
        .output()
        .unwrap()
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
    // The project file SMASH_CONFIG names is protected the same way, by its real path.
    let named = write(d, "team.toml", project);
    std::fs::create_dir_all(d.join("sub")).unwrap();
    let o = Command::new(SMASH)
        .args(["predict", "--club", &c, "--shots", &sh, "--out"])
        .arg(d.join("sub/../team.toml"))
        .current_dir(d)
        .env("SMASH_CONFIG", &named)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("(the project file)"), "{}", stderr(&o));
    assert_kept(&named, project);
    // A one-delivery predict writes nothing and is not refused.
    let mut args = vec!["predict", "--club", c.as_str()];
    args.extend_from_slice(&one);
    let o = smash_in(d, &args);
    assert!(o.status.success(), "{}", stderr(&o));
}

/// The paper driver's club file with `from` replaced by `to`, written to `dir/name`.
fn club_with(dir: &Path, name: &str, from: &str, to: &str) -> PathBuf {
    let text = std::fs::read_to_string(repo("configs/clubs/paper_driver.toml")).unwrap();
    assert!(text.contains(from), "{from}");
    write(dir, name, &text.replace(from, to))
}

/// Item 4: a club's loft outside any club's, a what-if head beyond a club file's limits and a
/// discretionary mass as heavy as the head are refused in one line with the allowed range; a
/// club written under `--ignore-club-mismatch` says so in the file.
#[test]
fn club_files_and_changed_heads_are_checked() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let one = ["--speed", "100", "--loft", "12"];
    for loft in ["1000", "-5", "80.5"] {
        let c = club_with(d, "c.toml", "loft_deg = 9.8", &format!("loft_deg = {loft}"));
        let mut args = vec!["predict", "--club", s(&c)];
        args.extend_from_slice(&one);
        common::assert_refused(
            &smash(&args),
            &["c.toml:", "club.loft_deg", loft, "[0, 80] deg"],
        );
    }
    // The edges are clubs: a zero-loft putter, an 80° wedge.
    for loft in ["0", "80"] {
        let c = club_with(d, "c.toml", "loft_deg = 9.8", &format!("loft_deg = {loft}"));
        let mut args = vec!["predict", "--club", s(&c)];
        args.extend_from_slice(&one);
        let o = smash(&args);
        assert!(o.status.success(), "{loft}: {}", stderr(&o));
    }
    // A what-if scaling re-checked against the club file's inertia cap.
    let c = club();
    let whatif = |extra: &[&str]| {
        let mut args = vec!["whatif", "--club", c.as_str(), "--speed", "95"];
        args.extend_from_slice(extra);
        smash(&args)
    };
    common::assert_refused(
        &whatif(&["--moi-scale", "1e6"]),
        &[
            "--moi-scale 1000000: the changed head's club inertia entry 2.843e9",
            "is outside the physical range [-1000000, 1000000] g·cm²",
        ],
    );
    common::assert_refused(
        &whatif(&["--loft-change-deg", "100"]),
        &[
            "--loft-change-deg 100:",
            "dynamic loft 113 is outside the physical range [-90, 90] deg",
        ],
    );
    common::assert_refused(
        &whatif(&["--com-shift-mm", "0,600,0"]),
        &[
            "--com-shift-mm 0,600,0: the changed head's club centre of mass",
            "[-500, 500] mm",
        ],
    );
    common::assert_refused(
        &whatif(&["--move-mass", "204g:-70,0,0:-80,0,0"]),
        &[
            "204 g is not part of the head",
            "below the head mass, 204 g",
        ],
    );
    // A discretionary mass as heavy as the head, in a study's [design] and [yards].
    let study = |table: &str| {
        format!(
            "[study]\nname = \"m\"\nclub = {:?}\noutputs = [\"ball_speed_mph\"]\n\n\
             [delivery]\nclub_speed_mph = 100.0\ndynamic_loft_deg = 12.0\n\n\
             [grid]\ny_mm = {{ from = -2.0, to = 2.0, count = 3 }}\n\
             z_mm = {{ from = -2.0, to = 2.0, count = 3 }}\n\n{table}",
            club()
        )
    };
    let design = write(
        d,
        "design.toml",
        &study(
            "[design]\ndiscretionary_mass = { mass_g = 204.0, at_mm = [-70.0, -10.0, 0.0] }\n\
             mass_dz_mm = [0.0, 5.0]\n",
        ),
    );
    let out = d.join("out");
    let o = smash(&["run", s(&design), "--out", s(&out)]);
    common::assert_refused(
        &o,
        &[
            "design.toml:",
            "design.discretionary_mass.mass_g",
            "below the head mass, 204 g",
        ],
    );
    assert!(!out.exists());
    let yards = write(
        d,
        "yards.toml",
        &study(
            "[distribution]\nmethod = \"quadrature\"\nnodes = 2\nsigma_y_mm = 4.0\n\n\
             [yards]\nstatic_loft_deg = 10.5\n\n\
             [yards.mass]\nmass_g = 204.0\nat_mm = [-70.0, -10.0, 0.0]\n\
             bounds_mm = [[-5.0, 5.0], [-5.0, 5.0], [-5.0, 5.0]]\n",
        ),
    );
    let o = smash(&["run", s(&yards), "--out", s(&out)]);
    common::assert_refused(
        &o,
        &[
            "yards.toml:",
            "yards.mass.mass_g",
            "below the head mass, 204 g",
        ],
    );
    // Fitted to another club's shots: the written club says so.
    let wedge = club_with(d, "wedge.toml", "loft_deg = 9.8", "loft_deg = 56.0");
    let shots = measured_shots(d);
    let out_club = d.join("fitted.toml");
    let o = smash(&[
        "calibrate",
        "--club",
        s(&wedge),
        "--shots",
        s(&shots),
        "--effects",
        "loft_bias",
        "--ignore-club-mismatch",
        "--out-club",
        s(&out_club),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let written = std::fs::read_to_string(&out_club).unwrap();
    let mark = written
        .lines()
        .find(|l| l.contains("--ignore-club-mismatch"))
        .unwrap_or_else(|| panic!("no mark in:\n{written}"));
    assert!(
        mark.starts_with("# WARNING: fitted under --ignore-club-mismatch: the shots do not match"),
        "{mark}"
    );
    // And the file still reads as a club.
    let mut args = vec!["predict", "--club", s(&out_club)];
    args.extend_from_slice(&one);
    assert!(smash(&args).status.success());
    // Without the flag (shots that match) there is no such line.
    let o = smash(&[
        "calibrate",
        "--club",
        &club(),
        "--shots",
        s(&shots),
        "--effects",
        "loft_bias",
        "--out-club",
        s(&out_club),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let written = std::fs::read_to_string(&out_club).unwrap();
    assert!(!written.contains("WARNING"), "{written}");
}

/// Item 2: balls driven into the ground are counted and named; when most of the distribution
/// never flies, carry and dispersion are refused in one line (they were 0 yd and "−100 %", exit
/// 0), in a what-if and in a `[yards]` study alike, and no output file is written.
#[test]
fn balls_that_never_fly_are_counted_and_too_many_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let c = club();
    let csv = d.join("w.csv");
    let whatif = |change: &str| {
        smash(&[
            "whatif",
            "--club",
            &c,
            "--speed",
            "95",
            "--loft-change-deg",
            change,
            "--out",
            s(&csv),
        ])
    };
    let o = whatif("-20");
    common::assert_refused(
        &o,
        &[
            "the changed head: 25 of 25 impacts (100.0 % of the distribution's weight)",
            "never fly",
            "not reported when more than 50 % of the weight never flies",
        ],
    );
    assert!(o.stdout.is_empty());
    assert!(!csv.exists());
    // A few topped balls among many: reported, counted with 0 yd, and named.
    let o = whatif("-12.5");
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8(o.stdout).unwrap();
    assert!(
        out.contains(
            "changed head: 10 of 25 impacts (23.3 % of the weight) launch into the ground and \
             never fly (counted as 0 yd carry)"
        ),
        "{out}"
    );
    assert!(!out.contains("base head:"), "{out}");
    let note = out.lines().find(|l| l.contains("into the ground")).unwrap();
    assert!(note.chars().count() <= 120, "{note}");
    assert!(!common::has_non_finite(&out), "{out}");
    let written = std::fs::read_to_string(&csv).unwrap();
    let head: Vec<&str> = written.lines().next().unwrap().split(',').collect();
    assert_eq!(head.last(), Some(&"grounded_pct"));
    assert!(written.lines().nth(1).unwrap().ends_with(",0"), "{written}");
    // A [yards] study whose swing drives every ball into the ground.
    let study = write(
        d,
        "low.toml",
        &format!(
            "[study]\nname = \"low\"\nclub = {c:?}\noutputs = [\"ball_speed_mph\"]\n\n\
             [delivery]\nclub_speed_mph = 95.0\ndynamic_loft_deg = -8.0\n\n\
             [distribution]\nmethod = \"quadrature\"\nnodes = 2\nsigma_y_mm = 4.0\n\n\
             [grid]\ny_mm = {{ from = -2.0, to = 2.0, count = 2 }}\n\
             z_mm = {{ from = -2.0, to = 2.0, count = 2 }}\n\n\
             [yards]\nstatic_loft_deg = 10.5\n"
        ),
    );
    let out = d.join("low_out");
    let o = smash(&["run", s(&study), "--out", s(&out)]);
    common::assert_refused(&o, &["[yards] base design", "never fly"]);
    assert!(!out.exists());
}

/// `text` as UTF-16 (little- or big-endian), with or without a byte-order mark.
fn utf16(text: &str, little: bool, bom: bool) -> Vec<u8> {
    let mut out: Vec<u8> = Vec::new();
    let units = bom.then_some(0xFEFF).into_iter().chain(text.encode_utf16());
    for u in units {
        out.extend(if little {
            u.to_le_bytes()
        } else {
            u.to_be_bytes()
        });
    }
    out
}

/// Item 6: the loud ones. UTF-16 given to a reader of UTF-8 is named in one short line with
/// the conversion; a header of thousands of columns is listed as its first few names and "and N
/// more"; a project's `format` applied to a shots file hints at `--format shots`.
#[test]
fn loud_messages_are_short_and_give_the_hint() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let shots_text = std::fs::read_to_string(measured_shots(d)).unwrap();
    let club_text = std::fs::read_to_string(repo("configs/clubs/paper_driver.toml")).unwrap();
    let launch_text = "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\nd1,150,12,2600\n";
    let c = club();
    let out = d.join("out.csv");
    for (little, bom) in [(true, false), (false, false), (true, true)] {
        let name = if little { "UTF-16LE" } else { "UTF-16BE" };
        let want = if bom {
            format!("the file is {name} text (it starts with a byte-order mark)")
        } else {
            format!("the file looks like {name} text without a byte-order mark")
        };
        let iconv = format!("iconv -f {name} -t UTF-8");
        let file = |n: &str, text: &str| {
            let p = d.join(n);
            std::fs::write(&p, utf16(text, little, bom)).unwrap();
            p
        };
        let shots = file("s16.csv", &shots_text);
        let launch = file("l16.csv", launch_text);
        let club16 = file("c16.toml", &club_text);
        for args in [
            vec![
                "predict",
                "--club",
                &c,
                "--shots",
                s(&shots),
                "--out",
                s(&out),
            ],
            vec!["compare", "--club", &c, "--shots", s(&shots)],
            vec!["flight", "--shots", s(&launch), "--out", s(&out)],
            vec![
                "predict",
                "--club",
                s(&club16),
                "--speed",
                "100",
                "--loft",
                "12",
            ],
        ] {
            let o = smash(&args);
            common::assert_refused(&o, &[":1: ", &want, &iconv]);
            assert!(stderr(&o).len() < 400, "{}", stderr(&o));
            assert!(!stderr(&o).contains("\\0"), "{}", stderr(&o));
            assert!(!out.exists());
        }
    }
    // An export missing the preset's columns, with 5,000 others and one 100 kB name.
    let mut head: Vec<String> = (0..5000).map(|i| format!("Extra {i}")).collect();
    head.insert(3, "N".repeat(100_000));
    let wide = write(
        d,
        "wide.csv",
        &format!("{}\n{}\n", head.join(","), vec!["1"; head.len()].join(",")),
    );
    let o = smash(&["import", "--format", "trackman", s(&wide), "--out", s(&out)]);
    common::assert_refused(
        &o,
        &[
            "not a TrackMan export as expected",
            "the file has: Extra 0, Extra 1, Extra 2, NNNN",
            "N…, Extra 3,",
            "… and 4981 more",
        ],
    );
    assert!(stderr(&o).len() < 1500, "{} bytes", stderr(&o).len());
    // A project's format on a shots file: the refusal says to read it with --format shots.
    let proj = d.join("proj");
    std::fs::create_dir(&proj).unwrap();
    write(&proj, "smash.toml", "[defaults]\nformat = \"trackman\"\n");
    let shots = write(&proj, "shots.csv", &shots_text);
    let args = [
        "predict",
        "--club",
        &c,
        "--shots",
        "shots.csv",
        "--out",
        "p.csv",
    ];
    let o = smash_in(&proj, &args);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    let line = err.lines().find(|l| l.starts_with("error: ")).unwrap();
    assert!(
        line.contains("shots.csv looks like a shots file already")
            && line.contains("read it with --format shots")
            && line.contains(&format!(
                "format = trackman is the project file {}'s",
                proj.join("smash.toml").display()
            )),
        "{line}"
    );
    // And so it reads.
    let mut with = args.to_vec();
    with.extend(["--format", "shots"]);
    let o = smash_in(&proj, &with);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(shots.exists());
}
