//! End to end on synthetic worlds made by `smash synth` with its default measurement noise
//! (launch monitor on the launch, motion capture on the delivery, 1.5 mm on the impact
//! location): `smash diagnose --json` must name the hidden effect first, find the hidden
//! effect *family* when the world's physics is not a library form, select nothing in a world
//! with nothing hidden, and account for impact-location noise instead of blaming physics.
//!
//! The shipped compliant-contact worlds (`configs/synth/compliant_*.toml`, 3000 shots each) are
//! synthesised and diagnosed once per test binary ([`shipped`]); every test about them asserts
//! on that shared run. Rules of the selection shown on a compliant world run on 600-shot
//! fixtures (`cli/tests/fixtures/`).

use crate::cli_support;

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use cli_support::{repo, smash};

/// Generate a world from `config` into `dir` (as `<name>.csv`).
fn synth(dir: &Path, name: &str, config: &Path) -> PathBuf {
    let shots = dir.join(format!("{name}.csv"));
    let o = smash(&[
        "synth",
        "--config",
        config.to_str().unwrap(),
        "--out",
        shots.to_str().unwrap(),
    ]);
    assert!(
        o.status.success(),
        "synth {name}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    shots
}

/// Generate a world from `config` and diagnose it with the nominal paper club.
fn diagnose_world(dir: &Path, name: &str, config: &Path, extra: &[&str]) -> serde_json::Value {
    let shots = synth(dir, name, config);
    let club = repo("configs/clubs/paper_driver.toml");
    let mut args = vec![
        "diagnose",
        "--club",
        club.to_str().unwrap(),
        "--shots",
        shots.to_str().unwrap(),
        "--json",
    ];
    args.extend_from_slice(extra);
    let o = smash(&args);
    assert!(
        o.status.success(),
        "diagnose {name}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).expect("one JSON object on stdout")
}

fn selected(d: &serde_json::Value) -> Vec<String> {
    d["selected"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap().to_owned())
        .collect()
}

fn hidden_world(dir: &Path, effect: &str, params: &str, seed: u64) -> PathBuf {
    let p = dir.join(format!("{effect}_world.toml"));
    let club = repo("configs/clubs/paper_driver.toml");
    let text = format!(
        "club = {:?}\nseed = {seed}\n\n[[hidden]]\nname = \"{effect}\"\n{params}\n",
        club.to_str().unwrap()
    );
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn each_hidden_library_effect_is_named_first() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        ("added_mass", "dm_g = 2.5"),
        ("ball_offset", "dy_mm = 0.48\ndz_mm = -0.07"),
        ("tangential_restitution", "et = -0.2"),
        ("friction", "mu = 0.05"),
        ("cor_speed", "k_per_m_s = 0.002"),
        ("cor_radial", "c_per_mm2 = 0.0002"),
        ("loft_bias", "deg = 1"),
        ("face_bias", "deg = -1.5"),
        ("com_offset", "dx_mm = -3\ndy_mm = -2\ndz_mm = 1.5"),
        ("inertia_scale", "s = 1.2"),
    ];
    let mut wrong = Vec::new();
    for (i, (effect, params)) in cases.iter().enumerate() {
        let cfg = hidden_world(dir.path(), effect, params, 11 + i as u64);
        let d = diagnose_world(dir.path(), effect, &cfg, &[]);
        let sel = selected(&d);
        // On launch data alone some library effects are aliases: `added_mass` and `cor_level`
        // change ball speed alike (so does `hosel_mass` at the centre), `cor_speed` and
        // `cor_power` differ only by curvature over the speeds of one experiment. Naming the
        // alias first is the data's limit, not a wrong diagnosis.
        let aliases: Vec<&str> = match *effect {
            "added_mass" => vec!["added_mass", "cor_level", "hosel_mass"],
            "cor_speed" => vec!["cor_speed", "cor_power"],
            e => vec![e],
        };
        if !sel.first().is_some_and(|s| aliases.contains(&s.as_str())) {
            wrong.push(format!("{effect}: selected {sel:?}"));
        }
    }
    assert!(wrong.is_empty(), "hidden effect not named first: {wrong:?}");
}

#[test]
fn worlds_off_the_library_lead_to_the_right_family() {
    let dir = tempfile::tempdir().unwrap();
    for (world, family) in [
        ("cor_power_world", "cor_power"),
        ("face_flex_world", "cor_radial"),
        ("loft_bias_world", "loft_bias"),
        ("paper_world", "ball_offset"),
    ] {
        let d = diagnose_world(
            dir.path(),
            world,
            &repo(&format!("configs/synth/{world}.toml")),
            &[],
        );
        let sel = selected(&d);
        assert_eq!(
            sel.first().map(String::as_str),
            Some(family),
            "{world}: selected {sel:?}"
        );
    }
}

#[test]
fn null_world_selects_nothing_and_finds_the_location_noise_instead() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = repo("configs/synth/null_world.toml");
    let d = diagnose_world(dir.path(), "null", &cfg, &[]);
    assert!(
        selected(&d).is_empty(),
        "null world selected {:?}",
        selected(&d)
    );
    let noise = &d["impact_noise_mm"];
    assert_eq!(noise["estimated"], true, "{noise}");
    let sy = noise["y"].as_f64().unwrap();
    assert!(
        (1.0..=2.0).contains(&sy),
        "synth's 1.5 mm location noise, found {sy} mm"
    );
    // Taking the noisy locations as exact, no noise is modelled. (Before physical candidates
    // paid 2·ln m for the best of m, this world then selected a spurious effect; with the
    // correction it does not, and tests/diagnose_fdr.rs measures the rate over 20 seeds.)
    let exact = diagnose_world(
        dir.path(),
        "null_exact",
        &cfg,
        &["--exact-impact-locations"],
    );
    assert!(exact["impact_noise_mm"].is_null());
}

#[test]
fn opt_in_candidates_name_the_hidden_power_law_cor() {
    // Among only its ball-speed neighbours (its linear cousin cor_speed, cor_level and
    // added_mass), the shipped world (library cor_power, q = 0.15) must be named as such.
    let dir = tempfile::tempdir().unwrap();
    let d = diagnose_world(
        dir.path(),
        "cor_power_opt_in",
        &repo("configs/synth/cor_power_world.toml"),
        &["--candidates", "cor_power,cor_speed,cor_level,added_mass"],
    );
    let sel = selected(&d);
    assert_eq!(
        sel.first().map(String::as_str),
        Some("cor_power"),
        "selected {sel:?}"
    );
}

const SPEED_COR: &[&str] = &["cor_speed", "cor_power"];
const SHAFT: &[&str] = &["hosel_mass"];
const TANGENTIAL: &[&str] = &["tangential_compliance"];
const CONTACT_TIME: &[&str] = &["contact_time"];

/// The shipped compliant-contact worlds with the physics each contains (alternatives per
/// ingredient: a library form that names it).
const COMPLIANT: [(&str, &[&[&str]]); 3] = [
    (
        "compliant_driver",
        &[SPEED_COR, SHAFT, TANGENTIAL, CONTACT_TIME],
    ),
    (
        "compliant_location_noise",
        &[SPEED_COR, SHAFT, TANGENTIAL, CONTACT_TIME],
    ),
    (
        "compliant_slip_world",
        &[SPEED_COR, TANGENTIAL, CONTACT_TIME],
    ),
];

/// `smash diagnose --json --instrument camera` (the camera-class noise floor: the worlds' own
/// instrument noise) of the shipped compliant world `world`, synthesised and diagnosed once per
/// test binary and shared by every test that asks for it (each takes about a minute).
fn shipped(world: &str) -> &'static serde_json::Value {
    static RUNS: [OnceLock<serde_json::Value>; 3] =
        [OnceLock::new(), OnceLock::new(), OnceLock::new()];
    let i = COMPLIANT
        .iter()
        .position(|(w, _)| *w == world)
        .unwrap_or_else(|| panic!("{world} is not a shipped compliant world"));
    RUNS[i].get_or_init(|| {
        let dir = tempfile::tempdir().unwrap();
        let config = repo(&format!("configs/synth/{world}.toml"));
        let d = diagnose_world(dir.path(), world, &config, &["--instrument", "camera"]);
        assert_eq!(
            d["n_shots"], 3000,
            "{world}: the shipped worlds have 3000 shots"
        );
        d
    })
}

/// The estimate of `effect.param` in a diagnosis, if selected.
fn estimate<'a>(
    d: &'a serde_json::Value,
    effect: &str,
    param: &str,
) -> Option<&'a serde_json::Value> {
    d["estimates"]
        .as_array()
        .unwrap()
        .iter()
        .find(|e| e["effect"] == effect && e["param"] == param)
}

/// The done-when conditions of issue 9 on one diagnosed compliant-contact world: what fails, as
/// text. An ingredient counts as named when one of its forms is selected with a plausible value
/// that is not on its no-effect bound (`"status": "absent"`).
fn compliant_world_failures(d: &serde_json::Value, physics: &[&[&str]]) -> Vec<String> {
    let mut fails = Vec::new();
    let floor = &d["noise_floor"];
    let launch_sd = &floor["instrument"]["launch_sd"];
    // Every group's mean error below 0.2 σ of the launch noise.
    for (g, comps) in d["after"].as_object().unwrap() {
        for (c, ms) in comps.as_object().unwrap() {
            let m = ms["mean"].as_f64().unwrap() / launch_sd[c].as_f64().unwrap();
            if m.abs() >= 0.2 {
                fails.push(format!("group {g} {c}: mean {m:+.2} σ"));
            }
        }
    }
    // Spread within 1.10× the noise floor.
    for c in floor["components"].as_array().unwrap() {
        let r = c["ratio"].as_f64().unwrap();
        if r > 1.10 {
            fails.push(format!("{}: {r:.2}× the noise floor", c["component"]));
        }
    }
    // No implausible value presented as found: every implausible estimate carries its stand-in
    // reading, and the selected effects must name the world's physics with plausible values.
    let est = d["estimates"].as_array().unwrap();
    for e in est {
        if e["plausible"] == false && (e["stand_in"].is_null() || e["status"] != "stand_in") {
            fails.push(format!(
                "{}.{} implausible without a stand-in reading",
                e["effect"], e["param"]
            ));
        }
    }
    for alternatives in physics {
        let named = est.iter().any(|e| {
            alternatives.contains(&e["effect"].as_str().unwrap())
                && e["plausible"] == true
                && e["status"] != "absent"
        });
        if !named {
            fails.push(format!(
                "physics not named plausibly: one of {alternatives:?}"
            ));
        }
    }
    fails
}

/// Issue 9's first done-when line, asserted in full on every shipped compliant world (3000
/// shots: at 600 a group mean's standard error, 0.13–0.16 σ of the launch noise, is too close to
/// the 0.2 σ criterion; docs/compliant-worlds.md, "Group means").
#[test]
fn compliant_worlds_meet_the_issue_9_done_when() {
    let mut all = Vec::new();
    for (world, physics) in COMPLIANT {
        let d = shipped(world);
        let fails = compliant_world_failures(d, physics);
        eprintln!("{world}: selected {:?}; failures {fails:?}", selected(d));
        all.extend(fails.into_iter().map(|f| format!("{world}: {f}")));
    }
    assert!(all.is_empty(), "{all:#?}");
}

/// A stand-in gives way to its plausible alias (`docs/diagnose-selection.md`, "A stand-in and
/// its plausible alias"), on the fixture `slip_world_off_ranges_600.toml` (the slip world before
/// its truth was put inside the plausible ranges: a face at `cor_ref` 0.85, +0.02 against the
/// file's 0.83). Forward selection takes `added_mass` for the livelier face first (+12.7 g, beyond
/// its plausible range: a stand-in), with `cor_level` as its kin (the same change to the
/// predictions, r = 1.00). The swap round must replace the stand-in by `cor_level` at the world's
/// +0.02 (same size, CV χ² worse by less than ln n), and `added_mass` must not be left among the
/// selected effects or findings.
#[test]
fn a_stand_in_gives_way_to_its_plausible_alias() {
    let dir = tempfile::tempdir().unwrap();
    let d = diagnose_world(
        dir.path(),
        "slip_world_off_ranges_600",
        &repo("cli/tests/fixtures/slip_world_off_ranges_600.toml"),
        &["--instrument", "camera"],
    );
    let sel = selected(&d);
    assert!(!sel.contains(&"added_mass".to_owned()), "{sel:?}");
    let steps = d["steps"].as_array().unwrap();
    assert_eq!(
        steps.first().map(|s| &s["selected"]),
        Some(&serde_json::json!("added_mass")),
        "forward selection no longer takes the stand-in first: {sel:?}"
    );
    let swap = steps
        .iter()
        .filter_map(|s| s["swap"].as_object())
        .find(|s| s["out"] == "added_mass")
        .unwrap_or_else(|| panic!("no swap of added_mass: {sel:?}"));
    assert_eq!(swap["in"], "cor_level", "{swap:?}");
    let cor = estimate(&d, "cor_level", "dcor")
        .unwrap_or_else(|| panic!("cor_level not selected: {sel:?}"));
    let v = cor["value"].as_f64().unwrap();
    assert!(
        (0.012..=0.028).contains(&v) && cor["plausible"] == true,
        "{cor}"
    );
    let findings = d["findings"].as_array().unwrap();
    assert!(
        !findings.iter().any(|f| f == "added_mass.dm_g"),
        "{findings:?}"
    );
}

/// Greedy forward selection cannot undo a step; the swap rounds can. On the fixture
/// `compliant_driver_600.toml` (the shipped `compliant_driver` at 600 shots), among the world's
/// own physics and the stand-in (`com_offset`), forward selection takes `com_offset` at step 4
/// (3 parameters, more CV gain than `hosel_mass`: 431 against 374 on release, dx a stand-in) and
/// `hosel_mass` after it; then replacing `com_offset` by `contact_time` lowers the CV χ² by far
/// more than the penalty (2970.2 → 2874.3 on release), leaving the world's physics with
/// plausible values (tip 6 g, contact 0.46 ms in the world).
#[test]
fn a_swap_replaces_the_greedy_stand_in_with_the_worlds_physics() {
    let dir = tempfile::tempdir().unwrap();
    let d = diagnose_world(
        dir.path(),
        "compliant_driver_600",
        &repo("cli/tests/fixtures/compliant_driver_600.toml"),
        &[
            "--instrument",
            "camera",
            "--candidates",
            "tangential_compliance,cor_speed,compression_lever,com_offset,hosel_mass,contact_time",
        ],
    );
    let steps = d["steps"].as_array().unwrap();
    assert!(
        steps.iter().any(|s| s["selected"] == "com_offset"),
        "forward selection no longer takes the stand-in: {:?}",
        selected(&d)
    );
    let swap = steps
        .iter()
        .find_map(|s| s["swap"].as_object())
        .unwrap_or_else(|| panic!("no swap: {:?}", selected(&d)));
    assert_eq!(swap["out"], "com_offset", "{swap:?}");
    assert!(
        swap["cv_chi2_after"].as_f64().unwrap() < swap["cv_chi2_before"].as_f64().unwrap(),
        "{swap:?}"
    );
    let sel = selected(&d);
    assert!(!sel.contains(&"com_offset".to_owned()), "{sel:?}");
    for (effect, param, lo, hi) in [
        ("hosel_mass", "dm_g", 5.0, 7.5),
        ("contact_time", "tau_ms", 0.38, 0.55),
    ] {
        let e =
            estimate(&d, effect, param).unwrap_or_else(|| panic!("{effect} not selected: {sel:?}"));
        let v = e["value"].as_f64().unwrap();
        assert!(v > lo && v < hi && e["plausible"] == true, "{e}");
    }
}

/// The report's honesty on the shipped worlds: only a plausible value without a plausible rival
/// or alias is listed as found, and every implausible value is a stand-in.
fn assert_reported_honestly(world: &str, d: &serde_json::Value) {
    let findings = d["findings"].as_array().unwrap();
    for e in d["estimates"].as_array().unwrap() {
        let label = format!(
            "{}.{}",
            e["effect"].as_str().unwrap(),
            e["param"].as_str().unwrap()
        );
        let found = findings.iter().any(|f| f == &label);
        assert_eq!(found, e["status"] == "finding", "{world}: {e}");
        if e["plausible"] == false {
            assert_eq!(e["status"], "stand_in", "{world}: {e}");
            assert!(e["stand_in"].is_string(), "{world}: {e}");
        }
    }
}

/// What the shipped 3000-shot worlds show beyond the done-when line (configs/README.md has the
/// output): in every world the speed-dependent COR with a slope near the Hunt–Crossley contact's
/// (0.83 at 48.77 m/s falling to ≈ 0.818 at 54 m/s: ≈ 0.0025–0.003 s/m), the tangential
/// compliance with plausible et0 and k_tan, the compressed ball's lever with a plausible δ̄ (the
/// balls peak at ≈ 6.5 mm) and the contact time inside its plausible range; the shaft tip (6 g)
/// as a positive `hosel_mass` in the two worlds that have one, and none in the slip world, which
/// has no tip; the slip world's livelier face (+0.008) as `cor_level` near +0.008, selected or
/// the rival that makes an `added_mass` ambiguous (the two alias on launch data), never an
/// `added_mass` finding.
#[test]
fn compliant_worlds_name_the_cor_law_and_flag_stand_ins() {
    // In the reverse order of the done-when test, so that the two start on different worlds
    // when the harness runs them side by side.
    for &(world, _) in COMPLIANT.iter().rev() {
        let d = shipped(world);
        let sel = selected(d);
        assert_reported_honestly(world, d);
        let value = |effect: &str, param: &str| {
            let e = estimate(d, effect, param)
                .unwrap_or_else(|| panic!("{world}: {effect} not selected: {sel:?}"));
            assert_eq!(e["plausible"], true, "{world}: {e}");
            e["value"].as_f64().unwrap()
        };
        let k = estimate(d, "cor_speed", "k_per_m_s").map(|_| value("cor_speed", "k_per_m_s"));
        let q = estimate(d, "cor_power", "q").map(|_| value("cor_power", "q"));
        assert!(
            k.is_some_and(|k| (0.002..=0.0035).contains(&k))
                || q.is_some_and(|q| (0.1..=0.2).contains(&q)),
            "{world}: speed-dependent COR k {k:?}, q {q:?}: {sel:?}"
        );
        value("tangential_compliance", "et0");
        value("tangential_compliance", "k_tan");
        let delta = value("compression_lever", "delta_mm");
        assert!(delta > 3.0, "{world}: δ̄ {delta} mm");
        let tau = value("contact_time", "tau_ms");
        assert!(tau > 0.15, "{world}: contact time {tau} ms");
        let tip = estimate(d, "hosel_mass", "dm_g");
        if world == "compliant_slip_world" {
            assert!(tip.is_none(), "{world}: a shaft tip where none is: {tip:?}");
            livelier_face_is_named_as_such(d);
        } else {
            let m = value("hosel_mass", "dm_g");
            assert!(
                (3.0..=8.0).contains(&m),
                "{world}: tip {m} g (the world's: 6 g)"
            );
        }
    }
}

/// The slip world's face is +0.008 livelier than its file: `cor_level` near that, selected or as
/// the rival of an ambiguous `added_mass`; `added_mass` never a finding.
fn livelier_face_is_named_as_such(d: &serde_json::Value) {
    let sel = selected(d);
    let mut dcor: Vec<f64> = estimate(d, "cor_level", "dcor")
        .map(|e| e["value"].as_f64().unwrap())
        .into_iter()
        .collect();
    for a in d["ambiguous"].as_array().unwrap() {
        if a["selected"] == "added_mass" && a["ambiguous"] == true {
            for r in a["rivals"].as_array().unwrap() {
                if r["effect"] == "cor_level" {
                    dcor.push(r["params"][0]["value"].as_f64().unwrap());
                }
            }
        }
    }
    assert!(
        dcor.iter().any(|v| (0.004..=0.012).contains(v)),
        "livelier face not named: cor_level {dcor:?}; {sel:?}"
    );
    let findings = d["findings"].as_array().unwrap();
    assert!(
        !findings.iter().any(|f| f == "added_mass.dm_g"),
        "{findings:?}"
    );
}
