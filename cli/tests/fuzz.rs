//! Mutation fuzz of the file readers: club, study, synth and instrument-noise TOML, shots CSV,
//! user-effect definitions (their expressions, alone and in a club file) and launch files
//! (`smash flight`'s input, through both of its readers and the flight), import mapping files (the
//! presets) and launch-monitor exports read with their presets.
//!
//! Each case takes a valid file (the shipped configs, a generated shots file), applies one to
//! four random mutations (bytes, lines, numbers and fields replaced by hostile values) and parses
//! it. The reader must not panic, and must return either a value or an error whose message, as
//! the command line prints it, is one line without control characters.
//!
//! Seeded and bounded: the seeds are fixed, and the run stops after `SMASH_FUZZ_CASES` cases
//! (default 20,000) or `SMASH_FUZZ_SECONDS` seconds (default 20), whichever comes first. For a
//! long local run: `SMASH_FUZZ_SECONDS=300 SMASH_FUZZ_CASES=100000000 cargo test -p smash-cli --test cli fuzz::`.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn root() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
}

/// Fixed seeds: every CI run fuzzes the same cases.
const SEEDS: [u64; 4] = [1, 7, 2024, 0x5eed];

/// Values that broke readers before or sit at the edges of types and ranges.
const HOSTILE: [&str; 40] = [
    "\"cor * 1e400\"",
    "\"((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((cor\"",
    "\"-------------------------------------------------------------------------cor\"",
    "\"cor / 0 + ln(0 - cor) ^ 1e308\"",
    "1e308",
    "-1e308",
    "1e-320",
    "nan",
    "inf",
    "-inf",
    "NaN",
    "0",
    "-0",
    "0.0",
    "-1",
    "65536",
    "4294967296",
    "9223372036854775807",
    "-9223372036854775808",
    "18446744073709551615",
    "1e155",
    "1e200",
    "1e300",
    "300",
    "1000000",
    "100001",
    "\"\"",
    "[]",
    "{}",
    "[1e308, -1e308]",
    "true",
    "\"x\"",
    "{ from = -1e308, to = 1e308, count = 3 }",
    "{ from = 0, to = 1, step = 1e-300 }",
    "{ from = 0, to = 1, count = 65536 }",
    "[[1e308, 0, 0], [0, 1e308, 0], [0, 0, 1e308]]",
    "\"\u{1b}[31m\"",
    "é",
    "",
    "1e-300",
];

const BYTES: [u8; 22] = [
    0, b'\n', b'\r', b'"', b',', b'[', b']', b'{', b'}', b'=', b'#', b'.', b'-', b'e', b'9', 0x1b,
    0xff, b' ', b'\'', b'\\', b'\t', b'0',
];

fn lines(b: &[u8]) -> Vec<Vec<u8>> {
    b.split(|&c| c == b'\n').map(<[u8]>::to_vec).collect()
}

fn join(l: &[Vec<u8>]) -> Vec<u8> {
    l.join(&b'\n')
}

/// Spans of number-like tokens.
fn numbers(b: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        if b[i].is_ascii_digit() || (b[i] == b'-' && b.get(i + 1).is_some_and(u8::is_ascii_digit)) {
            let s = i;
            i += 1;
            while i < b.len() && (b[i].is_ascii_alphanumeric() || b"._+-".contains(&b[i])) {
                i += 1;
            }
            out.push((s, i));
        } else {
            i += 1;
        }
    }
    out
}

/// Spans of values: after `= ` in TOML, or CSV fields.
fn fields(b: &[u8], csv: bool) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start = 0;
    for (i, &c) in b.iter().enumerate() {
        if csv {
            if c == b',' || c == b'\n' {
                out.push((start, i));
                start = i + 1;
            }
        } else if c == b'=' {
            let end = b[i..]
                .iter()
                .position(|&c| c == b'\n')
                .map_or(b.len(), |p| i + p);
            out.push(((i + 1).min(end), end));
        }
    }
    out
}

fn mutate(rng: &mut ChaCha8Rng, input: &[u8], csv: bool) -> Vec<u8> {
    let mut b = input.to_vec();
    for _ in 0..rng.random_range(1..=4) {
        let pos = |rng: &mut ChaCha8Rng, b: &Vec<u8>| rng.random_range(0..=b.len());
        match rng.random_range(0..11) {
            // A short chunk repeated thousands of times: `((((…`, `-----…`, `abs(abs(…`
            // nested deeper than any recursive parser's stack.
            10 if !b.is_empty() && rng.random_bool(0.3) => {
                let i = rng.random_range(0..b.len());
                let n = rng.random_range(1..=4).min(b.len() - i);
                let chunk = b[i..i + n].repeat(rng.random_range(1_000..=30_000));
                let j = pos(rng, &b);
                b.splice(j..j, chunk);
            }
            0 if !b.is_empty() => {
                let i = rng.random_range(0..b.len());
                b[i] = BYTES[rng.random_range(0..BYTES.len())];
            }
            1 => {
                let i = pos(rng, &b);
                b.insert(i, BYTES[rng.random_range(0..BYTES.len())]);
            }
            2 if !b.is_empty() => {
                let i = rng.random_range(0..b.len());
                let n = rng.random_range(1..=8).min(b.len() - i);
                b.drain(i..i + n);
            }
            3 => {
                let mut l = lines(&b);
                let i = rng.random_range(0..l.len());
                let dup = l[i].clone();
                l.insert(i, dup);
                b = join(&l);
            }
            4 => {
                let mut l = lines(&b);
                if l.len() > 1 {
                    l.remove(rng.random_range(0..l.len()));
                }
                b = join(&l);
            }
            5 => {
                let mut l = lines(&b);
                let (i, j) = (rng.random_range(0..l.len()), rng.random_range(0..l.len()));
                l.swap(i, j);
                b = join(&l);
            }
            6 | 7 => {
                let spans = if rng.random_bool(0.5) {
                    numbers(&b)
                } else {
                    fields(&b, csv)
                };
                if !spans.is_empty() {
                    let (s, e) = spans[rng.random_range(0..spans.len())];
                    let v = HOSTILE[rng.random_range(0..HOSTILE.len())].as_bytes();
                    let v = if csv && rng.random_bool(0.7) {
                        v.iter().copied().filter(|c| *c != b',').collect()
                    } else {
                        v.to_vec()
                    };
                    b.splice(s..e, v);
                }
            }
            8 => {
                let i = pos(rng, &b);
                b.truncate(i);
            }
            _ if !b.is_empty() => {
                let i = rng.random_range(0..b.len());
                let n = rng.random_range(1..=32).min(b.len() - i);
                let chunk = b[i..i + n].to_vec();
                let j = pos(rng, &b);
                b.splice(j..j, chunk);
            }
            _ => {}
        }
    }
    b
}

/// One reader under test.
struct Target {
    name: &'static str,
    csv: bool,
    /// Valid inputs to mutate.
    corpus: Vec<Vec<u8>>,
    /// Parse the bytes as if read from `path`: `Ok(())` or the error.
    parse: fn(&Path, &[u8]) -> Result<(), anyhow::Error>,
}

fn read(rel: &str) -> Vec<u8> {
    let text = std::fs::read_to_string(root().join(rel)).unwrap();
    // Absolute club paths, so a study or synth file parsed from a temporary path finds its club.
    let club = root().join("configs/clubs/paper_driver.toml");
    text.replace(
        "\"../clubs/paper_driver.toml\"",
        &format!("{:?}", club.to_str().unwrap()),
    )
    .into_bytes()
}

/// A shots file with every column, measured launch and a few odd-but-valid cells.
fn shots_corpus() -> Vec<u8> {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let mut t = String::from(
        "shot_id,group,golfer,shaft_mass_g,club_speed_mph,attack_angle_deg,club_path_deg,\
         dynamic_loft_deg,face_angle_deg,lie_tilt_deg,club_omega_x_rad_s,club_omega_y_rad_s,\
         club_omega_z_rad_s,impact_y_mm,impact_z_mm,ball_speed_mph,launch_angle_deg,azimuth_deg,\
         backspin_rpm,sidespin_rpm,note\n",
    );
    for i in 0..12 {
        let r = |rng: &mut ChaCha8Rng, a: f64, b: f64| a + (b - a) * rng.random::<f64>();
        t.push_str(&format!(
            "s{i},{},G{},{:.1},{:.2},{:.2},{:.2},{:.2},{:.2},{:.2},{:.2},{:.2},{:.2},{:.2},{:.2},\
             {:.2},{:.2},{:.2},{:.0},{:.0},\"a, b\"\n",
            ["A", "B"][i % 2],
            i % 3,
            r(&mut rng, 50.0, 80.0),
            r(&mut rng, 90.0, 115.0),
            r(&mut rng, -4.0, 4.0),
            r(&mut rng, -4.0, 4.0),
            r(&mut rng, 8.0, 16.0),
            r(&mut rng, -4.0, 4.0),
            r(&mut rng, -2.0, 2.0),
            r(&mut rng, -2.0, 2.0),
            r(&mut rng, -2.0, 2.0),
            r(&mut rng, -2.0, 2.0),
            r(&mut rng, -10.0, 10.0),
            r(&mut rng, -15.0, 15.0),
            r(&mut rng, 130.0, 165.0),
            r(&mut rng, 8.0, 16.0),
            r(&mut rng, -4.0, 4.0),
            r(&mut rng, 2000.0, 3500.0),
            r(&mut rng, -600.0, 600.0),
        ));
    }
    t.into_bytes()
}

/// A launch file as `smash predict` and a launch monitor write it: measured and predicted
/// columns, a quoted note.
fn launch_corpus() -> Vec<u8> {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let mut t = String::from(
        "shot_id,ball_speed_mph,launch_angle_deg,azimuth_deg,backspin_rpm,sidespin_rpm,\
         pred_ball_speed_mph,pred_launch_angle_deg,pred_backspin_rpm,carry_yd,note\n",
    );
    for i in 0..8 {
        let r = |rng: &mut ChaCha8Rng, a: f64, b: f64| a + (b - a) * rng.random::<f64>();
        t.push_str(&format!(
            "d{i},{:.1},{:.1},{:.1},{:.0},{:.0},{:.1},{:.1},{:.0},{:.1},\"a, b\"\n",
            r(&mut rng, 60.0, 170.0),
            r(&mut rng, 5.0, 30.0),
            r(&mut rng, -4.0, 4.0),
            r(&mut rng, 1500.0, 9000.0),
            r(&mut rng, -800.0, 800.0),
            r(&mut rng, 60.0, 170.0),
            r(&mut rng, 5.0, 30.0),
            r(&mut rng, 1500.0, 9000.0),
            r(&mut rng, 100.0, 280.0),
        ));
    }
    t.into_bytes()
}

/// Read and fly a launch file through both of `smash flight`'s readers (in memory, and streamed
/// in small chunks to an output file); an output written must hold only finite numbers.
fn fly_launch_file(b: &[u8]) -> Result<(), anyhow::Error> {
    use smash::data::launch_read::read_launches;
    let dir = std::env::temp_dir().join(format!("smash-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    let (input, out) = (dir.join("launch.csv"), dir.join("flown.csv"));
    std::fs::write(&input, b)?;
    let cfg = smash::flight::FlightConfig::default();
    let table = read_launches(&input, Default::default())?;
    smash_cli::flight::collect(
        &input,
        &table.lines,
        table.source.prefix(),
        smash::flight::fly(&cfg, &table.launches),
    )?;
    smash::app::flight::stream::fly_csv_file(&input, &out, &cfg, Default::default(), 64)?;
    // The columns the flight adds (after the input's, which are copied as given) are finite
    // numbers or empty.
    let mut r = csv::Reader::from_path(&out)?;
    let width = table.headers.len();
    for rec in r.records() {
        let rec = rec?;
        for cell in rec.iter().skip(width) {
            let finite = cell.is_empty() || cell.parse::<f64>().is_ok_and(f64::is_finite);
            assert!(finite, "a flown file holds '{cell}' in {rec:?}");
        }
    }
    Ok(())
}

/// A file's bytes as they are (exports: byte-order marks and Windows-1252 bytes included).
fn read_bytes(rel: &str) -> Vec<u8> {
    std::fs::read(root().join(rel)).unwrap()
}

/// Import an export with a preset, and read the result back as the commands do.
fn import_export(preset: &str, p: &Path, b: &[u8]) -> Result<(), anyhow::Error> {
    use smash::data::import::{import, load_mapping, ImportOptions, OffsetSide};
    let mapping = load_mapping(preset)?;
    let opts = ImportOptions {
        impact_offset_positive: Some(OffsetSide::Toe),
        ..ImportOptions::default()
    };
    let imported = import(p, b, &mapping, &opts)?;
    if imported.complete_delivery > 0 {
        imported.read_back(p)?;
    }
    Ok(())
}

fn targets() -> Vec<Target> {
    let text = |b: &[u8]| String::from_utf8_lossy(b).into_owned();
    vec![
        Target {
            name: "club",
            csv: false,
            corpus: vec![read("configs/clubs/paper_driver.toml"), {
                // A club file with its own user-defined effect, named by an [[effect]] table.
                let mut c = read("configs/clubs/paper_driver.toml");
                c.extend_from_slice(
                    b"\n[[define_effect]]\nname = \"fuzz_club\"\nparams = [{ key = \"k\", \
                      unit = \"1\", default = 0.0, lower = -1.0, upper = 1.0 }]\n\
                      cor = \"min(cor * (1 - k * abs(impact_z_mm) / 40) ^ 2, 1)\"\n\
                      \n[[effect]]\nname = \"fuzz_club\"\nk = 0.1\n",
                );
                c
            }],
            parse: |p, b| {
                smash::data::club_file::parse_club(p, &String::from_utf8_lossy(b))?;
                Ok(())
            },
        },
        Target {
            name: "effect definitions",
            csv: false,
            corpus: vec![read("configs/effects/example_effects.toml")],
            parse: |p, b| {
                smash::data::effect_defs::parse_effect_defs(p, &String::from_utf8_lossy(b))?;
                Ok(())
            },
        },
        Target {
            name: "launch",
            csv: true,
            corpus: vec![launch_corpus()],
            parse: |_, b| fly_launch_file(b),
        },
        Target {
            name: "study",
            csv: false,
            corpus: ["face_map", "com_sweep", "optimise", "face_map_fine"]
                .iter()
                .map(|s| read(&format!("configs/studies/{s}.toml")))
                .collect(),
            parse: |p, b| {
                smash::study::parse_study(p, &String::from_utf8_lossy(b))?;
                Ok(())
            },
        },
        Target {
            name: "synth",
            csv: false,
            corpus: [
                "null_world",
                "paper_world",
                "cor_power_world",
                "face_flex_world",
                "loft_bias_world",
            ]
            .iter()
            .map(|s| read(&format!("configs/synth/{s}.toml")))
            .collect(),
            parse: |p, b| {
                smash::synth::parse_config(p, &String::from_utf8_lossy(b))?;
                Ok(())
            },
        },
        Target {
            name: "noise",
            csv: false,
            corpus: vec![read("configs/noise/paper_world.toml")],
            parse: |p, b| {
                smash::data::noise_file::parse_noise_file(p, &String::from_utf8_lossy(b))?;
                Ok(())
            },
        },
        Target {
            name: "shots",
            csv: true,
            corpus: vec![shots_corpus()],
            parse: |p, b| {
                smash::data::shots::parse_shots(p, b)?;
                Ok(())
            },
        },
        Target {
            name: "mapping",
            csv: false,
            corpus: smash::data::import::PRESETS
                .iter()
                .map(|(_, text)| text.as_bytes().to_vec())
                .collect(),
            parse: |p, b| {
                smash::data::import::parse_mapping(p, &String::from_utf8_lossy(b))?;
                Ok(())
            },
        },
        Target {
            name: "export trackman",
            csv: true,
            corpus: vec![
                read_bytes("cli/tests/fixtures/import/trackman_normalized.csv"),
                read_bytes("cli/tests/fixtures/import/trackman_older.csv"),
                read_bytes("cli/tests/fixtures/import/trackman_semicolon.csv"),
            ],
            parse: |p, b| import_export("trackman", p, b),
        },
        Target {
            name: "export flightscope",
            csv: true,
            corpus: vec![
                read_bytes("cli/tests/fixtures/import/flightscope_fsgolf.csv"),
                read_bytes("cli/tests/fixtures/import/flightscope_cp1252.csv"),
            ],
            parse: |p, b| import_export("flightscope", p, b),
        },
        Target {
            name: "export garmin-r10",
            csv: true,
            corpus: vec![read_bytes("cli/tests/fixtures/import/garmin_r10.csv")],
            parse: |p, b| import_export("garmin-r10", p, b),
        },
        Target {
            name: "export uneekor",
            csv: true,
            corpus: vec![
                read_bytes("cli/tests/fixtures/import/uneekor_range.csv"),
                read_bytes("cli/tests/fixtures/import/uneekor_refine.csv"),
            ],
            parse: |p, b| import_export("uneekor", p, b),
        },
        Target {
            name: "export rapsodo",
            csv: true,
            corpus: vec![read_bytes("tests/data/real/rapsodo_mlm2pro_mixed.csv")],
            parse: |p, b| import_export("rapsodo", p, b),
        },
        Target {
            name: "export foresight",
            csv: true,
            corpus: vec![read_bytes("cli/tests/fixtures/import/foresight_fsx.csv")],
            parse: |p, b| import_export("foresight", p, b),
        },
    ]
    .into_iter()
    .inspect(|t| {
        // The unmutated corpus parses: the fuzz starts from valid files.
        for c in &t.corpus {
            if let Err(e) = (t.parse)(Path::new("corpus"), c) {
                panic!("{} corpus does not parse: {e}\n{}", t.name, text(c));
            }
        }
    })
    .collect()
}

fn env_or(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

#[test]
fn mutated_files_never_panic_and_errors_are_one_line() {
    let budget = Duration::from_secs(env_or("SMASH_FUZZ_SECONDS", 20));
    let max_cases = env_or("SMASH_FUZZ_CASES", 20_000);
    let targets = targets();
    let path = root().join("configs/studies/fuzz_case.toml");
    let start = Instant::now();
    let mut cases = 0u64;
    let mut errors = 0u64;
    let mut failures: Vec<String> = Vec::new();
    // Panics are caught and reported with their input; keep the default hook quiet meanwhile.
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    'outer: for round in 0.. {
        for seed in SEEDS {
            let mut rng = ChaCha8Rng::seed_from_u64(seed.wrapping_mul(1_000_003) + round);
            for t in &targets {
                for c in &t.corpus {
                    if cases >= max_cases || start.elapsed() > budget {
                        break 'outer;
                    }
                    cases += 1;
                    let input = mutate(&mut rng, c, t.csv);
                    let shown = || {
                        let s = String::from_utf8_lossy(&input);
                        format!("{:?}", s.chars().take(4000).collect::<String>())
                    };
                    match catch_unwind(AssertUnwindSafe(|| (t.parse)(&path, &input))) {
                        Err(p) => {
                            let why = p
                                .downcast_ref::<String>()
                                .cloned()
                                .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                                .unwrap_or_default();
                            failures.push(format!(
                                "{} (seed {seed}, round {round}): panic '{why}' on {}",
                                t.name,
                                shown()
                            ));
                        }
                        Ok(Err(e)) => {
                            errors += 1;
                            let line = smash_cli::error_chain(&e);
                            // One line, and no control character reaches the terminal.
                            if line.chars().any(char::is_control) || line.trim().is_empty() {
                                failures.push(format!(
                                    "{} (seed {seed}, round {round}): message {line:?} on {}",
                                    t.name,
                                    shown()
                                ));
                            }
                        }
                        Ok(Ok(())) => {}
                    }
                    if failures.len() >= 5 {
                        break 'outer;
                    }
                }
            }
        }
    }
    std::panic::set_hook(hook);
    eprintln!(
        "fuzz: {cases} cases ({errors} refused) in {:.1} s",
        start.elapsed().as_secs_f64()
    );
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    assert!(cases >= 100, "only {cases} cases ran");
}
