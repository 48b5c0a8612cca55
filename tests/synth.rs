//! The synthetic-experiment generator: reproducibility, file format, design, exactness against
//! `predict` without noise, noise statistics and the world-only physics.

use std::path::Path;

use smash::data::club_file::read_club;
use smash::data::shots::parse_shots;
use smash::effects::{Effect, EffectKind};
use smash::physics::LaunchComponent;
use smash::stats::std_dev;
use smash::synth::files::{synth_shots_csv, truth_toml};
use smash::synth::{generate, parse_config, read_config, SynthConfig, SynthError, SynthRun};
use smash::ClubSpec;

fn club() -> ClubSpec {
    read_club(Path::new("configs/clubs/paper_driver.toml")).unwrap()
}

fn world(name: &str) -> SynthConfig {
    read_config(Path::new(&format!("configs/synth/{name}.toml"))).unwrap()
}

fn run(cfg: &SynthConfig) -> SynthRun {
    generate(cfg, &club()).unwrap()
}

#[test]
fn same_seed_same_bytes_other_seed_other_bytes() {
    let cfg = world("paper_world");
    let a = synth_shots_csv(&run(&cfg));
    let b = synth_shots_csv(&run(&cfg));
    assert_eq!(a, b);
    let mut other = cfg.clone();
    other.seed += 1;
    assert_ne!(a, synth_shots_csv(&run(&other)));
}

#[test]
fn file_reads_back_with_the_paper_design() {
    let r = run(&world("paper_world"));
    let table = parse_shots(Path::new("mem.csv"), &synth_shots_csv(&r)[..]).unwrap();
    assert_eq!(table.shots.len(), 600);
    assert!(table.has_measurements());
    assert_eq!(table.groups(), ["A", "B", "C"]);
    let mut golfers: Vec<_> = table
        .shots
        .iter()
        .map(|s| s.golfer.clone().unwrap())
        .collect();
    golfers.sort();
    golfers.dedup();
    assert_eq!(golfers.len(), 20);
    for (g, m) in [("A", 74.5), ("B", 60.3), ("C", 70.9)] {
        let shots: Vec<_> = table.shots.iter().filter(|s| s.group == g).collect();
        assert_eq!(shots.len(), 200);
        assert!(shots.iter().all(|s| s.delivery.shaft_mass_g == Some(m)));
    }
    // Bit-for-bit: the file holds exactly what the generator made.
    for (parsed, made) in table.shots.iter().zip(&r.shots) {
        assert_eq!(parsed, &made.to_shot());
    }
}

fn assert_reproduces(cfg: &SynthConfig, model_club: &ClubSpec) {
    let r = run(cfg);
    for s in &r.shots {
        assert_eq!(s.delivery, s.clean_delivery);
        let pred = model_club
            .model_for_group(&s.group)
            .unwrap()
            .solve(&s.measured_delivery())
            .unwrap()
            .launch();
        for c in LaunchComponent::ALL {
            assert_eq!(pred.get_file(c), s.launch[c.index()], "{} {:?}", s.id, c);
        }
    }
}

#[test]
fn zero_noise_null_world_reproduces_predict_exactly() {
    assert_reproduces(&world("null_world").without_noise(), &club());
}

#[test]
fn zero_noise_hidden_effects_reproduce_predict_with_those_effects() {
    let cfg = world("paper_world").without_noise();
    let with = club().with_effects(cfg.hidden.clone()).unwrap();
    assert_reproduces(&cfg, &with);
    // And the nominal club does not: the hidden effects matter.
    let r = run(&cfg);
    let s = &r.shots[0];
    let nominal = club().model_for_group(&s.group).unwrap();
    let pred = nominal.solve(&s.measured_delivery()).unwrap().launch();
    assert!((pred.get_file(LaunchComponent::Backspin) - s.launch[3]).abs() > 100.0);
}

#[test]
fn noise_has_the_configured_standard_deviations() {
    let mut cfg = world("null_world");
    cfg.golfers = 100; // 3000 shots: SE of a SD is σ/√(2n) ≈ 1.3 %
    let r = run(&cfg);
    let n = r.shots.len() as f64;
    for c in LaunchComponent::ALL {
        let i = c.index();
        let d: Vec<f64> = r
            .shots
            .iter()
            .map(|s| s.launch[i] - s.true_launch[i])
            .collect();
        let (sd, sigma) = (std_dev(&d), cfg.launch_noise[i]);
        assert!(
            (sd - sigma).abs() < 4.0 * sigma / (2.0 * n).sqrt(),
            "{c:?}: {sd} vs {sigma}"
        );
    }
    for i in 0..cfg.delivery_noise.len() {
        let d: Vec<f64> = r
            .shots
            .iter()
            .map(|s| s.delivery[i] - s.clean_delivery[i])
            .collect();
        let (sd, sigma) = (std_dev(&d), cfg.delivery_noise[i]);
        assert!(
            (sd - sigma).abs() < 4.0 * sigma / (2.0 * n).sqrt(),
            "{i}: {sd} vs {sigma}"
        );
    }
}

#[test]
fn cor_power_law_changes_cor_with_speed_as_specified() {
    let cfg = world("cor_power_world").without_noise();
    let hidden = &cfg.hidden[0];
    assert_eq!(hidden.kind(), smash::effects::EffectKind::CorPower);
    let p = hidden.values()[0];
    let r = run(&cfg);
    for s in &r.shots {
        let expect = 0.83 * (s.normal_approach_speed_m_s / 48.77).powf(-p);
        assert!((s.cor_effective - expect).abs() < 1e-12);
    }
    // Ball speed of the world over the nominal model: higher for slow shots, lower for fast.
    let nominal = club().model_for_group("A").unwrap();
    let mut ratio: Vec<(f64, f64)> = r
        .shots
        .iter()
        .map(|s| {
            let pred = nominal.solve(&s.measured_delivery()).unwrap().launch();
            (
                s.normal_approach_speed_m_s,
                s.launch[0] / pred.get_file(LaunchComponent::BallSpeed),
            )
        })
        .collect();
    ratio.sort_by(|a, b| a.0.total_cmp(&b.0));
    let slow = &ratio[..50];
    let fast = &ratio[ratio.len() - 50..];
    let mean = |v: &[(f64, f64)]| v.iter().map(|x| x.1).sum::<f64>() / v.len() as f64;
    assert!(slow.iter().all(|x| x.0 < 48.77) && fast.iter().all(|x| x.0 > 48.77));
    assert!(
        mean(slow) > 1.0 && mean(fast) < 1.0,
        "{} {}",
        mean(slow),
        mean(fast)
    );
}

#[test]
fn face_flex_is_anisotropic_as_specified() {
    let cfg = world("face_flex_world").without_noise();
    let (cy, cz) = cfg.world.face_flex_per_mm2.unwrap();
    assert!(cy != cz);
    for s in &run(&cfg).shots {
        let (y, z) = (s.clean_delivery[9], s.clean_delivery[10]);
        assert!((s.cor_effective - (0.83 - cy * y * y - cz * z * z)).abs() < 1e-12);
    }
}

#[test]
fn loft_gain_and_offset_speed_act_on_the_world_only() {
    let mut cfg = world("null_world").without_noise();
    cfg.golfers = 2;
    cfg.world.loft_gain = Some(0.1);
    let r = run(&cfg);
    let nominal = club().model_for_group("A").unwrap();
    for s in &r.shots {
        let mut d = s.true_delivery();
        d.dynamic_loft_rad *= 1.1;
        let l = nominal.solve(&d).unwrap().launch();
        assert_eq!(l.get_file(LaunchComponent::LaunchAngle), s.launch[1]);
    }
    let mut cfg = world("null_world").without_noise();
    cfg.golfers = 4;
    cfg.world.offset_speed_mm_per_m_s = Some((0.05, 0.0));
    for s in &run(&cfg).shots {
        let dv = s.normal_approach_speed_m_s - 48.77;
        let e = Effect::new(EffectKind::BallOffset, &[0.05 * dv, 0.0], None).unwrap();
        let m = club()
            .with_effects(vec![e])
            .unwrap()
            .model_for_group("A")
            .unwrap();
        let l = m.solve(&s.true_delivery()).unwrap().launch();
        assert!((l.get_file(LaunchComponent::Backspin) - s.launch[3]).abs() < 1e-6);
    }
}

#[test]
fn unplayable_swings_are_redrawn_and_counted_or_an_error() {
    let mut cfg = world("null_world");
    cfg.golfers = 5;
    cfg.max_abs_impact_y_mm = 3.0;
    let r = run(&cfg);
    assert!(r.redrawn > 0);
    assert!(r.shots.iter().all(|s| s.clean_delivery[9].abs() <= 3.0));
    cfg.max_abs_impact_y_mm = 1e-3;
    cfg.max_redraws_per_shot = 3;
    let e = generate(&cfg, &club()).unwrap_err();
    assert!(
        matches!(e, SynthError::Unplayable { attempts: 4, .. }),
        "{e}"
    );
}

#[test]
fn truth_file_is_a_config_that_regenerates_the_same_shots() {
    let cfg = world("paper_world");
    let r = run(&cfg);
    let truth = truth_toml(&cfg, &r, "paper_world.toml");
    let back = parse_config(Path::new("truth.toml"), &truth).unwrap();
    assert_eq!(back.hidden, cfg.hidden);
    assert_eq!(synth_shots_csv(&run(&back)), synth_shots_csv(&r));
    assert!(truth.contains("[truth]") && truth.contains("shots = 600"));
}
