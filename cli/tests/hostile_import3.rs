//! Issue 41's headline import cases, checked again in the layouts the issue describes, and the
//! flight commands' sessions: a row cut short (unquoted or inside a quoted cell), a units row
//! anywhere in the first lines, measured flight columns out of range, and Excel serial dates
//! as sessions of `flight --calibrate-by session` and `--diagnose`.

use crate::cli_support;

use std::path::{Path, PathBuf};

use cli_support::{repo, s, smash, unwrapped as stderr};

use crate::common;

fn fixture(name: &str) -> String {
    std::fs::read_to_string(repo(&format!("cli/tests/fixtures/import/{name}"))).unwrap()
}

/// Import `text` (as `name`) with `format` and `flags`: the output (when written), the header
/// and rows, and stderr.
fn import(
    dir: &Path,
    name: &str,
    text: &str,
    format: &str,
    flags: &[&str],
) -> (std::process::Output, Vec<String>, Vec<Vec<String>>, PathBuf) {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    let out = dir.join(format!("{name}.shots.csv"));
    let _ = std::fs::remove_file(&out);
    let mut args = vec!["import", "--format", format, s(&path), "--out", s(&out)];
    args.extend_from_slice(flags);
    let o = smash(&args);
    let (mut h, mut rows) = (Vec::new(), Vec::new());
    if o.status.success() {
        let mut rdr = csv::Reader::from_path(&out).unwrap();
        h = rdr.headers().unwrap().iter().map(str::to_owned).collect();
        rows = rdr
            .records()
            .map(|r| r.unwrap().iter().map(str::to_owned).collect())
            .collect();
    }
    (o, h, rows, out)
}

fn col<'a>(h: &[String], rows: &'a [Vec<String>], name: &str) -> Vec<&'a str> {
    let i = h.iter().position(|c| c == name).unwrap();
    rows.iter().map(|r| r[i].as_str()).collect()
}

/// 41.2 in the layout: a range export's last shot cut after 11 of its 18 cells, in
/// its carry (`24` of `241.8`), is left out and counted; so is a last row cut inside a quoted
/// cell (the CSV reader closes the cell at the end of the file and would read the row whole),
/// and a middle row whose cut left a quote open that swallowed the next line: both lines are
/// counted, the other shots are kept as they were.
#[test]
fn rows_cut_short_are_counted_never_written() {
    let dir = tempfile::tempdir().unwrap();
    let text = fixture("uneekor_range.csv");
    let lines: Vec<&str> = text.lines().collect();
    // The last Driver shot (`Driver,4,…`), the summary rows under it dropped.
    let at = lines
        .iter()
        .position(|l| l.starts_with("Driver,4,"))
        .unwrap();
    let cells: Vec<&str> = lines[at].split(',').collect();
    assert_eq!((cells.len(), cells[10]), (18, "241.8"));
    let cut = format!("{},24", cells[..10].join(","));
    let short = format!("{}\n{cut}\n", lines[..at].join("\n"));
    let (o, h, rows, _) = import(dir.path(), "r.csv", &short, "uneekor", &[]);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert_eq!(rows.len(), 7, "{err}");
    assert!(!col(&h, &rows, "carry_yd").contains(&"24"), "{err}");
    assert!(
        err.contains("left out 1 row(s): fewer cells than the header has columns (line(s) 13"),
        "{err}"
    );

    // Quoted cells (Rapsodo's layout): the last row cut inside its spin axis, `"-3.` of
    // `"-3.5"`: the file ends in the open quote.
    let real = std::fs::read_to_string(repo("tests/data/real/rapsodo_mlm2pro_7i.csv")).unwrap();
    let whole = import(dir.path(), "w.csv", &real, "rapsodo", &[]);
    assert!(whole.0.status.success(), "{}", stderr(&whole.0));
    let lines: Vec<&str> = real.lines().collect();
    let last = lines
        .iter()
        .rposition(|l| l.starts_with("\"7i\"") || l.starts_with("\"7 Iron\""))
        .unwrap_or(lines.len() - 1);
    let quote = lines[last].rfind(",\"").unwrap() + 4;
    let cut = format!("{}\n{}", lines[..last].join("\n"), &lines[last][..quote]);
    let (o, _, rows, _) = import(dir.path(), "q.csv", &cut, "rapsodo", &[]);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert_eq!(rows.len() + 1, whole.2.len(), "{err}");
    assert!(err.contains("cut short inside a quoted cell"), "{err}");
    assert_eq!(rows[..], whole.2[..rows.len()], "the other shots changed");

    // A middle row cut in its first quoted cell: the open quote takes the next line.
    let mid = lines.len() / 2;
    let cut = format!(
        "{}\n\"7\n{}\n",
        lines[..mid].join("\n"),
        lines[mid + 1..].join("\n")
    );
    let (o, _, rows, _) = import(dir.path(), "m.csv", &cut, "rapsodo", &[]);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert_eq!(rows.len() + 2, whole.2.len(), "{err}");
    assert!(
        err.contains(&format!(
            "left out 2 row(s): a quoted cell runs over its line's end (line(s) {}, {}",
            mid + 1,
            mid + 2
        )),
        "{err}"
    );
}

/// 41.3 in more places: a units row is applied or refused, never ignored. Above a Rapsodo
/// export's title line it is applied (`[m]`: 156.4 m of carry is 171.0 yd); a GSPro file whose
/// first cell is `[m]` is a CSV, not "not valid JSON"; a second units row that disagrees with
/// the first, or one among the shots that disagrees with the file's units, refuses the file
/// in one line; one among the shots that agrees is skipped and counted.
#[test]
fn units_rows_anywhere_are_applied_or_refused() {
    let dir = tempfile::tempdir().unwrap();
    let real = std::fs::read_to_string(repo("tests/data/real/rapsodo_mlm2pro_7i.csv")).unwrap();
    let plain = import(dir.path(), "p.csv", &real, "rapsodo", &[]);
    assert!(plain.0.status.success(), "{}", stderr(&plain.0));
    let header = real.lines().nth(2).unwrap();
    let units: Vec<&str> = header
        .split(',')
        .map(|c| match c {
            "\"Carry Distance\"" | "\"Total Distance\"" => "[m]",
            "\"Ball Speed\"" | "\"Club Speed\"" => "[km/h]",
            _ => "",
        })
        .collect();
    let above = format!("{}\n{real}", units.join(","));
    let (o, h, rows, _) = import(dir.path(), "a.csv", &above, "rapsodo", &[]);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("the units row is line 1"), "{err}");
    let (was, now) = (
        col(&plain.1, &plain.2, "carry_yd"),
        col(&h, &rows, "carry_yd"),
    );
    for (w, n) in was.iter().zip(&now) {
        let (w, n): (f64, f64) = (w.parse().unwrap(), n.parse().unwrap());
        assert!(
            (n - w / 0.9144).abs() < 1e-9 * w,
            "{w} yd read as {n}: {err}"
        );
    }

    let gspro = fixture("gspro.csv");
    let head = gspro.lines().next().unwrap();
    let row: Vec<&str> = head
        .split(',')
        .map(|c| match c {
            "Carry" | "TotalDistance" => "[m]",
            "BallSpeed" | "ClubSpeed" => "[km/h]",
            _ => "",
        })
        .collect();
    let with = format!("{}\n{gspro}", row.join(","));
    let (o, h, rows, _) = import(
        dir.path(),
        "g.csv",
        &with,
        "gspro",
        &["--impact-offset-positive", "toe"],
    );
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    let ball: f64 = col(&h, &rows, "ball_speed_mph")[0].parse().unwrap();
    assert!((ball - 90.48284 / 1.609344).abs() < 1e-9, "{ball}: {err}");

    // TrackMan's units row, and a second one that says km/h: refused, naming both lines.
    let tm = fixture("trackman_older.csv");
    let lines: Vec<&str> = tm.lines().collect();
    let kmh = lines[1].replace("[mph]", "[km/h]");
    let two = format!("{kmh}\n{tm}");
    let (o, ..) = import(
        dir.path(),
        "t.csv",
        &two,
        "trackman",
        &["--impact-offset-positive", "toe"],
    );
    common::assert_refused(
        &o,
        &["a second units row: line 1 says '[km/h]' and line 3 says '[mph]'"],
    );
    // Under the third shot: disagreeing, refused; agreeing, skipped and counted.
    let deep = |row: &str| {
        let mut l = lines.clone();
        l.insert(5, row);
        l.join("\n")
    };
    let (o, ..) = import(
        dir.path(),
        "d.csv",
        &deep(&kmh),
        "trackman",
        &["--impact-offset-positive", "toe"],
    );
    common::assert_refused(
        &o,
        &[
            "d.csv:6:",
            "a units row among the shots says '[km/h]'",
            "read in mph",
        ],
    );
    let (o, _, rows, _) = import(
        dir.path(),
        "e.csv",
        &deep(lines[1]),
        "trackman",
        &["--impact-offset-positive", "toe"],
    );
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert_eq!(rows.len(), 8, "{err}");
    assert!(
        err.contains("skipped 1 repeated units row(s), never shots (line(s) 6)"),
        "{err}"
    );
}

/// Item B: measured flight columns out of their range (a carry of 5000 yd, an apex of −3 yd,
/// a flight time of 0 s, a −2147483648 carry) are read as not measured and counted; GSPro's
/// `ClubSpeed` 0 on every shot and Foresight's club cells of 16777216 leave a file of complete
/// launches: its shots are kept (without a delivery) and `smash flight` flies every one.
#[test]
fn measured_flight_columns_are_range_checked() {
    let dir = tempfile::tempdir().unwrap();
    let fly = |shots: &Path, n: usize| {
        let out = dir.path().join("flown.csv");
        let o = smash(&["flight", "--shots", s(shots), "--out", s(&out)]);
        assert!(o.status.success(), "flight: {}", stderr(&o));
        let flown = std::fs::read_to_string(&out).unwrap();
        assert_eq!(flown.lines().count(), n + 1, "{flown}");
    };
    let text = fixture("uneekor_refine.csv");
    let toe = ["--impact-offset-positive", "toe"];
    let whole = import(dir.path(), "w.csv", &text, "uneekor", &toe);
    assert!(whole.0.status.success(), "{}", stderr(&whole.0));
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    lines[1] = lines[1].replacen("6,113.3,", "6,5000,", 1);
    lines[2] = lines[2].replacen(",30,6.1 s,", ",-3,0 s,", 1);
    lines[5] = lines[5].replacen("2,122.8,", "2,-2147483648,", 1);
    let (o, h, rows, out) = import(dir.path(), "u.csv", &lines.join("\n"), "uneekor", &toe);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert_eq!(rows.len(), whole.2.len(), "{err}");
    let carry = col(&h, &rows, "carry_yd");
    assert_eq!((carry[0], carry[carry.len() - 2]), ("", ""), "{err}");
    assert_eq!(col(&h, &rows, "apex_yd")[1], "", "{err}");
    assert_eq!(col(&h, &rows, "flight_time_s")[1], "", "{err}");
    assert!(
        err.contains("column 'Carry': outside its physical range (line(s) 2"),
        "{err}"
    );
    assert!(
        err.contains("column 'Apex': outside its physical range (line(s) 3"),
        "{err}"
    );
    assert!(
        err.contains("column 'Flight Time': 0, which vendors write"),
        "{err}"
    );
    assert!(err.contains("column 'Carry': a vendor's sentinel"), "{err}");
    fly(&out, rows.len());

    let gspro = fixture("gspro.csv");
    let mut lines: Vec<String> = gspro.lines().map(str::to_owned).collect();
    let i = lines[0].split(',').position(|c| c == "ClubSpeed").unwrap();
    for l in lines.iter_mut().skip(1) {
        let mut cells: Vec<&str> = l.split(',').collect();
        cells[i] = "0";
        *l = cells.join(",");
    }
    let (o, _, rows, out) = import(
        dir.path(),
        "g.csv",
        &lines.join("\n"),
        "gspro",
        &["--impact-offset-positive", "toe"],
    );
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert_eq!(rows.len(), 4, "{err}");
    assert!(
        err.contains("4 of 4 shot(s) have no complete delivery"),
        "{err}"
    );
    fly(&out, 4);

    let fsx = fixture("foresight_fsx.csv").replace("16777215.000000", "16777216");
    let (o, _, rows, out) = import(
        dir.path(),
        "f.csv",
        &fsx,
        "foresight",
        &["--impact-offset-positive", "toe"],
    );
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert_eq!(rows.len(), 3, "{err}");
    assert!(
        err.contains("a vendor's sentinel for not measured"),
        "{err}"
    );
    fly(&out, 3);
}

/// A JSON Lines log cut while it was written: the cut line is a bad row, counted, not a
/// reason to lose the shots before it (it refused the whole file).
#[test]
fn a_json_lines_log_cut_short_keeps_its_shots() {
    let dir = tempfile::tempdir().unwrap();
    let log = fixture("corpus/openflight.jsonl");
    let whole = import(dir.path(), "w.jsonl", &log, "openflight", &[]);
    assert!(whole.0.status.success(), "{}", stderr(&whole.0));
    // The last shot's line cut in its middle, as a log being written ends.
    let lines: Vec<&str> = log.lines().collect();
    let n = 1 + lines
        .iter()
        .rposition(|l| l.contains("shot_detected"))
        .unwrap();
    let last = lines[n - 1];
    let cut = format!("{}\n{}", lines[..n - 1].join("\n"), &last[..last.len() / 2]);
    let (o, _, rows, _) = import(dir.path(), "c.jsonl", &cut, "openflight", &[]);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert_eq!(rows.len() + 1, whole.2.len(), "{err}");
    assert!(
        err.contains(&format!(
            "left out 1 row(s): not valid JSON (a line cut short?) (line(s) {n}"
        )),
        "{err}"
    );
    // The shots before it as they were.
    let kept: Vec<&Vec<String>> = whole
        .2
        .iter()
        .filter(|r| r[0] != format!("row{n}"))
        .collect();
    assert_eq!(rows.iter().collect::<Vec<_>>(), kept, "{err}");
    // --strict refuses it, naming the line.
    let path = dir.path().join("c.jsonl");
    let o = smash(&[
        "import",
        "--format",
        "openflight",
        s(&path),
        "--out",
        s(&dir.path().join("x.csv")),
        "--strict",
    ]);
    common::assert_refused(&o, &[&format!("c.jsonl:{n}: not valid JSON")]);
}

/// 41.8 in the flight commands and diagnose: one day written `5/1/2026`, `2026-05-01` and as
/// Excel serials is one session, so `flight --calibrate-by session` fits two sessions, not a
/// shot each; serials of eight days (a session of one shot each) are refused by
/// `--calibrate-by session` in one line and named by `--diagnose` as folds by shot; the
/// impact `diagnose` reads one day's serials as time blocks, and warns when every shot is a
/// session of its own.
#[test]
fn excel_serials_and_two_date_forms_make_sessions_not_shots() {
    let dir = tempfile::tempdir().unwrap();
    let tm = fixture("trackman_older.csv");
    let lines: Vec<&str> = tm.lines().collect();
    let with_dates = |dates: &[&str]| {
        let mut text = format!("Date,{}\n,{}\n", lines[0], lines[1]);
        for (d, l) in dates.iter().zip(&lines[2..]) {
            text.push_str(&format!("{d},{l}\n"));
        }
        text
    };
    let toe = ["--impact-offset-positive", "toe"];
    let two_days = [
        "5/1/2026 10:00",
        "2026-05-01 10:05",
        "46143.4236",
        "46143.43",
        "46144.40",
        "5/2/2026 11:00",
        "2026-05-02 11:30",
        "46144.6",
    ];
    let (o, _, rows, two) = import(
        dir.path(),
        "two.csv",
        &with_dates(&two_days),
        "trackman",
        &toe,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(rows.len(), 8);
    let flight = |shots: &Path, extra: &[&str]| {
        let out = dir.path().join("f.csv");
        let mut args = vec!["flight", "--shots", s(shots), "--out", s(&out)];
        args.extend_from_slice(extra);
        smash(&args)
    };
    let o = flight(&two, &["--calibrate", "drag", "--calibrate-by", "session"]);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert_eq!(
        err.matches("calibrated fmm2022 for datetime '").count(),
        2,
        "{err}"
    );
    assert!(
        err.contains("for datetime '2026-05-01'") && err.contains("for datetime '2026-05-02'"),
        "{err}"
    );
    let o = flight(&two, &["--diagnose"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("folds by session (sessions from column 'datetime')"),
        "{}",
        stderr(&o)
    );

    let days: Vec<String> = (0..8).map(|i| format!("{}.5", 46143 + i)).collect();
    let days: Vec<&str> = days.iter().map(String::as_str).collect();
    let (o, _, _, eight) = import(
        dir.path(),
        "eight.csv",
        &with_dates(&days),
        "trackman",
        &toe,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let o = flight(
        &eight,
        &["--calibrate", "drag", "--calibrate-by", "session"],
    );
    common::assert_refused(
        &o,
        &[
            "--calibrate-by session: 8 of the 8 sessions hold a single shot",
            "at least 2 shots",
        ],
    );
    let o = flight(&eight, &["--diagnose"]);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("folds by shot (column 'datetime' names a session of its own for every shot)"),
        "{err}"
    );

    // The impact model's diagnose, on a shots file with a date column of Excel serials.
    let shots = cli_support::measured_shots(dir.path());
    let text = std::fs::read_to_string(&shots).unwrap();
    let diagnose = |serial: &dyn Fn(usize) -> String| {
        let mut out = String::new();
        for (i, l) in text.lines().enumerate() {
            let cell = if i == 0 { "date".to_owned() } else { serial(i) };
            out.push_str(&format!("{l},{cell}\n"));
        }
        let path = dir.path().join("dated.csv");
        std::fs::write(&path, out).unwrap();
        let o = smash(&[
            "diagnose",
            "--club",
            &cli_support::club(),
            "--shots",
            s(&path),
            "--json",
            "--candidates",
            "added_mass",
            "--max-steps",
            "1",
            "--exact-impact-locations",
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        let warned = json["warnings"].as_array().unwrap().iter().any(|w| {
            w.as_str()
                .unwrap()
                .contains("gives every shot a session of its own")
        });
        (json["fold_by"].as_str().unwrap().to_owned(), warned)
    };
    // One afternoon, a shot a minute: time blocks, not 40 sessions.
    let by = diagnose(&|i| format!("{:.6}", 46143.5 + i as f64 / 1440.0));
    assert_eq!(by, ("time block".to_owned(), false));
    // A day each: session folds, and the warning that they are folds by shot.
    let by = diagnose(&|i| format!("{}.5", 46100 + i));
    assert_eq!(by, ("session".to_owned(), true));
}
