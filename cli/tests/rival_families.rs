//! Issue 43's worlds over seeds, as a user runs them (`smash synth --config WORLD --seed N`,
//! then `smash diagnose --json`, with the world's true noise and without noise figures). The
//! worlds and seeds were written down before the first run (`docs/rival-families.md`, "Plan");
//! the bounds are the rates measured when the tests were written (28 Nov 2026) and may only
//! tighten. Where they fall short of the issue's done-when, the doc says so.
//!
//! - `aniso_paper_world` (the paper world with a world-only COR falloff 2.5e-4·y² + 1e-4·z²),
//!   seeds 1–20: before the rival-family check (`src/diagnose/rival_family.rs`) `cor_radial`
//!   was a false finding in 9 of 20 seeds in each setting; measured now 0 of 20 with the true
//!   noise and 2 of 20 without (seeds 14, 18: the location terms gain 27.6 and 31.0 beyond
//!   `cor_radial`'s form against a penalty of 32.0). `ball_offset` is a finding in 20 of 20.
//!   The added mass is named in none: `cor_radial`'s uncentred falloff takes its ball-speed
//!   level (`docs/rival-families.md`).
//! - `paper_world`, seeds 1–20: the added mass (per shaft, `shaft_fraction` or an alias
//!   carrying it) is named — selected, or ambiguous with a plausible rival — or stated as not
//!   resolved with the candidates it cannot be told from, in 15 of 20 with the true noise
//!   (9 named, 6 stated) and 18 of 20 without (16 named, 2 stated; 13 and 2 before the near
//!   rivals of `docs/rival-families.md` named it beside `hosel_mass`). No false finding in either
//!   setting: without noise figures `hosel_mass` was one in seeds 15 and 17 until the level
//!   check (a location form must gain over a face-wide level too) made it a stand-in.
//! - `plateau_paper_world`, seeds 1–10, with the true noise: no false finding (10 of 10). The
//!   ball-speed error the plateau leaves (high at the top and bottom of the face, low in the
//!   middle) is within the given noise in size (spread ratio 0.86–0.94) but the noise floor's
//!   shape search names it against impact location (`face_quadratic`, p 7.5e-6 to 2.4e-15) in
//!   10 of 10 seeds, and no seed names a straight line (measured 28 Nov 2026, before the bound
//!   was written).
//! - The design worlds (`cli/tests/fixtures/rivals/`, seeds 301–310, `--instrument camera`
//!   and without): `#[ignore]`d, about 100 diagnoses; the rates are in the doc.

use crate::cli_support;

use cli_support::{diagnose_json, repo, s, synth_config as synth};
use std::path::Path;

fn strings(v: &serde_json::Value) -> Vec<String> {
    v.as_array()
        .map(|a| {
            a.iter()
                .filter_map(|f| f.as_str().map(str::to_owned))
                .collect()
        })
        .unwrap_or_default()
}

/// Is `label` (`name.param`, `name@A.param`, `name` or `name@group`) of one of `family`?
fn of(label: &str, family: &[&str]) -> bool {
    let name = label.split(['.', '@']).next().unwrap_or(label);
    family.contains(&name)
}

/// One diagnosis read against the truth: (a finding outside `truth`, per family: named,
/// stated as not resolved).
fn read(d: &serde_json::Value, truth: &[&[&str]]) -> (Vec<String>, Vec<(bool, bool)>) {
    let findings = strings(&d["findings"]);
    let all: Vec<&str> = truth.iter().flat_map(|f| f.iter().copied()).collect();
    let wrong = findings.iter().filter(|f| !of(f, &all)).cloned().collect();
    let ambiguous: Vec<&serde_json::Value> = d["ambiguous"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|a| a["ambiguous"] == true)
        .collect();
    let per_family = truth
        .iter()
        .map(|fam| {
            let found = findings.iter().any(|f| of(f, fam));
            let selected_ambiguous = ambiguous
                .iter()
                .any(|a| of(a["selected"].as_str().unwrap(), fam));
            let plausible_rival = ambiguous.iter().any(|a| {
                a["rivals"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .any(|r| r["plausible"] == true && of(r["effect"].as_str().unwrap(), fam))
            });
            let u = &d["unresolved"];
            let stated = !u.is_null()
                && (of(u["effect"].as_str().unwrap(), fam)
                    || u["alike"]
                        .as_array()
                        .unwrap()
                        .iter()
                        .any(|a| of(a["candidate"].as_str().unwrap(), fam)));
            (found || selected_ambiguous || plausible_rival, stated)
        })
        .collect();
    (wrong, per_family)
}

/// Over `seeds` of `config` diagnosed with `args`: seeds with a false finding, and per family
/// of `truth` the seeds naming it and the seeds only stating it as not resolved.
fn tally(
    config: &Path,
    seeds: std::ops::RangeInclusive<u32>,
    args: &[&str],
    truth: &[&[&str]],
) -> (usize, Vec<(usize, usize)>) {
    tally_with(config, seeds, args, truth, |_, _| {})
}

/// [`tally`], handing each seed's diagnosis to `each` too.
fn tally_with(
    config: &Path,
    seeds: std::ops::RangeInclusive<u32>,
    args: &[&str],
    truth: &[&[&str]],
    mut each: impl FnMut(u32, &serde_json::Value),
) -> (usize, Vec<(usize, usize)>) {
    let dir = tempfile::tempdir().unwrap();
    let mut false_seeds = 0;
    let mut counts = vec![(0, 0); truth.len()];
    for seed in seeds {
        let d = diagnose_json(&synth(dir.path(), config, seed), args);
        each(seed, &d);
        let (wrong, fams) = read(&d, truth);
        println!(
            "{} seed {seed} {args:?}: selected {:?}, findings {:?}, false {wrong:?}, \
             named/stated {fams:?}",
            config.display(),
            strings(&d["selected"]),
            strings(&d["findings"])
        );
        false_seeds += usize::from(!wrong.is_empty());
        for (c, (named, stated)) in counts.iter_mut().zip(fams) {
            c.0 += usize::from(named);
            c.1 += usize::from(!named && stated);
        }
    }
    println!(
        "{}: false {false_seeds}, named/stated {counts:?}",
        config.display()
    );
    (false_seeds, counts)
}

const MASS: &[&str] = &["added_mass", "shaft_fraction"];
const OFFSET: &[&str] = &["ball_offset"];

#[test]
fn anisotropic_cor_world_over_twenty_seeds() {
    let world = repo("configs/synth/aniso_paper_world.toml");
    let noise = repo("configs/noise/paper_world.toml");
    for (args, bound) in [(vec!["--noise", s(&noise)], 0), (vec![], 2)] {
        let (false_seeds, counts) = tally(&world, 1..=20, &args, &[MASS, OFFSET]);
        assert!(
            false_seeds <= bound,
            "{args:?}: {false_seeds} seeds with a false finding"
        );
        assert!(
            counts[1].0 >= 18,
            "{args:?}: ball_offset named in {}",
            counts[1].0
        );
    }
}

#[test]
fn paper_world_mass_named_or_stated() {
    let world = repo("configs/synth/paper_world.toml");
    let noise = repo("configs/noise/paper_world.toml");
    // Without noise figures the mass is named in 16 and stated in 2 since the near rivals
    // (29 Nov 2026: `hosel_mass` in seeds 15, 17 and 20 has the added mass as its rival).
    for (args, bound) in [(vec!["--noise", s(&noise)], 15), (vec![], 18)] {
        let (false_seeds, counts) = tally(&world, 1..=20, &args, &[MASS, OFFSET]);
        let (named, stated) = counts[0];
        assert!(
            named + stated >= bound,
            "{args:?}: mass named {named}, stated {stated}"
        );
        assert!(
            counts[1].0 >= 18,
            "{args:?}: ball_offset named in {}",
            counts[1].0
        );
        // Without noise figures `hosel_mass` was a finding in two seeds (15, 17) until the
        // level check made it a stand-in for a face-wide level (measured 0 of 20 since).
        assert!(
            false_seeds == 0,
            "{args:?}: {false_seeds} seeds with a false finding"
        );
    }
}

/// The noise floor's pointer for ball speed in one diagnosis: the term its shape search names
/// (`face_map_bins`, …, or `null`), the linear trend's variable and r, and the verdict.
fn ball_speed_pointer(d: &serde_json::Value) -> (Option<String>, Option<(String, f64)>, String) {
    let c = d["noise_floor"]["components"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["component"] == "ball_speed_mph")
        .unwrap();
    let found = c["shape"]["found"].as_str().map(str::to_owned);
    let trend = (!c["trend"].is_null()).then(|| {
        (
            c["trend"]["variable"].as_str().unwrap().to_owned(),
            c["trend"]["r"].as_f64().unwrap(),
        )
    });
    (found, trend, c["verdict"].as_str().unwrap().to_owned())
}

/// No false finding; and the ball-speed error the plateau leaves (high at the edges of the
/// face, low in the middle: r ≈ 0 with every straight line) is pointed at impact location, the
/// face map, never at a straight line with a weak r.
#[test]
fn plateau_world_has_no_false_finding() {
    let world = repo("configs/synth/plateau_paper_world.toml");
    let noise = repo("configs/noise/paper_world.toml");
    let mut pointers = Vec::new();
    let (false_seeds, _) = tally_with(
        &world,
        1..=10,
        &["--noise", s(&noise)],
        &[MASS, OFFSET],
        |seed, d| pointers.push((seed, ball_speed_pointer(d))),
    );
    assert_eq!(false_seeds, 0, "{false_seeds} seeds with a false finding");
    for (seed, (found, trend, verdict)) in &pointers {
        println!("seed {seed}: found {found:?}, trend {trend:?}: {verdict}");
    }
    let face = |f: &Option<String>| {
        f.as_deref()
            .is_some_and(|t| t == "face_map_bins" || t == "face_quadratic")
    };
    let named_face = pointers.iter().filter(|(_, p)| face(&p.0)).count();
    let weak_line = pointers
        .iter()
        .filter(|(_, p)| {
            p.2.contains("trends with") && p.1.as_ref().is_some_and(|t| t.1.abs() < 0.1)
        })
        .count();
    assert_eq!(weak_line, 0, "a straight line with r < 0.1 named");
    assert!(
        named_face >= FACE_NAMED_MIN,
        "face map named in {named_face} of 10"
    );
}

/// Plateau seeds (of 1–10) whose ball-speed leftover the face map names, at least.
const FACE_NAMED_MIN: usize = 10;

/// A design world: its file stem, the families of its truth, and per family the seeds of ten
/// naming it as measured when written (the lower of the two settings).
type DesignWorld = (&'static str, &'static [&'static [&'static str]], [usize; 2]);

/// The design worlds of `docs/rival-families.md`: at most one seed of ten with a false
/// finding per world and setting, and every world's truth named at least as often as measured
/// when written. `cargo test --release -p smash-cli --test cli rival_families:: -- --ignored`.
#[test]
#[ignore = "about 100 diagnoses; run with --ignored"]
fn design_worlds_over_ten_seeds() {
    let worlds: [DesignWorld; 6] = [
        ("spot_mass", &[&["cor_spot"], MASS], [9, 2]),
        ("fraction_offset", &[MASS, OFFSET], [10, 10]),
        ("mass_loft", &[MASS, &["loft_bias"]], [7, 10]),
        ("mass_loft_flex", &[MASS, &["loft_bias"]], [1, 10]),
        ("fraction_offset_speed", &[MASS, OFFSET], [10, 0]),
        ("hosel_offset", &[&["hosel_mass"], OFFSET], [10, 10]),
    ];
    for (world, truth, named) in worlds {
        let config = repo(&format!("cli/tests/fixtures/rivals/{world}.toml"));
        for args in [vec!["--instrument", "camera"], vec![]] {
            let (false_seeds, counts) = tally(&config, 301..=310, &args, truth);
            assert!(false_seeds <= 1, "{world} {args:?}: {false_seeds} false");
            for ((n, _), min) in counts.iter().zip(named) {
                assert!(*n >= min, "{world} {args:?}: named {counts:?}");
            }
        }
    }
}
