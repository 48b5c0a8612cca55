//! Mutation fuzz over the presets (issue 41, item E): each preset's fixture, changed the ways
//! real exports arrive changed, imported by the binary. The mutations: the last or a middle
//! shot's line cut short (at seeded places), a units row inserted on any of the first lines
//! (three versions: km/h and m, mph and yd, m/s and ft), the file re-saved by a European
//! spreadsheet (`;`, decimal commas) with thousands separators in its numbers, and summary-row
//! words (Dev, Mean, Average, Total, Std. Dev., …) as the golfers' names.
//!
//! The invariants, for every mutation: no panic; exit 0 or one line of error; never a number
//! changed in a row the mutation did not touch (each row of the import compared with the
//! unmutated import's row of the same export line); every shot that goes missing counted in
//! the import's report (`left out N row(s)`). A units row is applied or refused, never
//! ignored: the versions that are accepted must all imply one unit for the file's numbers.
//!
//! Deterministic: the seeds below are the first eight integers, fixed before the test was
//! run, and a small generator of the file's own (SplitMix64) turns them into places.

use crate::cli_support;

use std::collections::HashMap;
use std::path::Path;

use cli_support::{repo, s, smash, stderr};

/// The seeds: each picks a cut in the last shot's line and one in a middle shot's line, and
/// which cells get a thousands separator.
const SEEDS: [u64; 8] = [1, 2, 3, 4, 5, 6, 7, 8];

/// A preset's fixture: file (under `cli/tests/fixtures/import/`, or the repository's own when
/// it starts with `tests/`), preset, and the flags it needs.
struct Fixture {
    file: &'static str,
    preset: &'static str,
    flags: &'static [&'static str],
}

const TOE: &[&str] = &["--impact-offset-positive", "toe"];

const FIXTURES: [Fixture; 19] = [
    fx("trackman_older.csv", "trackman", TOE),
    fx("trackman_normalized.csv", "trackman", TOE),
    fx("trackman_semicolon.csv", "trackman", TOE),
    fx("flightscope_fsgolf.csv", "flightscope", TOE),
    fx("flightscope_cp1252.csv", "flightscope", TOE),
    fx("foresight_fsx.csv", "foresight", TOE),
    fx("corpus/fsx2020_lastshot.csv", "foresight", TOE),
    fx("garmin_r10.csv", "garmin-r10", &[]),
    fx("corpus/garmin_r10_metric.csv", "garmin-r10", &[]),
    fx("corpus/garmin_r50.csv", "garmin-r10", &[]),
    fx("gspro.csv", "gspro", TOE),
    fx("skytrak.csv", "skytrak", &[]),
    fx("uneekor_refine.csv", "uneekor", TOE),
    fx("uneekor_range.csv", "uneekor", &[]),
    fx("corpus/square_range.csv", "uneekor", &[]),
    fx("corpus/flightscope_cloud.csv", "flightscope-scrape", &[]),
    fx("tests/data/real/rapsodo_mlm2pro_7i.csv", "rapsodo", &[]),
    fx("corpus/openflight.jsonl", "openflight", &[]),
    fx("corpus/fsx_session.session", "foresight-session", TOE),
];

const fn fx(file: &'static str, preset: &'static str, flags: &'static [&'static str]) -> Fixture {
    Fixture {
        file,
        preset,
        flags,
    }
}

impl Fixture {
    fn bytes(&self) -> Vec<u8> {
        let path = if self.file.starts_with("tests/") {
            repo(self.file)
        } else {
            repo(&format!("cli/tests/fixtures/import/{}", self.file))
        };
        std::fs::read(path).unwrap()
    }
    fn json(&self) -> bool {
        self.file.ends_with(".jsonl") || self.file.ends_with(".session")
    }
}

/// SplitMix64 (Steele, Lea & Flood 2014): the seeds' places, the same on every machine.
struct Mix(u64);

impl Mix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// A number in `0..n` (`n` > 0).
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// What one import gave: the exit, stderr, and the shots file's header and rows.
struct Import {
    ok: bool,
    err: String,
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Import {
    /// Each row by its export line (`row<line>` ids; an id column's ids as they are).
    fn by_id(&self) -> HashMap<String, &Vec<String>> {
        self.rows.iter().map(|r| (r[0].clone(), r)).collect()
    }
    fn col(&self, name: &str) -> Option<usize> {
        self.header.iter().position(|h| h == name)
    }
    /// Rows the import says it left out (`left out N row(s)`).
    fn left_out(&self) -> usize {
        count_after(&self.err, "left out ")
    }
}

/// The sum of the numbers that follow `prefix` in `text`.
fn count_after(text: &str, prefix: &str) -> usize {
    text.match_indices(prefix)
        .filter_map(|(i, _)| {
            let rest = &text[i + prefix.len()..];
            let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
            digits.parse::<usize>().ok()
        })
        .sum()
}

/// Imports run, for the summary line.
static IMPORTS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

/// Import `bytes` as `f` would be; checks the first invariants: no panic, exit 0 or one line
/// of error, no NaN or infinity written.
fn import(dir: &Path, f: &Fixture, bytes: &[u8], what: &str) -> Import {
    IMPORTS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let ext = f.file.rsplit('.').next().unwrap();
    let input = dir.join(format!("m.{ext}"));
    let out = dir.join("m.shots.csv");
    let _ = std::fs::remove_file(&out);
    std::fs::write(&input, bytes).unwrap();
    let mut args = vec!["import", "--format", f.preset, s(&input), "--out", s(&out)];
    args.extend_from_slice(f.flags);
    let o = smash(&args);
    let err = stderr(&o);
    let label = format!("{} {what}", f.file);
    assert!(!err.contains("panicked"), "{label}: {err}");
    if !o.status.success() {
        assert_eq!(o.status.code(), Some(1), "{label}: {err}");
        let lines: Vec<&str> = err.lines().filter(|l| !l.trim().is_empty()).collect();
        assert!(
            lines.len() == 1 && lines[0].starts_with("error: "),
            "{label}: not one line of error: {err}"
        );
        assert!(
            !out.exists(),
            "{label}: refused, yet wrote {}",
            out.display()
        );
        return Import {
            ok: false,
            err,
            header: Vec::new(),
            rows: Vec::new(),
        };
    }
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(
        !text.contains("NaN") && !text.contains("inf"),
        "{label}: a non-finite number written"
    );
    let mut rdr = csv::Reader::from_reader(text.as_bytes());
    let header = rdr.headers().unwrap().iter().map(str::to_owned).collect();
    let rows = rdr
        .records()
        .map(|r| r.unwrap().iter().map(str::to_owned).collect())
        .collect();
    Import {
        ok: true,
        err,
        header,
        rows,
    }
}

/// The invariants against the unmutated import: every row of `m` that `line` maps to an
/// untouched export line of the original (`None`: a line the mutation made or touched) has
/// the original's cells, `except` the columns named; every original shot missing from `m`
/// is counted as left out.
fn same_untouched(
    orig: &Import,
    m: &Import,
    line: &dyn Fn(usize) -> Option<usize>,
    except: &[&str],
    label: &str,
) {
    // The same columns, but for the ones the mutation may add (a golfer column).
    let cols: Vec<Option<usize>> = orig.header.iter().map(|h| m.col(h)).collect();
    let added: Vec<&String> = m.header.iter().filter(|h| orig.col(h).is_none()).collect();
    assert!(
        cols.iter().all(Option::is_some) && added.iter().all(|h| except.contains(&h.as_str())),
        "{label}: another layout: {:?} against {:?}\n{}",
        m.header,
        orig.header,
        m.err
    );
    let o = orig.by_id();
    let mut seen = Vec::new();
    for row in &m.rows {
        let id = match row[0].strip_prefix("row").and_then(|n| n.parse().ok()) {
            Some(l) => match line(l) {
                Some(ol) => format!("row{ol}"),
                None => continue,
            },
            None => row[0].clone(),
        };
        let Some(want) = o.get(&id) else {
            panic!("{label}: {} is no shot of the original\n{}", row[0], m.err);
        };
        for (k, h) in orig.header.iter().enumerate().skip(1) {
            let got = &row[cols[k].expect("checked")];
            if !except.contains(&h.as_str()) {
                assert_eq!(
                    &want[k], got,
                    "{label}: {id} ({}) {h} changed\n{}",
                    row[0], m.err
                );
            }
        }
        seen.push(id);
    }
    let missing = orig.rows.iter().filter(|r| !seen.contains(&r[0])).count();
    let counted = m.left_out().saturating_sub(orig.left_out());
    // A touched line's shot may be missing too, and must be counted like the others.
    assert!(
        missing <= counted + touched_kept(m, line),
        "{label}: {missing} shot(s) missing, {counted} counted as left out\n{}",
        m.err
    );
}

/// Shots of `m` on lines the mutation touched or made (they stand for an original shot).
fn touched_kept(m: &Import, line: &dyn Fn(usize) -> Option<usize>) -> usize {
    m.rows
        .iter()
        .filter(|r| {
            r[0].strip_prefix("row")
                .and_then(|n| n.parse::<usize>().ok())
                .is_some_and(|l| line(l).is_none())
        })
        .count()
}

/// The export lines (1-based) of the original import's shots, in order.
fn shot_lines(orig: &Import) -> Vec<usize> {
    let mut v: Vec<usize> = orig
        .rows
        .iter()
        .filter_map(|r| r[0].strip_prefix("row")?.parse().ok())
        .collect();
    v.sort_unstable();
    v
}

/// Split text into lines, keeping each line's end (so cutting and inserting keep the file's
/// own line ends).
fn lines_of(text: &str) -> Vec<&str> {
    text.split_inclusive('\n').collect()
}

/// Truncation: the last shot's line cut (the rest of the file dropped), and a middle shot's
/// line cut (the rest kept), at seeded places. A CSV or JSON Lines file keeps its other shots;
/// a JSON document may be refused.
fn truncations(dir: &Path, f: &Fixture, text: &str, orig: &Import) {
    if f.file.ends_with(".session") {
        // One JSON document: cut anywhere, it is refused in one line (checked by `import`).
        for seed in SEEDS {
            let mut at = Mix(seed).below(text.len());
            while !text.is_char_boundary(at) {
                at -= 1;
            }
            let _ = import(dir, f, &text.as_bytes()[..at], &format!("cut at byte {at}"));
        }
        return;
    }
    let lines = lines_of(text);
    let shots = shot_lines(orig);
    let (Some(&last), Some(&mid)) = (shots.last(), shots.get(shots.len() / 2)) else {
        return;
    };
    for seed in SEEDS {
        let mut mix = Mix(seed);
        for (which, at) in [("last", last), ("middle", mid)] {
            let line = lines[at - 1].trim_end_matches(['\n', '\r']);
            if line.len() < 2 {
                continue;
            }
            let mut cut = 1 + mix.below(line.len() - 1);
            while !line.is_char_boundary(cut) {
                cut -= 1;
            }
            let mut t: String = lines[..at - 1].concat();
            t.push_str(&line[..cut]);
            if which == "middle" {
                t.push('\n');
                t.push_str(&lines[at..].concat());
            }
            let what = format!("{which} shot (line {at}) cut after {cut} bytes (seed {seed})");
            let m = import(dir, f, t.as_bytes(), &what);
            let label = format!("{} {what}", f.file);
            // A file of one shot has no other to keep.
            if orig.rows.len() == 1 && !m.ok {
                continue;
            }
            assert!(m.ok, "{label}: a cut row sank the file: {}", m.err);
            same_untouched(orig, &m, &|l| (l != at).then_some(l), &[], &label);
        }
    }
}

/// Three units rows in turn (km/h and m, mph and yd, m/s and ft under the mapped speeds and
/// lengths) inserted before each of the first lines, under the header and under the first and
/// second shots. Each is applied or refused: the versions accepted imply one unit for the
/// file's speeds and one for its lengths (an ignored units row would imply three).
fn units_rows(dir: &Path, f: &Fixture, text: &str, orig: &Import) {
    let Some((header_at, delimiter, cells)) = header_of(f, text) else {
        return;
    };
    let mapping = smash::data::import::load_mapping(f.preset).unwrap();
    let target = |cell: &str| {
        let name = normal(cell);
        mapping
            .column
            .iter()
            .find(|c| c.source.iter().any(|s| normal(s) == name))
            .map(|c| c.target.as_str())
    };
    let versions = [("[km/h]", "[m]"), ("[mph]", "[yd]"), ("[m/s]", "[ft]")];
    let lines = lines_of(text);
    let shots = shot_lines(orig);
    let last = (shots.get(1).copied().unwrap_or(header_at + 1)).min(lines.len());
    for at in 0..=last {
        let mut accepted = Vec::new();
        for (speed, length) in versions {
            let row: Vec<&str> = cells
                .iter()
                .map(|c| match target(c) {
                    Some(t) if t.ends_with("_mph") => speed,
                    Some(t) if t.ends_with("_yd") => length,
                    _ => "",
                })
                .collect();
            let mut t: String = lines[..at].concat();
            t.push_str(&row.join(&(delimiter as char).to_string()));
            t.push('\n');
            t.push_str(&lines[at..].concat());
            let what = format!("units row {speed} {length} inserted as line {}", at + 1);
            let m = import(dir, f, t.as_bytes(), &what);
            if !m.ok {
                continue;
            }
            let label = format!("{} {what}", f.file);
            let inserted = at + 1;
            let line = |l: usize| match l.cmp(&inserted) {
                std::cmp::Ordering::Less => Some(l),
                std::cmp::Ordering::Equal => None,
                std::cmp::Ordering::Greater => Some(l - 1),
            };
            let scaled = [
                "ball_speed_mph",
                "club_speed_mph",
                "carry_yd",
                "total_yd",
                "apex_yd",
                "offline_yd",
            ];
            same_untouched(orig, &m, &line, &scaled, &label);
            let implied = implied_units(orig, &m, &line, (speed, length), &label);
            accepted.push((speed, length, implied));
        }
        let label = format!("{} units row as line {}", f.file, at + 1);
        for pair in accepted.windows(2) {
            assert_eq!(
                pair[0].2, pair[1].2,
                "{label}: {} {} and {} {} were both accepted, and read the numbers in different \
                 units: a units row was ignored",
                pair[0].0, pair[0].1, pair[1].0, pair[1].1
            );
        }
    }
}

/// The units the original import read the file's speeds and lengths in, as `m` (the file with
/// a units row stating `stated`) implies them: each column's ratio to the original, the same
/// in every row, is the stated unit over the original's. `None` where the column is absent.
fn implied_units(
    orig: &Import,
    m: &Import,
    line: &dyn Fn(usize) -> Option<usize>,
    stated: (&str, &str),
    label: &str,
) -> [Option<&'static str>; 2] {
    // Sizes in SI: 1 mph = 0.44704 m/s, 1 yd = 0.9144 m, 1 ft = 0.3048 m (exact).
    const SPEEDS: [(&str, f64); 3] = [("[mph]", 0.44704), ("[km/h]", 1.0 / 3.6), ("[m/s]", 1.0)];
    const LENGTHS: [(&str, f64); 3] = [("[yd]", 0.9144), ("[m]", 1.0), ("[ft]", 0.3048)];
    let o = orig.by_id();
    let mut found = [None; 2];
    for (k, (col, units, unit)) in [
        ("ball_speed_mph", &SPEEDS, stated.0),
        ("carry_yd", &LENGTHS, stated.1),
    ]
    .into_iter()
    .enumerate()
    {
        let (Some(i), Some(j)) = (orig.col(col), m.col(col)) else {
            continue;
        };
        let mut ratios = Vec::new();
        for row in &m.rows {
            let Some(l) = row[0].strip_prefix("row").and_then(|n| n.parse().ok()) else {
                continue;
            };
            let Some(want) = line(l).and_then(|ol| o.get(&format!("row{ol}"))) else {
                continue;
            };
            if let (Ok(a), Ok(b)) = (row[j].parse::<f64>(), want[i].parse::<f64>()) {
                if b != 0.0 {
                    ratios.push(a / b);
                }
            }
        }
        let Some(&r) = ratios.first() else {
            continue;
        };
        assert!(
            ratios.iter().all(|x| (x / r - 1.0).abs() < 1e-9),
            "{label}: {col} not scaled alike in every row: {ratios:?}\n{}",
            m.err
        );
        let si_stated = units.iter().find(|(n, _)| *n == unit).unwrap().1;
        let si_orig = si_stated / r;
        let Some((name, _)) = units
            .iter()
            .find(|(_, si)| (si / si_orig - 1.0).abs() < 1e-9)
        else {
            panic!(
                "{label}: {col} scaled by {r}: no ratio of two units\n{}",
                m.err
            );
        };
        found[k] = Some(*name);
    }
    found
}

/// The header's index among the file's lines, the delimiter and the header's cells: the first
/// of the first 30 lines naming two of the preset's columns. `None` for JSON.
fn header_of(f: &Fixture, text: &str) -> Option<(usize, u8, Vec<String>)> {
    if f.json() {
        return None;
    }
    let mapping = smash::data::import::load_mapping(f.preset).unwrap();
    let names: Vec<String> = mapping
        .column
        .iter()
        .flat_map(|c| c.source.iter().map(|s| normal(s)))
        .collect();
    lines_of(text)
        .iter()
        .take(30)
        .enumerate()
        .find_map(|(i, l)| {
            let delimiter = if l.matches(';').count() > l.matches(',').count() {
                b';'
            } else {
                b','
            };
            let cells = split(l, delimiter);
            let known = cells.iter().filter(|c| names.contains(&normal(c))).count();
            (known >= 2).then_some((i, delimiter, cells))
        })
}

/// A line's cells (quotes read as CSV reads them).
fn split(line: &str, delimiter: u8) -> Vec<String> {
    let mut rdr = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .delimiter(delimiter)
        .from_reader(line.as_bytes());
    rdr.records()
        .next()
        .and_then(Result::ok)
        .map(|r| r.iter().map(str::to_owned).collect())
        .unwrap_or_default()
}

/// A column name as the import compares names: without case, spacing or a unit in brackets.
fn normal(name: &str) -> String {
    let t = name.trim().trim_start_matches('\u{feff}');
    let unit = |i: usize| smash::data::import::units::Unit::parse(&t[i..]).is_some();
    let t = match (t.ends_with(')') || t.ends_with(']'), t.rfind(['(', '['])) {
        (true, Some(i)) if i > 0 && unit(i) => &t[..i],
        _ => t,
    };
    t.split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .to_lowercase()
}

/// A number written the European way: decimal comma, and (`group`) a dot between thousands.
fn european(cell: &str, group: bool) -> String {
    let b = cell.as_bytes();
    // The number's digits: the first run of digits with at most one dot inside.
    let Some(start) = b.iter().position(u8::is_ascii_digit) else {
        return cell.to_owned();
    };
    let mut end = start;
    while end < b.len()
        && (b[end].is_ascii_digit() || (b[end] == b'.' && !b[start..end].contains(&b'.')))
    {
        end += 1;
    }
    let number = &cell[start..end];
    // Only a number with words or its unit around it (`12.7 L`, `77 °F`): not a date or time.
    let words = |t: &str| t.chars().all(|c| c.is_alphabetic() || " °%″".contains(c));
    let before = cell[..start].trim_end_matches(['-', '+']);
    if number.ends_with('.') || !words(before) || !words(&cell[end..]) {
        return cell.to_owned();
    }
    let (int, frac) = number
        .split_once('.')
        .map_or((number, None), |(i, f)| (i, Some(f)));
    let int = if group && int.len() > 3 && !int.starts_with('0') {
        let mut out = String::new();
        for (k, c) in int.chars().enumerate() {
            if k > 0 && (int.len() - k) % 3 == 0 {
                out.push('.');
            }
            out.push(c);
        }
        out
    } else {
        int.to_owned()
    };
    let number = match frac {
        Some(f) => format!("{int},{f}"),
        None => int,
    };
    format!("{}{number}{}", &cell[..start], &cell[end..])
}

/// The file re-saved by a European spreadsheet: `;` between cells and decimal commas in the
/// shots' numbers, then thousands separators (`3.083`) in the cells a seed picks. The shots
/// are the original's, number for number.
fn decimal_commas(dir: &Path, f: &Fixture, text: &str, orig: &Import) {
    let Some((header_at, delimiter, _)) = header_of(f, text) else {
        return;
    };
    let shots = shot_lines(orig);
    let lines = lines_of(text);
    for seed in SEEDS {
        let mut mix = Mix(seed);
        let mut out = String::new();
        for (i, l) in lines.iter().enumerate() {
            let end = &l[l.trim_end_matches(['\n', '\r']).len()..];
            let cells = split(l, delimiter);
            let shot = shots.contains(&(i + 1));
            let cells: Vec<String> = cells
                .iter()
                .map(|c| {
                    if !shot || (delimiter == b';' && i < header_at) {
                        return c.clone();
                    }
                    let group = mix.below(2) == 0;
                    if delimiter == b';' {
                        // Already decimal commas: only the thousands separators.
                        match c.parse::<u64>() {
                            Ok(_) if group => european(c, true),
                            _ => c.clone(),
                        }
                    } else {
                        european(c, group)
                    }
                })
                .collect();
            let mut w = csv::WriterBuilder::new()
                .delimiter(b';')
                .terminator(csv::Terminator::Any(b'\n'))
                .from_writer(Vec::new());
            if cells.is_empty() {
                out.push_str(end);
                continue;
            }
            w.write_record(&cells).unwrap();
            let row = String::from_utf8(w.into_inner().unwrap()).unwrap();
            out.push_str(row.trim_end_matches('\n'));
            out.push_str(if end.is_empty() { "" } else { "\n" });
        }
        let what = format!("re-saved with ';', decimal commas and thousands dots (seed {seed})");
        let m = import(dir, f, out.as_bytes(), &what);
        let label = format!("{} {what}", f.file);
        assert!(m.ok, "{label}: {}", m.err);
        same_untouched(orig, &m, &|l| Some(l), &[], &label);
        assert_eq!(m.rows.len(), orig.rows.len(), "{label}: {}", m.err);
    }
}

/// Words of the summary rows vendors append (and `Total`, `Std`), as golfers' names.
const SUMMARY_WORDS: [&str; 10] = [
    "Dev",
    "Mean",
    "Average",
    "Avg",
    "Total",
    "Std",
    "Std. Dev.",
    "Median",
    "Deviation",
    "Consistency",
];

/// The golfers named with summary words: the file's golfer column (a `Player` column added
/// when the preset maps one and the file has none). Every shot stays, number for number.
fn golfers_named_like_summaries(dir: &Path, f: &Fixture, text: &str, orig: &Import) {
    let mapping = smash::data::import::load_mapping(f.preset).unwrap();
    let Some(golfer) = mapping.column.iter().find(|c| c.target == "golfer") else {
        return;
    };
    if f.json() {
        // A JSON file's player name: every string value of a golfer key.
        let key = golfer.source[0].rsplit('.').next().unwrap();
        let needle = format!("\"{key}\":");
        if !text.contains(&needle) {
            return;
        }
        for word in SUMMARY_WORDS {
            let mut out = String::new();
            let mut rest = text;
            while let Some(i) = rest.find(&needle) {
                out.push_str(&rest[..i + needle.len()]);
                rest = &rest[i + needle.len()..];
                let value = rest.trim_start();
                if let Some(v) = value.strip_prefix('"') {
                    let close = v.find('"').unwrap();
                    out.push_str(&format!("\"{word}\""));
                    rest = &v[close + 1..];
                }
            }
            out.push_str(rest);
            check_golfers(dir, f, &out, orig, word, None);
        }
        return;
    }
    let Some((header_at, delimiter, cells)) = header_of(f, text) else {
        return;
    };
    let at = cells
        .iter()
        .position(|c| golfer.source.iter().any(|s| normal(s) == normal(c)));
    let shots = shot_lines(orig);
    let sep = (delimiter as char).to_string();
    for (n, word) in SUMMARY_WORDS.iter().enumerate() {
        let mut out = String::new();
        for (i, l) in lines_of(text).iter().enumerate() {
            let body = l.trim_end_matches(['\n', '\r']);
            let end = &l[body.len()..];
            let mut row = split(body, delimiter);
            let shot = shots.contains(&(i + 1));
            // Two names in turn, so a file of one golfer becomes one of two.
            let name = SUMMARY_WORDS[(n + i % 2) % SUMMARY_WORDS.len()];
            match at {
                Some(k) if shot && k < row.len() => row[k] = name.to_owned(),
                Some(_) => {}
                None if i == header_at => row.insert(0, golfer.source[0].clone()),
                None if i > header_at => row.insert(0, if shot { name } else { "" }.to_owned()),
                None => {}
            }
            if at.is_none() && i < header_at || (at.is_some() && !shot) {
                out.push_str(l);
                continue;
            }
            let mut w = csv::WriterBuilder::new()
                .delimiter(delimiter)
                .from_writer(Vec::new());
            w.write_record(&row).unwrap();
            let text = String::from_utf8(w.into_inner().unwrap()).unwrap();
            out.push_str(text.trim_end_matches(['\n', '\r']));
            out.push_str(end);
        }
        let _ = sep;
        check_golfers(dir, f, &out, orig, word, Some(delimiter));
    }
}

/// The import of `text`, golfers named `word`, has the original's shots, number for number.
fn check_golfers(dir: &Path, f: &Fixture, text: &str, orig: &Import, word: &str, _d: Option<u8>) {
    let what = format!("golfers named '{word}'");
    let m = import(dir, f, text.as_bytes(), &what);
    let label = format!("{} {what}", f.file);
    assert!(m.ok, "{label}: {}", m.err);
    assert_eq!(m.rows.len(), orig.rows.len(), "{label}: {}", m.err);
    let golfer = m
        .col("golfer")
        .unwrap_or_else(|| panic!("{label}: no golfer column"));
    assert!(
        m.rows
            .iter()
            .all(|r| SUMMARY_WORDS.contains(&r[golfer].as_str())),
        "{label}: {:?}",
        m.rows.iter().map(|r| &r[golfer]).collect::<Vec<_>>()
    );
    same_untouched(orig, &m, &|l| Some(l), &["golfer"], &label);
}

#[test]
fn every_preset_survives_its_mutations() {
    let dir = tempfile::tempdir().unwrap();
    for f in &FIXTURES {
        let bytes = f.bytes();
        let orig = import(dir.path(), f, &bytes, "as shipped");
        assert!(orig.ok, "{}: {}", f.file, orig.err);
        // The mutations edit text: a Windows-1252 fixture is edited as the import reads it.
        let text = match std::str::from_utf8(&bytes) {
            Ok(t) => t.to_owned(),
            Err(_) => bytes.iter().map(|&b| windows_1252(b)).collect(),
        };
        let orig = if text.as_bytes() == bytes.as_slice() {
            orig
        } else {
            let utf8 = import(dir.path(), f, text.as_bytes(), "saved as UTF-8");
            assert_eq!(utf8.rows, orig.rows, "{}: {}", f.file, utf8.err);
            utf8
        };
        truncations(dir.path(), f, &text, &orig);
        units_rows(dir.path(), f, &text, &orig);
        decimal_commas(dir.path(), f, &text, &orig);
        golfers_named_like_summaries(dir.path(), f, &text, &orig);
    }
    let n = IMPORTS.load(std::sync::atomic::Ordering::Relaxed);
    eprintln!("{n} imports of {} fixtures", FIXTURES.len());
}

/// The character of a Windows-1252 byte, for the bytes the fixtures hold (Latin-1 from 0xA0;
/// 0x94 is the right double quotation mark).
fn windows_1252(b: u8) -> char {
    match b {
        0x94 => '\u{201D}',
        0x80..=0x9F => panic!("byte 0x{b:02X}: add it to the test's table"),
        _ => char::from(b),
    }
}
