//! The compliant-contact world of `smash synth` (`[world] contact`): integrator convergence, the
//! rigid limit against the momentum model, Hunt–Crossley COR falling with speed, and the
//! tangential-compliance regimes (spin overshoot with a gripping spring, gross slip with low μ).

use nalgebra::Vector3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use smash::physics::{Delivery, ImpactModel, ModelParams};
use smash::synth::contact::{hunt_crossley_cor, ContactParams, ContactWorld, ShaftTip};

fn delivery(speed: f64, loft_deg: f64, y_mm: f64, z_mm: f64) -> Delivery {
    Delivery {
        club_speed_m_s: speed,
        attack_angle_rad: 0.0,
        club_path_rad: 0.0,
        dynamic_loft_rad: loft_deg.to_radians(),
        face_angle_rad: 0.0,
        lie_tilt_rad: 0.0,
        club_omega_rad_s: Vector3::zeros(),
        impact_y_m: y_mm * 1e-3,
        impact_z_m: z_mm * 1e-3,
    }
}

/// Random deliveries over the synth defaults' range (centre and off-centre).
fn random_deliveries(seed: u64, n: usize, centre: bool) -> Vec<Delivery> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| {
            let mut u = |a: f64, b: f64| rng.random_range(a..b);
            Delivery {
                club_speed_m_s: u(38.0, 54.0),
                attack_angle_rad: u(-5.0, 5.0_f64).to_radians(),
                club_path_rad: u(-4.0, 4.0_f64).to_radians(),
                dynamic_loft_rad: u(8.0, 16.0_f64).to_radians(),
                face_angle_rad: u(-4.0, 4.0_f64).to_radians(),
                lie_tilt_rad: u(-3.0, 3.0_f64).to_radians(),
                club_omega_rad_s: Vector3::new(u(-3.0, 3.0), u(-4.0, 4.0), u(-3.0, 3.0)),
                impact_y_m: if centre { 0.0 } else { u(-15.0, 15.0) * 1e-3 },
                impact_z_m: if centre { 0.0 } else { u(-25.0, 25.0) * 1e-3 },
            }
        })
        .collect()
}

fn paper() -> ImpactModel {
    ImpactModel::new(ModelParams::paper_driver()).unwrap()
}

/// Stiff, gripping, no shaft: the limit in which the momentum model's assumptions hold.
fn rigid_limit() -> ContactParams {
    ContactParams {
        hertz_k_n_per_m1_5: 1e15,
        cor_ref: None,
        mu: 100.0,
        tangential_stiffness_ratio: 50.0,
        tangential_damping_ratio: 1.0,
        steps_per_contact: 2000,
        shaft_tip: None,
    }
}

fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

/// Worst relative differences over deliveries (ball speed, spin vector, achieved COR, normal
/// impulse) between the rigid-limit contact and the momentum model given `cor_for(outcome)`.
fn rigid_worst(
    deliveries: &[Delivery],
    cor_for: impl Fn(&ContactWorld, &smash::synth::ContactOutcome) -> f64,
) -> [f64; 4] {
    let m = paper();
    let cw = ContactWorld::new(&m, rigid_limit()).unwrap();
    let mut worst = [0.0f64; 4];
    for d in deliveries {
        let o = cw.impact(d).unwrap();
        let mut p = ModelParams::paper_driver();
        p.cor = cor_for(&cw, &o);
        let r = ImpactModel::new(p.clone()).unwrap().solve(d).unwrap();
        let pn = r.impulse_n_s.dot(&r.normal);
        let w = [
            rel(o.ball_velocity_m_s.norm(), r.ball_velocity_m_s.norm()),
            (o.ball_spin_rad_s - r.ball_spin_rad_s).norm() / r.ball_spin_rad_s.norm(),
            rel(o.cor_measured, p.cor),
            rel(o.normal_impulse_n_s, pn),
        ];
        for k in 0..4 {
            worst[k] = worst[k].max(w[k]);
        }
    }
    worst
}

/// Rigid limit, centre strikes: the momentum model with the Hunt–Crossley COR at each shot's
/// `u1n` and `e_t = 0` reproduces the integrated impact.
#[test]
fn rigid_limit_matches_momentum_model_at_the_centre() {
    let w = rigid_worst(&random_deliveries(7, 40, true), |cw, o| {
        cw.cor_at(o.normal_approach_speed_m_s)
    });
    println!(
        "centre: speed {:.2e} spin {:.2e} cor {:.2e} Pn {:.2e}",
        w[0], w[1], w[2], w[3]
    );
    assert!(
        w[0] < 1e-3 && w[1] < 1e-3 && w[2] < 2e-3 && w[3] < 1e-3,
        "{w:?}"
    );
}

/// Rigid limit, off-centre: the restitution differs slightly from the one-body Hunt–Crossley COR
/// because the gripping tangential force couples into the normal motion (the module docs explain
/// why), so the ball speed differs by up to ~0.2 %. Given the COR the contact actually achieved,
/// the momentum model's kinematics (impulse direction, spin, speed) agree much more closely.
#[test]
fn rigid_limit_off_centre_difference_is_in_the_restitution_only() {
    let ds = random_deliveries(11, 40, false);
    let w = rigid_worst(&ds, |cw, o| cw.cor_at(o.normal_approach_speed_m_s));
    println!(
        "off-centre, 1-D COR: speed {:.2e} spin {:.2e} cor {:.2e} Pn {:.2e}",
        w[0], w[1], w[2], w[3]
    );
    assert!(w[0] < 3e-3 && w[1] < 2e-3, "{w:?}");
    let w2 = rigid_worst(&ds, |_, o| o.cor_measured);
    println!(
        "off-centre, achieved COR: speed {:.2e} spin {:.2e} cor {:.2e} Pn {:.2e}",
        w2[0], w2[1], w2[2], w2[3]
    );
    // Speed and normal impulse then agree to 1e-4; the spin keeps a ~0.2 % difference from the
    // not-quite-perfect grip of a finite tangential spring (e_t slightly off 0).
    assert!(w2[0] < 1e-4 && w2[3] < 1e-4 && w2[1] < 3e-3, "{w2:?}");
}

/// RK4 at the default step against a step 4× finer, with everything switched on.
#[test]
fn integrator_converges_against_a_finer_step() {
    let m = paper();
    let coarse = ContactParams {
        shaft_tip: Some(ShaftTip::default()),
        ..ContactParams::default()
    };
    let fine = ContactParams {
        steps_per_contact: 4 * coarse.steps_per_contact,
        ..coarse
    };
    let (a, b) = (
        ContactWorld::new(&m, coarse).unwrap(),
        ContactWorld::new(&m, fine).unwrap(),
    );
    let mut worst = [0.0f64; 5];
    for d in random_deliveries(3, 40, false) {
        let la = a.impact(&d).unwrap().launch().to_file_units();
        let lb = b.impact(&d).unwrap().launch().to_file_units();
        for k in 0..5 {
            worst[k] = worst[k].max((la[k] - lb[k]).abs());
        }
    }
    println!("coarse − fine, worst (mph, deg, deg, rpm, rpm): {worst:?}");
    // Negligible against a launch monitor's noise (0.5 mph, 0.3°, 0.5°, 120 rpm, 150 rpm): 2 %
    // of it. (The Coulomb clip makes the error first order where the contact starts to slide.)
    let limit = [0.01, 0.006, 0.01, 2.4, 3.0];
    for k in 0..5 {
        assert!(worst[k] < limit[k], "component {k}: {worst:?}");
    }
}

/// The COR falls with speed as Hunt & Crossley's law says, whatever the masses.
#[test]
fn cor_falls_with_speed_as_hunt_crossley_predicts() {
    // Small damping: 1 − e → (2/3)·χ·v.
    let c = 1e-3;
    let slope = (1.0 - hunt_crossley_cor(c)) / c;
    assert!((slope - 2.0 / 3.0).abs() < 0.01 * 2.0 / 3.0, "{slope}");
    // χ calibrated at 48.77 m/s hits the target there.
    let chi = smash::synth::contact::hunt_crossley_chi(0.8, 48.77).unwrap();
    assert!((hunt_crossley_cor(chi * 48.77) - 0.8).abs() < 1e-9);
    // Centre strikes with the default world: the achieved COR follows the one-body law.
    let m = paper();
    let cw = ContactWorld::new(&m, ContactParams::default()).unwrap();
    let mut last = f64::INFINITY;
    for speed in [30.0, 38.0, 46.0, 54.0, 62.0] {
        let o = cw.impact(&delivery(speed, 10.0, 0.0, 0.0)).unwrap();
        let e1 = cw.cor_at(o.normal_approach_speed_m_s);
        println!(
            "{speed} m/s: e {:.4} (one-body law {e1:.4}), contact {:.3} ms",
            o.cor_measured,
            o.contact_time_s * 1e3
        );
        assert!(rel(o.cor_measured, e1) < 2e-3, "{} vs {e1}", o.cor_measured);
        assert!(o.cor_measured < last);
        last = o.cor_measured;
    }
}

/// Tangential compliance: with grip (large μ, no tangential damping) the contact point's
/// tangential velocity reverses before release (spin beyond rolling, e_t > 0); with a low μ
/// the ball slides throughout and it does not (e_t < 0).
#[test]
fn tangential_regimes_overshoot_and_gross_slip() {
    let m = paper();
    let e_t = |p: ContactParams| {
        let o = ContactWorld::new(&m, p)
            .unwrap()
            .impact(&delivery(45.0, 14.0, 0.0, 0.0))
            .unwrap();
        let u = o.tangential_before_m_s;
        -o.tangential_after_m_s.dot(&u) / u.norm_squared()
    };
    let grip = ContactParams {
        mu: 10.0,
        tangential_damping_ratio: 0.0,
        ..ContactParams::default()
    };
    let et_grip = e_t(grip);
    let et_slide = e_t(ContactParams {
        mu: 0.05,
        ..ContactParams::default()
    });
    let et_default = e_t(ContactParams::default());
    let et_soft = e_t(ContactParams {
        tangential_stiffness_ratio: 0.05,
        ..grip
    });
    println!("e_t: grip {et_grip:.3}, default {et_default:.3}, soft spring {et_soft:.3}, low mu {et_slide:.3}");
    assert!(et_grip > 0.1, "{et_grip}");
    assert!(et_slide < 0.0, "{et_slide}");
}

#[test]
fn synth_of_a_contact_world_is_fast_and_reproducible() {
    let text = "seed = 5\n[world]\ncontact = { shaft_tip = { mass_g = 4.0 } }\n";
    let cfg =
        smash::synth::parse_config(std::path::Path::new("configs/synth/x.toml"), text).unwrap();
    let club =
        smash::club::ClubSpec::new("paper".into(), None, ModelParams::paper_driver(), vec![])
            .unwrap();
    let t = std::time::Instant::now();
    let a = smash::synth::generate(&cfg, &club).unwrap();
    let secs = t.elapsed().as_secs_f64();
    println!("600 shots in {secs:.2} s");
    assert_eq!(a.shots.len(), 600);
    assert_eq!(a, smash::synth::generate(&cfg, &club).unwrap());
}
