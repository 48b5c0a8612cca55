//! `smash infer-club` validated on synthetic worlds whose heads vary beyond the shipped five
//! (issue 40): CoM depth ±6 mm, height ±3 mm, vertical-axis MOI ±25 %, radii 230–430 mm, COR
//! 0.78–0.83 with a radial falloff, and loft/face biases of the monitor.
//!
//! Decided before any result was seen, and not changed after:
//!
//! - the four heads of [`HEADS`] (changes from the paper driver, the start club of every fit;
//!   the moments changed by moving mass as `inertia_axes` does, so that `I_xx` follows);
//! - seeds: world `h` (1–4), seed `s` (1–10) is `synth` seed `40_000 + 100·h + s`; its held-out
//!   session of the same head is seed `40_000 + 100·h + 50 + s`;
//! - 600 shots a session: `smash synth`'s default design (3 shafts × 20 golfers × 10 swings)
//!   with its default camera-class noise on delivery, impact location and launch;
//! - the fit: `Settings::default()` without profile intervals (a lean fit: the profiles are the
//!   same fit repeated, tested on one world in the unit tests of the CLI).
//!
//! What is asserted, and why not the issue's literal "≥ 9 of 10 seeds for every determined
//! parameter": an honest 2-SE interval covers the truth with probability 0.954, so a parameter
//! is within 2 SE in ≥ 9 of 10 seeds with probability 0.925 only; over the ~40 (head,
//! parameter) pairs a *correct* estimator meets the literal rule everywhere with probability
//! about 0.925⁴⁰ ≈ 4 %. The literal counts are printed; asserted are (a) pooled coverage of all
//! determined (head, parameter, seed) estimates ≥ 90 % (0.954 expected; 90 % is about five
//! binomial SDs below it at this count) and (b) no pair misses in more than 3 of its determined
//! seeds (a correct estimator does so with probability ≈ 0.15 % a pair). The same reasoning
//! pools the held-out spread ratio (its SE at 600 shots, 0.029, makes 1.05 a 1.7-SD event for
//! a right model per component and seed) and the plan's agreement (the SD of 10 estimates is
//! itself uncertain by 24 %) over the seeds of a head.

use std::time::Instant;

use rayon::prelude::*;

use smash::club::ClubSpec;
use smash::diagnose::noise_floor::{noise_floor_of, InstrumentClass};
use smash::effects::{Effect, EffectKind};
use smash::fit::{FitProblem, Weighting};
use smash::infer::head::{head_layout, HEAD_PARAMS};
use smash::infer::{fit_data, run, run_plan, Settings};
use smash::measurement::ImpactNoise;
use smash::model::Shot;
use smash::physics::delivery_vars::DeliveryVar;
use smash::synth::{generate, SynthConfig};
use smash::ModelParams;

/// One varied head: changes from the paper driver (Table 1: CoM [−42.3, 2.9, 1.0] mm, I_yy
/// 5679 and I_zz 4085 g cm², radii 305 mm, COR 0.83).
struct Head {
    d_com_mm: [f64; 3],
    s_iyy: f64,
    s_izz: f64,
    bulge_mm: f64,
    roll_mm: f64,
    cor: f64,
    falloff_per_mm2: f64,
    loft_bias_deg: f64,
    face_bias_deg: f64,
}

const HEADS: [Head; 4] = [
    // Deep, high CoM, stiff about the vertical axis, flat face, dead COR.
    Head {
        d_com_mm: [-6.0, 3.0, 0.0],
        s_iyy: 1.25,
        s_izz: 1.10,
        bulge_mm: 430.0,
        roll_mm: 380.0,
        cor: 0.80,
        falloff_per_mm2: 1.0e-4,
        loft_bias_deg: 0.0,
        face_bias_deg: 0.0,
    },
    // Forward, low CoM toward the toe, soft about both axes, tight face, monitor biased.
    Head {
        d_com_mm: [6.0, -3.0, 2.0],
        s_iyy: 0.75,
        s_izz: 0.85,
        bulge_mm: 230.0,
        roll_mm: 250.0,
        cor: 0.83,
        falloff_per_mm2: 0.5e-4,
        loft_bias_deg: 1.0,
        face_bias_deg: -0.5,
    },
    // Heel-ward CoM, tight roll, the deadest COR with the steepest falloff.
    Head {
        d_com_mm: [3.0, 1.5, -2.0],
        s_iyy: 1.10,
        s_izz: 0.80,
        bulge_mm: 330.0,
        roll_mm: 230.0,
        cor: 0.78,
        falloff_per_mm2: 2.0e-4,
        loft_bias_deg: -1.5,
        face_bias_deg: 1.0,
    },
    // Deep, low CoM, soft about the vertical axis and stiff about the heel-toe axis.
    Head {
        d_com_mm: [-4.0, -2.0, 1.0],
        s_iyy: 0.85,
        s_izz: 1.20,
        bulge_mm: 280.0,
        roll_mm: 430.0,
        cor: 0.815,
        falloff_per_mm2: 1.5e-4,
        loft_bias_deg: 0.5,
        face_bias_deg: 0.0,
    },
];

const SEEDS: u64 = 10;

fn start_club() -> ClubSpec {
    smash::data::club_file::read_club(std::path::Path::new("configs/clubs/paper_driver.toml"))
        .unwrap()
}

/// The true head's club (nominal fields) and its hidden effects.
fn true_world(h: &Head) -> (ClubSpec, Vec<Effect>) {
    let mut p = ModelParams::paper_driver();
    for k in 0..3 {
        p.club_com_m[k] += h.d_com_mm[k] * 1e-3;
    }
    // The moments as the effect library moves them (mass moved, `I_xx` following), so that
    // the head is one a mass distribution can have.
    EffectKind::InertiaAxes.apply(&[h.s_iyy, h.s_izz], &mut p);
    p.bulge_m = h.bulge_mm * 1e-3;
    p.roll_m = h.roll_mm * 1e-3;
    p.cor = h.cor;
    let club = ClubSpec::new("true head".into(), None, p, vec![]).unwrap();
    let hidden = vec![
        Effect::new(EffectKind::CorRadial, &[h.falloff_per_mm2], None).unwrap(),
        Effect::new(EffectKind::LoftBias, &[h.loft_bias_deg], None).unwrap(),
        Effect::new(EffectKind::FaceBias, &[h.face_bias_deg], None).unwrap(),
    ];
    (club, hidden)
}

/// The truth in the report's units, in [`HEAD_PARAMS`] order.
fn truth(h: &Head) -> [f64; 11] {
    let p = ModelParams::paper_driver();
    [
        p.club_com_m.x * 1e3 + h.d_com_mm[0],
        p.club_com_m.y * 1e3 + h.d_com_mm[1],
        p.club_com_m.z * 1e3 + h.d_com_mm[2],
        p.club_inertia_kgm2[(1, 1)] * 1e7 * h.s_iyy,
        p.club_inertia_kgm2[(2, 2)] * 1e7 * h.s_izz,
        h.bulge_mm,
        h.roll_mm,
        h.cor,
        h.falloff_per_mm2,
        h.loft_bias_deg,
        h.face_bias_deg,
    ]
}

fn session(h: &Head, seed: u64) -> Vec<Shot> {
    session_with_noise(h, seed, NoiseOn::All)
}

/// Which of `smash synth`'s delivery noise a world carries (the launch noise always).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum NoiseOn {
    /// The default: every delivery variable, impact location included.
    All,
    /// The impact location's only.
    Location,
    /// The other delivery variables' only.
    Delivery,
    /// None.
    None,
}

impl NoiseOn {
    /// Keep variable `v`'s noise?
    fn keeps(self, v: DeliveryVar) -> bool {
        let location = matches!(v, DeliveryVar::ImpactY | DeliveryVar::ImpactZ);
        match self {
            Self::All => true,
            Self::Location => location,
            Self::Delivery => !location,
            Self::None => false,
        }
    }
}

fn session_with_noise(h: &Head, seed: u64, noise: NoiseOn) -> Vec<Shot> {
    let (club, hidden) = true_world(h);
    let mut cfg = SynthConfig {
        seed,
        hidden,
        ..SynthConfig::default()
    };
    for v in DeliveryVar::ALL {
        if !noise.keeps(v) {
            cfg.delivery_noise[v.index()] = 0.0;
        }
    }
    generate(&cfg, &club)
        .unwrap()
        .shots
        .iter()
        .map(|s| s.to_shot())
        .collect()
}

/// `S_c = ratio²·(n − 1)` per component of the noise floor of `club` on held-out `shots`, with
/// the fit's measurement model.
fn floor_sums(settings: &Settings, club: &ClubSpec, shots: &[Shot]) -> [f64; 5] {
    let data = fit_data(settings, shots).unwrap();
    let layout = head_layout();
    let errors = FitProblem::new(club, layout.clone(), &data, Weighting::launch(&[1.0; 5]))
        .launch_errors(layout.defaults().as_slice())
        .unwrap();
    let inst = InstrumentClass::Camera.noise();
    let loc = ImpactNoise::from_mm(1.5, 1.5).unwrap();
    let floor = noise_floor_of(club, shots, &errors, &inst, Some(loc)).unwrap();
    let nu = (shots.len() - 1) as f64;
    std::array::from_fn(|c| floor.components[c].ratio.powi(2) * nu)
}

/// One world's results.
struct World {
    value: [f64; 11],
    stderr: [f64; 11],
    determined: [bool; 11],
    /// The plan's predicted SE at the start head for this session's design (before any shot).
    planned_se: [f64; 11],
    /// The plan's predicted SE at the fitted head for this session's design: the plan a user
    /// makes for the next session with the head this one inferred (`--start head.toml --plan`).
    planned_fit_se: [f64; 11],
    /// Data-only SE at the true head (the plan's machinery at the truth).
    truth_data_se: [Option<f64>; 11],
    /// The plan's SE at the true head (information only: the plan a user makes is the start's).
    truth_se: [f64; 11],
    inferred_floor: [f64; 5],
    start_floor: [f64; 5],
}

fn world(hi: usize, s: u64) -> World {
    let h = &HEADS[hi];
    let settings = Settings {
        profile_grid_se: vec![],
        ..Settings::default()
    };
    let start = start_club();
    let base = 40_000 + 100 * (hi as u64 + 1);
    let shots = session(h, base + s);
    let r = run(&settings, &start, &shots).unwrap();
    let plan = run_plan(&settings, &start, &shots, None, None, &[]).unwrap();
    let plan_fit = run_plan(&settings, &r.club, &shots, None, None, &[]).unwrap();
    let (true_club, hidden) = true_world(h);
    let true_full = true_club.with_effects(hidden).unwrap();
    let at_truth = run_plan(&settings, &true_full, &shots, None, None, &[]).unwrap();
    let held_out = session(h, base + 50 + s);
    World {
        value: std::array::from_fn(|j| r.params[j].value),
        stderr: std::array::from_fn(|j| r.params[j].stderr),
        determined: std::array::from_fn(|j| r.params[j].determined),
        planned_se: std::array::from_fn(|j| plan.params[j].stderr),
        planned_fit_se: std::array::from_fn(|j| plan_fit.params[j].stderr),
        truth_data_se: std::array::from_fn(|j| at_truth.params[j].data_stderr),
        truth_se: std::array::from_fn(|j| at_truth.params[j].stderr),
        inferred_floor: floor_sums(&settings, &r.club, &held_out),
        start_floor: floor_sums(&settings, &start, &held_out),
    }
}

#[test]
fn infer_club_recovers_varied_heads_with_honest_uncertainty() {
    let t0 = Instant::now();
    let jobs: Vec<(usize, u64)> = (0..HEADS.len())
        .flat_map(|h| (1..=SEEDS).map(move |s| (h, s)))
        .collect();
    let worlds: Vec<World> = jobs.par_iter().map(|&(h, s)| world(h, s)).collect();
    let f = Settings::default().determined_fraction;
    let start = start_club();
    let start_vals = smash::infer::head::start_values(&start);
    let mut pooled = (0usize, 0usize);
    // Per parameter, the heads' (observed SD / plan at the fitted head)² (determined in every
    // seed only), and the pairs within 30 % one by one.
    let mut plan_by_param: Vec<Vec<f64>> = vec![Vec::new(); HEAD_PARAMS.len()];
    let mut plan_one_by_one = (0usize, 0usize);
    let mut literal_failures = Vec::new();
    let mut failures = Vec::new();
    for (hi, h) in HEADS.iter().enumerate() {
        let ws = &worlds[hi * SEEDS as usize..(hi + 1) * SEEDS as usize];
        let t = truth(h);
        println!("head {}:", hi + 1);
        let mut plan_ratios = Vec::new();
        for (j, hp) in HEAD_PARAMS.iter().enumerate() {
            let det: Vec<&World> = ws.iter().filter(|w| w.determined[j]).collect();
            let within = det
                .iter()
                .filter(|w| (w.value[j] - t[j]).abs() <= 2.0 * w.stderr[j])
                .count();
            pooled.0 += within;
            pooled.1 += det.len();
            let vals: Vec<f64> = ws.iter().map(|w| w.value[j]).collect();
            let mean = vals.iter().sum::<f64>() / vals.len() as f64;
            let sd_obs = (vals.iter().map(|v| (v - mean).powi(2)).sum::<f64>()
                / (vals.len() - 1) as f64)
                .sqrt();
            let planned = ws.iter().map(|w| w.planned_se[j]).sum::<f64>() / ws.len() as f64;
            let planned_fit = ws.iter().map(|w| w.planned_fit_se[j]).sum::<f64>() / ws.len() as f64;
            let at_truth = ws.iter().map(|w| w.truth_se[j]).sum::<f64>() / ws.len() as f64;
            let reported_se = ws.iter().map(|w| w.stderr[j]).sum::<f64>() / ws.len() as f64;
            let mean_z = ws
                .iter()
                .map(|w| (w.value[j] - t[j]) / w.stderr[j])
                .sum::<f64>()
                / ws.len() as f64;
            let prior = hp.prior_sd * smash::infer::head::reported(j, start_vals[j], 1.0).1;
            println!(
                "  {:<22} truth {:>10.4e}  determined {:>2}/10  within 2 SE {:>2}/{:<2}  \
                 observed SD {:.3e}  planned SE at the fitted head {:.3e}  ratio {:.2}  \
                 (at the start head {:.3e}, ratio {:.2}; reported SE {:.3e}, plan at the true \
                 head {:.3e}, mean z {:+.2})",
                hp.key,
                t[j],
                det.len(),
                within,
                det.len(),
                sd_obs,
                planned_fit,
                sd_obs / planned_fit,
                planned,
                sd_obs / planned,
                reported_se,
                at_truth,
                mean_z
            );
            if within + 1 < det.len() {
                let z: Vec<String> = ws
                    .iter()
                    .map(|w| format!("{:+.1}", (w.value[j] - t[j]) / w.stderr[j]))
                    .collect();
                println!("    z by seed: {}", z.join(" "));
            }
            if !det.is_empty() && within + 1 < det.len() {
                literal_failures.push(format!(
                    "head {} {}: {within}/{}",
                    hi + 1,
                    hp.key,
                    det.len()
                ));
            }
            if det.len() - within > 3 {
                failures.push(format!(
                    "head {} {}: within 2 SE in only {within} of {} determined seeds",
                    hi + 1,
                    hp.key,
                    det.len()
                ));
            }
            if !det.is_empty() && sd_obs > 1.5 * f * prior {
                failures.push(format!(
                    "head {} {}: reported determined but its estimates scatter by {sd_obs:.3e} \
                     over the seeds, more than 1.5 × {f:.3} of the prior width {prior:.3e}",
                    hi + 1,
                    hp.key
                ));
            }
            for (s, w) in ws.iter().enumerate() {
                let undeterminable = w.truth_data_se[j].is_none_or(|se| se > 1.5 * f * prior);
                if w.determined[j] && undeterminable {
                    failures.push(format!(
                        "head {} seed {} {}: reported determined, but at the true head the data \
                         SE is {:?} (prior {prior:.3e})",
                        hi + 1,
                        s + 1,
                        hp.key,
                        w.truth_data_se[j]
                    ));
                }
            }
            if det.len() == ws.len() {
                let ratio = sd_obs / planned_fit;
                plan_ratios.push(ratio);
                plan_by_param[j].push(ratio);
                plan_one_by_one.0 += usize::from((ratio - 1.0).abs() <= 0.3);
                plan_one_by_one.1 += 1;
            }
        }
        // Plan against the seeds' spread, pooled over the parameters determined in every seed.
        let pooled_ratio = (plan_ratios.iter().map(|r| r * r).sum::<f64>()
            / plan_ratios.len().max(1) as f64)
            .sqrt();
        let within30 = plan_ratios
            .iter()
            .filter(|r| (**r - 1.0).abs() <= 0.3)
            .count();
        println!(
            "  plan at the fitted head: observed/planned pooled {pooled_ratio:.3} over {} \
             parameters; {within30} within 30 % one by one",
            plan_ratios.len()
        );
        if plan_ratios.is_empty() || (pooled_ratio - 1.0).abs() > 0.3 {
            failures.push(format!(
                "head {}: plan pooled ratio {pooled_ratio:.3}",
                hi + 1
            ));
        }
        // Held-out spread against the noise floor, pooled over the seeds.
        let nu = ws.len() as f64 * 599.0;
        let ratio = |pick: fn(&World) -> [f64; 5]| -> [f64; 5] {
            std::array::from_fn(|c| (ws.iter().map(|w| pick(w)[c]).sum::<f64>() / nu).sqrt())
        };
        let inferred = ratio(|w| w.inferred_floor);
        let started = ratio(|w| w.start_floor);
        println!("  held-out spread / floor: inferred {inferred:.3?}, start {started:.3?}");
        if inferred.iter().any(|&r| r > 1.05) {
            failures.push(format!(
                "head {}: inferred head's held-out ratios {inferred:.3?}",
                hi + 1
            ));
        }
        if started.iter().all(|&r| r <= 1.05) {
            failures.push(format!(
                "head {}: the start head is at the floor too {started:.3?}",
                hi + 1
            ));
        }
    }
    // The plan against the seeds' spread, each parameter pooled over the heads (4 × 9 degrees
    // of freedom: the ratio is then known to about 12 %, where one head's 10 seeds know it to
    // 24 % only and a right plan misses 30 % in about one (head, parameter) pair of five).
    for (j, hp) in HEAD_PARAMS.iter().enumerate() {
        let r = &plan_by_param[j];
        let rms = (r.iter().map(|x| x * x).sum::<f64>() / r.len().max(1) as f64).sqrt();
        println!(
            "plan {:<22} observed/planned at the fitted head, pooled over {} heads: {rms:.3}",
            hp.key,
            r.len()
        );
        if r.is_empty() || (rms - 1.0).abs() > 0.3 {
            failures.push(format!(
                "{}: plan at the fitted head against the seeds' spread {rms:.3} over {} heads",
                hp.key,
                r.len()
            ));
        }
    }
    println!(
        "plan one by one: {}/{} (head, parameter) pairs within 30 %",
        plan_one_by_one.0, plan_one_by_one.1
    );
    let coverage = pooled.0 as f64 / pooled.1.max(1) as f64;
    println!(
        "pooled coverage of determined estimates: {}/{} = {coverage:.3}; literal rule (>= 9 of \
         10) failed for: {literal_failures:?}; wall time {:.1} s",
        pooled.0,
        pooled.1,
        t0.elapsed().as_secs_f64()
    );
    if coverage < 0.90 {
        failures.push(format!("pooled coverage {coverage:.3} < 0.90"));
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Held-out diagnosis of the coverage (not part of the validation above, whose heads and seeds
/// were fixed first): the same four heads, 40 further seeds each (`synth` seed
/// `90_000 + 100·h + s`, s = 1–40), with the synthetic world's delivery noise as shipped or
/// switched off in part (`SMASH_HELDOUT_NOISE` = `all` (default), `location`, `delivery` or
/// `none`; the fit's correction follows). Prints, per head and parameter, the z-scores'
/// mean and SD and the estimates within 2 SE, the radii's z also on the curvature scale `1/R`.
/// `cargo test -p smash --test library infer_club:: -- --ignored --nocapture`; the figures are in
/// docs/infer-club.md ("Validation").
#[test]
#[ignore = "diagnosis on held-out seeds: 160 fits a run, figures in docs/infer-club.md"]
fn held_out_seeds_locate_the_coverage_shortfall() {
    let noise = match std::env::var("SMASH_HELDOUT_NOISE").as_deref() {
        Ok("location") => NoiseOn::Location,
        Ok("delivery") => NoiseOn::Delivery,
        Ok("none") => NoiseOn::None,
        _ => NoiseOn::All,
    };
    let mut settings = Settings {
        profile_grid_se: vec![],
        ..Settings::default()
    };
    for v in DeliveryVar::ALL {
        if !noise.keeps(v) {
            settings.delivery_noise_sd[v.index()] = 0.0;
        }
    }
    let start = start_club();
    let jobs: Vec<(usize, u64)> = (0..HEADS.len())
        .flat_map(|h| (1..=40).map(move |s| (h, s)))
        .collect();
    let fits: Vec<(usize, [f64; 11], [f64; 11])> = jobs
        .par_iter()
        .map(|&(hi, s)| {
            let shots = session_with_noise(&HEADS[hi], 90_000 + 100 * (hi as u64 + 1) + s, noise);
            let r = run(&settings, &start, &shots).unwrap();
            let value = std::array::from_fn(|j| r.params[j].value);
            (hi, value, std::array::from_fn(|j| r.params[j].stderr))
        })
        .collect();
    let summary = |z: &[f64]| {
        let n = z.len() as f64;
        let mean = z.iter().sum::<f64>() / n;
        let sd = (z.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        let within = z.iter().filter(|v| v.abs() <= 2.0).count();
        (mean, sd, within)
    };
    let mut pooled = (0, 0);
    println!("delivery noise: {noise:?}");
    for (hi, h) in HEADS.iter().enumerate() {
        let t = truth(h);
        let ws: Vec<_> = fits.iter().filter(|f| f.0 == hi).collect();
        println!("head {}:", hi + 1);
        for (j, hp) in HEAD_PARAMS.iter().enumerate() {
            let z: Vec<f64> = ws.iter().map(|w| (w.1[j] - t[j]) / w.2[j]).collect();
            let (mean, sd, within) = summary(&z);
            pooled.0 += within;
            pooled.1 += z.len();
            let mut line = format!(
                "  {:<22} z mean {mean:+.2}  SD {sd:.2}  within 2 SE {within}/{}",
                hp.key,
                z.len()
            );
            if hp.unit == "mm" && hp.key.ends_with("_mm") {
                // Curvature 1/R, its SE by the delta method, SE_R / R².
                let zk: Vec<f64> = ws
                    .iter()
                    .map(|w| (1.0 / w.1[j] - 1.0 / t[j]) / (w.2[j] / w.1[j].powi(2)))
                    .collect();
                let (km, ksd, kw) = summary(&zk);
                line += &format!("  (on 1/R: z mean {km:+.2}  SD {ksd:.2}  within {kw})");
            }
            println!("{line}");
        }
    }
    println!(
        "pooled: {}/{} = {:.3} within 2 SE",
        pooled.0,
        pooled.1,
        pooled.0 as f64 / pooled.1 as f64
    );
}
