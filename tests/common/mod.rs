//! Deterministic synthetic experiments for the fitting tests: paper-like deliveries
//! (20 golfers × 3 shafts × 10 swings), a hidden "truth" club, launch-monitor noise.
#![allow(dead_code)]

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use nalgebra::Vector3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

use smash::data::club_file::read_club;
use smash::effects::{Effect, EffectKind};
use smash::model::Shot;
use smash::physics::{Delivery, Launch};
use smash::units::{deg, mm, mph, rpm};
use smash::ClubSpec;

/// The paper's 15 equations solved directly (a cross-check of the closed form).
pub mod fifteen;

/// Launch-monitor noise, file units: mph, deg, deg, rpm, rpm.
pub const NOISE: [f64; 5] = [0.8, 0.5, 0.5, 150.0, 150.0];

/// The paper's shafts: group and mass, g.
pub const SHAFTS: [(&str, f64); 3] = [("A", 74.5), ("B", 60.3), ("C", 70.9)];

/// The repository root. This module is compiled into the tests of both packages of the
/// workspace: the library's (`tests/`) and the command line's (`cli/tests/`, one level down).
pub fn repo_root() -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    if env!("CARGO_PKG_NAME") == "smash-cli" {
        dir.parent().expect("cli/ has a parent").to_path_buf()
    } else {
        dir.to_path_buf()
    }
}

/// The paper's driver (Table 1), nominal.
pub fn paper_club() -> ClubSpec {
    let p = repo_root().join("configs/clubs/paper_driver.toml");
    read_club(&p).expect("paper club reads")
}

/// The nominal club with hidden effects.
pub fn truth(effects: Vec<Effect>) -> ClubSpec {
    paper_club()
        .with_effects(effects)
        .expect("truth is physical")
}

/// Shorthand for an effect.
pub fn fx(name: &str, values: &[f64], group: Option<&str>) -> Effect {
    Effect::new(
        EffectKind::from_name(name).expect("library effect"),
        values,
        group.map(str::to_owned),
    )
    .expect("valid effect")
}

/// The paper world: per-shaft added mass (Table 4) and the ball offset.
pub fn paper_truth() -> ClubSpec {
    truth(vec![
        fx("added_mass", &[2.54], Some("A")),
        fx("added_mass", &[0.88], Some("B")),
        fx("added_mass", &[1.18], Some("C")),
        fx("ball_offset", &[0.48, -0.07], None),
    ])
}

/// Synthetic experiment options.
#[derive(Debug, Clone)]
pub struct Experiment {
    pub golfers: usize,
    pub swings: usize,
    pub noise: [f64; 5],
    pub seed: u64,
    pub with_golfer: bool,
}

impl Default for Experiment {
    fn default() -> Self {
        Self {
            golfers: 20,
            swings: 10,
            noise: NOISE,
            seed: 1,
            with_golfer: true,
        }
    }
}

fn clip(v: f64, lo: f64, hi: f64) -> f64 {
    v.clamp(lo, hi)
}

/// Shots of `truth` measured with noise: golfers × shafts × swings.
pub fn shots(truth: &ClubSpec, e: &Experiment) -> Vec<Shot> {
    let mut rng = ChaCha8Rng::seed_from_u64(e.seed);
    let n01 = Normal::new(0.0, 1.0).unwrap();
    let mut out = Vec::new();
    for g in 0..e.golfers {
        let speed_g: f64 = rng.random_range(97.0..113.0);
        let loft_g: f64 = rng.random_range(9.5..14.5);
        let attack_g = clip(2.0 * n01.sample(&mut rng), -3.0, 3.0);
        let path_g = clip(1.5 * n01.sample(&mut rng), -3.0, 3.0);
        let face_g = clip(path_g + 1.0 * n01.sample(&mut rng), -3.0, 3.0);
        let y_g = clip(4.0 * n01.sample(&mut rng), -6.0, 6.0);
        let z_g = clip(4.0 * n01.sample(&mut rng), -6.0, 6.0);
        for (shaft, shaft_mass) in SHAFTS {
            for s in 0..e.swings {
                let mut nz = || n01.sample(&mut rng);
                let delivery = Delivery {
                    club_speed_m_s: mph(clip(speed_g + 2.0 * nz(), 95.0, 115.0)),
                    attack_angle_rad: deg(clip(attack_g + nz(), -4.0, 4.0)),
                    club_path_rad: deg(clip(path_g + 1.2 * nz(), -4.0, 4.0)),
                    dynamic_loft_rad: deg(clip(loft_g + nz(), 8.0, 16.0)),
                    face_angle_rad: deg(clip(face_g + 1.2 * nz(), -4.0, 4.0)),
                    lie_tilt_rad: 0.0,
                    club_omega_rad_s: Vector3::zeros(),
                    impact_y_m: mm(clip(y_g + 5.0 * nz(), -15.0, 15.0)),
                    impact_z_m: mm(clip(z_g + 5.0 * nz(), -15.0, 15.0)),
                    shaft_mass_g: Some(shaft_mass),
                };
                let model = truth.model_for_group(shaft).expect("physical");
                let l = model.solve(&delivery).expect("solvable").launch();
                let f = l.to_file_units();
                let noisy: Vec<f64> = (0..5).map(|c| f[c] + e.noise[c] * nz()).collect();
                out.push(Shot {
                    id: format!("g{g:02}-{shaft}-{s}"),
                    group: shaft.to_owned(),
                    golfer: e.with_golfer.then(|| format!("golfer{g:02}")),
                    delivery,
                    measured: Some(Launch {
                        ball_speed_m_s: mph(noisy[0]),
                        launch_angle_rad: deg(noisy[1]),
                        azimuth_rad: deg(noisy[2]),
                        backspin_rad_s: rpm(noisy[3]),
                        sidespin_rad_s: rpm(noisy[4]),
                    }),
                });
            }
        }
    }
    out
}

/// Shots CSV text. `measured`: include the launch columns; `golfer`: the golfer column.
pub fn shots_csv(shots: &[Shot], measured: bool, golfer: bool) -> String {
    let mut s = String::from(
        "shot_id,group,shaft_mass_g,club_speed_mph,attack_angle_deg,club_path_deg,\
         dynamic_loft_deg,face_angle_deg,impact_y_mm,impact_z_mm",
    );
    if golfer {
        s.push_str(",golfer");
    }
    if measured {
        s.push_str(",ball_speed_mph,launch_angle_deg,azimuth_deg,backspin_rpm,sidespin_rpm");
    }
    s.push('\n');
    for sh in shots {
        let d = &sh.delivery;
        let _ = write!(
            s,
            "{},{},{},{},{},{},{},{},{},{}",
            sh.id,
            sh.group,
            d.shaft_mass_g.unwrap_or(70.0),
            d.club_speed_m_s / 0.44704,
            d.attack_angle_rad.to_degrees(),
            d.club_path_rad.to_degrees(),
            d.dynamic_loft_rad.to_degrees(),
            d.face_angle_rad.to_degrees(),
            d.impact_y_m * 1e3,
            d.impact_z_m * 1e3
        );
        if golfer {
            let _ = write!(s, ",{}", sh.golfer.as_deref().unwrap_or(""));
        }
        if measured {
            for v in sh.measured.expect("measured").to_file_units() {
                let _ = write!(s, ",{v}");
            }
        }
        s.push('\n');
    }
    s
}

/// Path of the paper club file.
pub fn paper_club_path() -> PathBuf {
    repo_root().join("configs/clubs/paper_driver.toml")
}

/// Sixteen deliveries (four speeds × four face locations, angles and head rotation varied
/// with the index) for the scalar-solve, kernel and golden checks of the effect tests.
pub fn deliveries() -> Vec<Delivery> {
    let mut out = Vec::new();
    for (i, speed_mph) in [80.0, 95.0, 105.0, 118.0].into_iter().enumerate() {
        for (j, (y_mm, z_mm)) in [(0.0, 0.0), (8.0, -12.0), (-6.0, 15.0), (12.0, 20.0)]
            .into_iter()
            .enumerate()
        {
            let f = (i * 4 + j) as f64;
            out.push(Delivery {
                club_speed_m_s: speed_mph * 0.44704,
                attack_angle_rad: (-2.0 + 0.3 * f).to_radians(),
                club_path_rad: (1.5 - 0.2 * f).to_radians(),
                dynamic_loft_rad: (10.0 + 0.4 * f).to_radians(),
                face_angle_rad: (0.8 - 0.1 * f).to_radians(),
                lie_tilt_rad: 0.5f64.to_radians(),
                club_omega_rad_s: Vector3::new(-2.0, 4.0 - 0.5 * f, -8.0),
                impact_y_m: y_mm * 1e-3,
                impact_z_m: z_mm * 1e-3,
                shaft_mass_g: None,
            });
        }
    }
    out
}

/// Does `text` show a non-finite number (`inf`, `NaN`, …) as a word?
pub fn has_non_finite(text: &str) -> bool {
    text.split(|c: char| !c.is_ascii_alphanumeric())
        .any(|w| matches!(w, "inf" | "NaN" | "nan" | "infinity" | "Infinity"))
}

/// The command failed cleanly: exit 1 (not a panic's 101 or a signal), exactly one line on
/// stderr, starting `error: ` and containing every `needle`, and nothing infinite or undefined
/// on stdout or stderr.
pub fn assert_refused(o: &std::process::Output, needles: &[&str]) {
    let err = String::from_utf8_lossy(&o.stderr);
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(
        o.status.code(),
        Some(1),
        "exit {:?}; stderr: {err}",
        o.status
    );
    assert!(!err.contains("panicked"), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "not one line: {err:?}");
    assert!(err.starts_with("error: "), "{err}");
    for n in needles {
        assert!(err.contains(n), "missing {n:?} in: {err}");
    }
    assert!(!has_non_finite(&err) && !has_non_finite(&out), "{out}{err}");
}

/// A value of each parameter inside its plausible range, away from its neutral default: 70 % of
/// the way up the range (30 % where that is the default).
pub fn active_values(params: &[smash::effects::ParamSpec]) -> Vec<f64> {
    params
        .iter()
        .map(|s| {
            let (lo, hi) = s.plausible;
            let v = lo + 0.7 * (hi - lo);
            if v == s.default {
                lo + 0.3 * (hi - lo)
            } else {
                v
            }
        })
        .collect()
}
