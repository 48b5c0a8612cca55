//! A bad row does not sink a whole file in any command (issue 44, item 5): a hand-made shots
//! or launch file with a few rows whose measured cells cannot be used (a ball speed of 0 or
//! 900 mph, a launch angle of 95°, spin `abc`, a carry of 9999 yd) runs in `predict`,
//! `compare`, `calibrate`, `diagnose` and `flight` (plain, `--calibrate`, `--diagnose`): the
//! rows are left out, counted with their lines in one note per reason (stderr and the JSON's
//! `warnings`), and the good rows give exactly the numbers of the file without the bad rows.
//! `--strict` refuses the file in one line; a file most of whose rows are bad, or with none
//! usable, is refused in one line.

use crate::cli_support;

use std::path::{Path, PathBuf};

use cli_support::{club, measured_shots, repo, s, smash, unwrapped as stderr, write};

/// `clean` with bad rows inserted: `(file line at which it goes, row)`, in increasing line
/// order. Returns the file's path.
fn with_bad_rows(dir: &Path, clean: &Path, bad: &[(usize, String)], name: &str) -> PathBuf {
    let text = std::fs::read_to_string(clean).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    for (line, row) in bad {
        lines.insert(line - 1, row.clone());
    }
    write(dir, name, &(lines.join("\n") + "\n"))
}

/// Row `k` (1-based data row) of `path` with `column` set to `value` and its id made unique.
fn spoiled(path: &Path, k: usize, column: &str, value: &str) -> String {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let mut cells: Vec<String> = lines
        .nth(k - 1)
        .unwrap()
        .split(',')
        .map(str::to_owned)
        .collect();
    let i = header.iter().position(|h| *h == column).unwrap();
    cells[i] = value.to_owned();
    if let Some(id) = header.iter().position(|h| *h == "shot_id") {
        cells[id] = format!("bad_{k}_{column}");
    }
    cells.join(",")
}

/// The four bad rows every shots test inserts, at file lines 3, 10, 20 and 30 of the spoiled
/// file.
fn bad_shot_rows(clean: &Path) -> Vec<(usize, String)> {
    vec![
        (3, spoiled(clean, 1, "ball_speed_mph", "900")),
        (10, spoiled(clean, 2, "ball_speed_mph", "0")),
        (20, spoiled(clean, 3, "launch_angle_deg", "95")),
        (30, spoiled(clean, 4, "backspin_rpm", "abc")),
    ]
}

/// Run and return (success, stdout, stderr).
fn run(args: &[&str]) -> (bool, String, String) {
    let o = smash(args);
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        stderr(&o),
    )
}

/// The notes every shots command must print for [`bad_shot_rows`].
fn assert_notes(text: &str, file: &Path) {
    let f = file.display().to_string();
    for want in [
        "left out 2 of 44 rows: a value outside its physical range in column 'ball_speed_mph' (line(s) 3, 10; the first: ".to_owned(),
        format!("{f}:3: column 'ball_speed_mph': measured ball speed 900 is outside the physical range (0, 400] mph"),
        "left out 1 of 44 rows: a value outside its physical range in column 'launch_angle_deg' (line(s) 20;".to_owned(),
        format!("{f}:30: column 'backspin_rpm': 'abc' is not a number; --strict refuses the file"),
    ] {
        assert!(text.contains(&want), "missing «{want}» in:\n{text}");
    }
}

/// The JSON without its `warnings`, and the warnings.
fn split_warnings(json: &str) -> (serde_json::Value, Vec<String>) {
    let mut v: serde_json::Value = serde_json::from_str(json).unwrap();
    let w = v
        .as_object_mut()
        .unwrap()
        .remove("warnings")
        .expect("a warnings key");
    // The Rapsodo session's carries are its flight model (`flight_modelled = 1`): the caveat
    // on every run of it, and the count of shots compared, are not about bad rows
    // (`cli_flight_calibrate.rs` tests them).
    if let Some(e) = v.get_mut("errors").and_then(|e| e.as_object_mut()) {
        e.remove("compared");
        e.remove("modelled");
    }
    let w = w
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_str().unwrap().to_owned())
        .filter(|x| !x.contains("the vendor's flight model"))
        .collect();
    (v, w)
}

/// `cmd` on the clean and the spoiled file give the same JSON but for the warnings, which name
/// the bad rows; `--strict` refuses the spoiled file in one line.
fn same_on_good_rows(cmd: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let clean = measured_shots(dir.path());
    let bad = with_bad_rows(dir.path(), &clean, &bad_shot_rows(&clean), "bad.csv");
    let club = club();
    let with = |shots: &Path, extra: &[&str]| {
        let mut a: Vec<&str> = cmd.to_vec();
        a.extend(["--club", &club, "--shots", s(shots)]);
        a.extend_from_slice(extra);
        run(&a)
    };
    let (ok, want, e) = with(&clean, &["--json"]);
    assert!(ok, "{e}");
    let (ok, got, e) = with(&bad, &["--json"]);
    assert!(ok, "{cmd:?} refused a file with four bad rows: {e}");
    assert_notes(&e, &bad);
    let (want, others) = split_warnings(&want);
    let (got, warnings) = split_warnings(&got);
    let (notes, rest): (Vec<String>, Vec<String>) = warnings
        .into_iter()
        .partition(|w| w.starts_with("left out "));
    assert_eq!(rest, others, "{cmd:?}: other warnings changed");
    assert_eq!(got, want, "{cmd:?}: the good rows give other numbers");
    assert_eq!(notes.len(), 3, "{notes:?}");
    assert_notes(&notes.join("\n"), &bad);
    let (ok, out, e) = with(&bad, &["--strict"]);
    assert!(!ok && out.is_empty());
    assert_eq!(e.trim_end().lines().count(), 1, "{e}");
    assert!(
        e.contains(&format!("{}:3: column 'ball_speed_mph'", bad.display())),
        "{e}"
    );
}

#[test]
fn compare_leaves_bad_rows_out() {
    same_on_good_rows(&["compare"]);
}

#[test]
fn calibrate_leaves_bad_rows_out() {
    same_on_good_rows(&["calibrate", "--effects", "ball_offset"]);
}

#[test]
fn diagnose_leaves_bad_rows_out() {
    same_on_good_rows(&[
        "diagnose",
        "--candidates",
        "ball_offset",
        "--max-steps",
        "1",
    ]);
}

#[test]
fn predict_leaves_bad_rows_out() {
    let dir = tempfile::tempdir().unwrap();
    let clean = measured_shots(dir.path());
    let bad = with_bad_rows(dir.path(), &clean, &bad_shot_rows(&clean), "bad.csv");
    let (a, b) = (dir.path().join("a.csv"), dir.path().join("b.csv"));
    let predict = |shots: &Path, out: &Path, extra: &[&str]| {
        let club = club();
        let mut args = vec![
            "predict",
            "--club",
            &club,
            "--shots",
            s(shots),
            "--out",
            s(out),
        ];
        args.extend_from_slice(extra);
        run(&args)
    };
    let (ok, _, e) = predict(&clean, &a, &[]);
    assert!(ok, "{e}");
    let (ok, _, e) = predict(&bad, &b, &[]);
    assert!(ok, "{e}");
    assert_notes(&e, &bad);
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
    let (ok, _, e) = predict(&bad, &b, &["--strict"]);
    assert!(!ok && e.trim_end().lines().count() == 1, "{e}");
}

#[test]
fn most_rows_bad_or_none_usable_is_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let clean = measured_shots(dir.path());
    // 40 good rows and 41 bad ones: more than half.
    let mut rows = Vec::new();
    for k in 0..41 {
        rows.push((
            2 + 2 * k,
            spoiled(&clean, 1 + k % 40, "ball_speed_mph", "0"),
        ));
    }
    let rows: Vec<(usize, String)> = rows
        .into_iter()
        .enumerate()
        .map(|(i, (l, r))| (l, r.replace("bad_", &format!("b{i}_"))))
        .collect();
    let bad = with_bad_rows(dir.path(), &clean, &rows, "most.csv");
    let (ok, _, e) = run(&["compare", "--club", &club(), "--shots", s(&bad)]);
    assert!(!ok, "{e}");
    assert_eq!(e.trim_end().lines().count(), 1, "{e}");
    assert!(
        e.contains("41 of 81 rows hold values that cannot be used, more than half"),
        "{e}"
    );
}

/// A real MLM2PRO session imported to a launch file with Rapsodo's carry, apex and descent.
fn launch_file(dir: &Path) -> PathBuf {
    let out = dir.join("launch.csv");
    let (ok, _, e) = run(&[
        "import",
        "--format",
        "rapsodo",
        s(&repo("tests/data/real/rapsodo_mlm2pro_7i.csv")),
        "--out",
        s(&out),
    ]);
    assert!(ok, "{e}");
    out
}

#[test]
fn flight_in_every_mode_leaves_bad_rows_out() {
    let dir = tempfile::tempdir().unwrap();
    let clean = launch_file(dir.path());
    let bad_rows = vec![
        (4, spoiled(&clean, 1, "ball_speed_mph", "900")),
        (12, spoiled(&clean, 2, "launch_angle_deg", "95")),
        (20, spoiled(&clean, 3, "backspin_rpm", "abc")),
        (30, spoiled(&clean, 4, "carry_yd", "9999")),
    ];
    let bad = with_bad_rows(dir.path(), &clean, &bad_rows, "bad.csv");
    let f = bad.display().to_string();
    for mode in [&[][..], &["--calibrate", "drag"][..], &["--diagnose"][..]] {
        let fly = |shots: &Path, out: &str, extra: &[&str]| {
            let o = dir.path().join(out);
            let mut a = vec!["flight", "--shots", s(shots), "--out", s(&o)];
            a.extend_from_slice(mode);
            a.extend_from_slice(extra);
            let r = run(&a);
            (r, o)
        };
        let ((ok, want, e), a) = fly(&clean, "a.csv", &["--json"]);
        assert!(ok, "{mode:?}: {e}");
        let ((ok, got, e), b) = fly(&bad, "b.csv", &["--json"]);
        assert!(ok, "{mode:?} refused a launch file with four bad rows: {e}");
        for want in [
            format!("left out 1 of 63 rows: a launch value the flight model does not take in column 'ball_speed_mph' (line(s) 4; the first: {f}:4: column 'ball_speed_mph': ball_speed_mph = 900"),
            "in column 'launch_angle_deg' (line(s) 12;".to_owned(),
            format!("{f}:20: column 'backspin_rpm': 'abc' is not a finite number"),
            format!("a value outside its physical range in column 'carry_yd' (line(s) 30; the first: {f}:30: column 'carry_yd': measured carry 9999 is outside the physical range [-600, 600] yd"),
        ] {
            assert!(e.contains(&want), "{mode:?}: missing «{want}» in:\n{e}");
        }
        let (want, none) = split_warnings(&want);
        let (got, notes) = split_warnings(&got);
        assert!(none.is_empty());
        assert_eq!(notes.len(), 4, "{notes:?}");
        assert_eq!(got, want, "{mode:?}: the good rows give other numbers");
        assert_eq!(
            std::fs::read(&a).unwrap(),
            std::fs::read(&b).unwrap(),
            "{mode:?}: the flown file differs"
        );
        let ((ok, out, e), _) = fly(&bad, "c.csv", &["--strict"]);
        assert!(!ok && out.is_empty(), "{mode:?}");
        assert_eq!(e.trim_end().lines().count(), 1, "{mode:?}: {e}");
        assert!(
            e.contains(&format!("{f}:4: column 'ball_speed_mph'")),
            "{e}"
        );
        assert!(!dir.path().join("c.csv").exists());
    }
}

#[test]
fn flight_with_per_shot_conditions_leaves_bad_rows_out() {
    let dir = tempfile::tempdir().unwrap();
    let clean = launch_file(dir.path());
    // A temperature per shot: the path that flies each shot in its own air.
    let text = std::fs::read_to_string(&clean).unwrap();
    let mut lines = text.lines();
    let mut t = format!("{},air_temperature_c\n", lines.next().unwrap());
    for (k, l) in lines.enumerate() {
        t.push_str(&format!("{l},{}\n", 10 + k % 20));
    }
    let clean = write(dir.path(), "warm.csv", &t);
    let bad = with_bad_rows(
        dir.path(),
        &clean,
        &[
            (5, spoiled(&clean, 1, "air_temperature_c", "hot")),
            (9, spoiled(&clean, 2, "ball_speed_mph", "0")),
        ],
        "bad.csv",
    );
    let (a, b) = (dir.path().join("a.csv"), dir.path().join("b.csv"));
    let (ok, _, e) = run(&["flight", "--shots", s(&clean), "--out", s(&a)]);
    assert!(ok, "{e}");
    let (ok, _, e) = run(&["flight", "--shots", s(&bad), "--out", s(&b)]);
    assert!(ok, "{e}");
    assert!(e.contains("column 'air_temperature_c' (line(s) 5;"), "{e}");
    assert!(e.contains("column 'ball_speed_mph' (line(s) 9;"), "{e}");
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
}
