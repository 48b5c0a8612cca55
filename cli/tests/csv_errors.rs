//! One wording and one line count for every CSV reader's `csv` errors (`data::csv_error_at`):
//! the shots reader, the launch reader of `smash flight`, the flight's coefficient table and the
//! shard files `smash merge` reads. Each is given the same faults — a row short of fields after
//! a blank line, and a byte that is not UTF-8 — with `\n`, `\r\n` and lone `\r` line ends, and
//! must name the fault's own line (the `csv` crate's count is off after a blank line in CRLF
//! files and puts every record of a CR-only file on line 1).

use crate::cli_support;
use crate::common;

use std::path::{Path, PathBuf};

use cli_support::{club, repo, s, smash};

/// The end of every message about a byte that is not UTF-8 (readers that hold the whole text name
/// the byte on the line, the others the field).
const NOT_UTF8: &str = "is not valid UTF-8 text (save the file as UTF-8)";

const ENDS: [(&str, &str); 3] = [("lf", "\n"), ("crlf", "\r\n"), ("cr", "\r")];

/// `lines` joined by `end` (and ended by it) into `dir/name`.
fn write_lines(dir: &Path, name: &str, lines: &[&[u8]], end: &str) -> PathBuf {
    let mut bytes = Vec::new();
    for l in lines {
        bytes.extend_from_slice(l);
        bytes.extend_from_slice(end.as_bytes());
    }
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

/// A file with a header, a good line 2, a blank line 3 and a bad line 4: short of fields, or
/// with a byte that is not UTF-8 (the csv crate checks the field count first).
fn faults<'a>(
    head: &'a [u8],
    line2: &'a [u8],
    short4: &'a [u8],
    bad_byte4: &'a [u8],
) -> [(&'static str, Vec<&'a [u8]>); 2] {
    [
        ("short", vec![head, line2, b"", short4]),
        ("utf8", vec![head, line2, b"", bad_byte4]),
    ]
}

fn refused(args: &[&str], needles: &[&str]) {
    let o = smash(args);
    common::assert_refused(&o, needles);
}

#[test]
fn the_shots_reader_names_the_line_of_a_short_row_or_a_bad_byte() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let head = b"shot_id,club_speed_mph,attack_angle_deg,club_path_deg,dynamic_loft_deg,\
                 face_angle_deg,impact_y_mm,impact_z_mm";
    let club = club();
    for (tag, end) in ENDS {
        let lines_of = faults(
            head,
            b"s1,100,0,0,12,0,0,0",
            b"s2,100,12",
            b"s2,100,0,0,12,0,0,\xff0",
        );
        for (kind, lines) in lines_of {
            let name = format!("{kind}_{tag}.csv");
            let shots = write_lines(d, &name, &lines, end);
            let out = d.join(format!("{name}.out.csv"));
            let want = match kind {
                "short" => format!(
                    "{name}:4: found a row with 3 field(s), but the header has 8 (one per column)"
                ),
                _ => format!("{name}:4: field 8 {NOT_UTF8}"),
            };
            refused(
                &[
                    "predict",
                    "--strict",
                    "--club",
                    &club,
                    "--shots",
                    s(&shots),
                    "--out",
                    s(&out),
                ],
                &[&want],
            );
            assert!(!out.exists());
        }
    }
}

#[test]
fn the_launch_reader_of_flight_names_the_line_of_a_short_row_or_a_bad_byte() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let head = b"shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm";
    for (tag, end) in ENDS {
        for (kind, lines) in faults(head, b"d1,150,12,2600", b"d2,150", b"\xff,150,12,2600") {
            let name = format!("{kind}_{tag}.csv");
            let launch = write_lines(d, &name, &lines, end);
            let out = d.join(format!("{name}.out.csv"));
            let want = match kind {
                "short" => format!(
                    "{name}:4: found a row with 2 field(s), but the header has 4 (one per column)"
                ),
                _ => format!("{name}:4: byte 1 of the line {NOT_UTF8}"),
            };
            refused(
                &["flight", "--shots", s(&launch), "--out", s(&out)],
                &[&want],
            );
            assert!(!out.exists());
        }
    }
}

#[test]
fn the_coefficient_table_names_the_line_of_a_short_row_or_a_bad_byte() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let launch = d.join("launch.csv");
    std::fs::write(
        &launch,
        "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\nd1,150,12,2600\n",
    )
    .unwrap();
    let out = d.join("out.csv");
    for (tag, end) in ENDS {
        for (kind, lines) in faults(
            b"spin_factor,cd,cl",
            b"0.0,0.25,0.0",
            b"0.2,0.28",
            b"\xff,0.28,0.2",
        ) {
            let name = format!("{kind}_{tag}.csv");
            let table = write_lines(d, &name, &lines, end);
            let aero = format!("table:{}", s(&table));
            let want = match kind {
                "short" => {
                    "line 4: found a row with 2 field(s), but the header has 3 (one per column)"
                }
                _ => "line 4: byte 1 of the line is not valid UTF-8 text",
            };
            refused(
                &[
                    "flight",
                    "--shots",
                    s(&launch),
                    "--out",
                    s(&out),
                    "--aero",
                    &aero,
                ],
                &[&name, want],
            );
            assert!(!out.exists());
        }
    }
}

/// The shard files of a 3 × 3 face map (one shard), for merge to read back.
fn shard(dir: &Path) -> PathBuf {
    let study = dir.join("tiny.toml");
    let club = repo("configs/clubs/paper_driver.toml");
    std::fs::write(
        &study,
        format!(
            "[study]\nname = \"tiny\"\nclub = {:?}\n[delivery]\nclub_speed_mph = 100.0\n\
             dynamic_loft_deg = 12.0\n[grid]\ny_mm = {{ from = -2.0, to = 2.0, count = 3 }}\n\
             z_mm = {{ from = -2.0, to = 2.0, count = 3 }}\n",
            s(&club)
        ),
    )
    .unwrap();
    let out = dir.join("shard");
    let o = smash(&["run", s(&study), "--shard", "0/1", "--out", s(&out)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    out
}

/// `file` of the shard rewritten with `end` line ends, a blank line 3 and `line4` as line 4.
fn spoil(shard: &Path, to: &Path, file: &str, end: &str, line4: Option<&[u8]>) {
    std::fs::create_dir_all(to).unwrap();
    for f in ["shard.toml", "study.toml", "rows.csv", "metrics.csv"] {
        std::fs::copy(shard.join(f), to.join(f)).unwrap();
    }
    let text = std::fs::read(shard.join(file)).unwrap();
    let mut lines: Vec<&[u8]> = text
        .split(|&b| b == b'\n')
        .filter(|l| !l.is_empty())
        .collect();
    lines.insert(2, b"");
    let short: Vec<u8>;
    match line4 {
        Some(l) => lines[3] = l,
        None => {
            let l = lines[3];
            let cut = l.iter().rposition(|&b| b == b',').unwrap();
            short = l[..cut].to_vec();
            lines[3] = &short;
        }
    }
    write_lines(to, file, &lines, end);
}

#[test]
fn merge_names_the_line_of_a_short_row_or_a_bad_byte_in_a_shard() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let shard = shard(d);
    let out = d.join("merged");
    for (tag, end) in ENDS {
        for (file, fields) in [("rows.csv", 9), ("metrics.csv", 3)] {
            let to = d.join(format!("short_{tag}_{file}"));
            spoil(&shard, &to, file, end, None);
            let want = format!(
                "{file}:4: found a row with {} field(s), but the header has {fields} (one per \
                 column)",
                fields - 1
            );
            refused(&["merge", s(&to), "--out", s(&out)], &[&want]);
            let to = d.join(format!("utf8_{tag}_{file}"));
            let bad: &[u8] = if fields == 9 {
                b"0,\xff,0,1,1,1,1,1,1"
            } else {
                b"0,\xff,1"
            };
            spoil(&shard, &to, file, end, Some(bad));
            // rows.csv is streamed through the csv reader; metrics.csv is read whole.
            let place = if fields == 9 {
                "field 2"
            } else {
                "byte 3 of the line"
            };
            let want = format!("{file}:4: {place} {NOT_UTF8}");
            refused(&["merge", s(&to), "--out", s(&out)], &[&want]);
            assert!(!out.exists());
        }
        // A fault past the blank line, in a later record: the count stays right as it streams.
        let to = d.join(format!("late_{tag}"));
        spoil(&shard, &to, "rows.csv", end, None);
        let text = std::fs::read(shard.join("rows.csv")).unwrap();
        let mut lines: Vec<&[u8]> = text
            .split(|&b| b == b'\n')
            .filter(|l| !l.is_empty())
            .collect();
        lines.insert(2, b"");
        lines.insert(5, b"");
        lines[7] = b"0,9,0,1,1,1,1,1,1";
        write_lines(&to, "rows.csv", &lines, end);
        refused(
            &["merge", s(&to), "--out", s(&out)],
            &["rows.csv:8: column row: 9 is outside the study"],
        );
    }
}
