//! The effects `cor_level`, `cor_power`, `hosel_mass`, `face_curvature`, `cor_spot`,
//! `shaft_fraction` and `inertia_axes` against independent computations:
//! the paper's 15 equations solved directly, with the restitution law and the head-plus-point-
//! mass body written in the test from their definitions (not the engine's code); and the
//! single-definition design: the face-map kernel agrees with the scalar solve to 1e-12 with
//! every library effect switched on at once.

use crate::common;

use common::fifteen::{solve_fifteen, with_point_mass, FifteenSolution};
use nalgebra::Vector3;
use smash::effects::EffectKind;
use smash::fit::{calibrate, parse_effect_list, CalibrateOptions};
use smash::physics::{ImpactModel, ModelParams};
use smash::sweep::face_map;
use smash::{Delivery, ImpactOutcome, LaunchComponent};

fn deviation(closed: &ImpactOutcome, direct: &FifteenSolution) -> f64 {
    [
        (closed.impulse_n_s, direct.impulse_n_s),
        (
            closed.club_velocity_after_m_s,
            direct.club_velocity_after_m_s,
        ),
        (closed.club_omega_after_rad_s, direct.club_omega_after_rad_s),
        (closed.ball_velocity_m_s, direct.ball_velocity_m_s),
        (closed.ball_spin_rad_s, direct.ball_spin_rad_s),
    ]
    .iter()
    .map(|(a, b)| (a - b).norm() / b.norm().max(1e-300))
    .fold(0.0, f64::max)
}

/// The engine with `kind` applied at `values` against the 15 equations on `independent`.
fn check_against_fifteen(kind: EffectKind, values: &[f64], independent: ModelParams) {
    check_per_shot(kind, values, |_| independent.clone());
}

#[test]
fn cor_level_matches_the_fifteen_equations() {
    let mut independent = ModelParams::paper_driver();
    independent.cor = 0.83 - 0.03;
    check_against_fifteen(EffectKind::CorLevel, &[-0.03], independent);
}

#[test]
fn cor_power_matches_the_fifteen_equations() {
    let mut independent = ModelParams::paper_driver();
    independent.cor_power_q = 0.15;
    check_against_fifteen(EffectKind::CorPower, &[0.15], independent);
    // Golden values of the law itself: e = 0.83·(u1n/48.77)^(−0.15).
    let mut p = ModelParams::paper_driver();
    EffectKind::CorPower.apply(&[0.15], &mut p);
    let m = ImpactModel::new(p).unwrap();
    for d in common::deliveries() {
        let o = m.solve(&d).unwrap();
        let want = 0.83 * (o.normal_approach_speed_m_s / 48.77).powf(-0.15);
        assert!(
            (o.cor_effective - want).abs() <= 1e-15,
            "{} vs {want}",
            o.cor_effective
        );
    }
}

#[test]
fn hosel_mass_matches_a_rigid_head_plus_point_mass() {
    let hosel = Vector3::new(-20.0, 25.0, -55.0) * 1e-3;
    assert_eq!(ModelParams::paper_driver().hosel_m, hosel);
    let independent = with_point_mass(&ModelParams::paper_driver(), 6e-3, hosel);
    check_against_fifteen(EffectKind::HoselMass, &[6.0], independent.clone());
    // Golden values, by hand: m' = 210 g; c' = c + (6/210)·(h − c) with h − c = (22.3, 22.1,
    // −56.0) mm; the parallel-axis term μ(|d|²·1 − d dᵀ), μ = 204·6/210 g = 5.828571… g, adds
    // μ·(22.1² + 56²) = 21125.52… g·mm² = 211.2552… g·cm² to I_xx.
    let mut p = ModelParams::paper_driver();
    EffectKind::HoselMass.apply(&[6.0], &mut p);
    assert!((p.club_mass_kg - 0.210).abs() < 1e-15);
    let c_mm = p.club_com_m * 1e3;
    let want_c = [
        -42.3 + 22.3 * 6.0 / 210.0,
        2.9 + 22.1 * 6.0 / 210.0,
        1.0 - 56.0 * 6.0 / 210.0,
    ];
    for i in 0..3 {
        assert!((c_mm[i] - want_c[i]).abs() < 1e-12, "{c_mm} vs {want_c:?}");
    }
    let mu_g = 204.0 * 6.0 / 210.0;
    let dxx_gcm2 = mu_g * (22.1f64.powi(2) + 56.0f64.powi(2)) / 100.0;
    let dxy_gcm2 = -mu_g * 22.3 * 22.1 / 100.0;
    let i = p.club_inertia_kgm2 * 1e7;
    assert!(
        (i[(0, 0)] - (2843.0 + dxx_gcm2)).abs() < 1e-9,
        "{}",
        i[(0, 0)]
    );
    assert!(
        (i[(0, 1)] - (-733.0 + dxy_gcm2)).abs() < 1e-9,
        "{}",
        i[(0, 1)]
    );
    assert!((p.club_inertia_kgm2 - independent.club_inertia_kgm2).amax() < 1e-15);
    // Not the same physics as added_mass: the mass sits at the hosel, so the gear effect
    // changes (sidespin of a toe strike differs by more than a few rpm).
    let mut q = ModelParams::paper_driver();
    EffectKind::AddedMass.apply(&[6.0], &mut q);
    let d = common::deliveries()[6];
    let a = ImpactModel::new(p).unwrap().solve(&d).unwrap().launch();
    let b = ImpactModel::new(q).unwrap().solve(&d).unwrap().launch();
    let side = |l: smash::Launch| l.get_file(LaunchComponent::Sidespin);
    assert!(
        (side(a) - side(b)).abs() > 5.0,
        "{} vs {}",
        side(a),
        side(b)
    );
}

#[test]
fn face_curvature_matches_the_fifteen_equations() {
    // The twisted-face issue's world: a face of bulge 250 mm and roll 380 mm where the club
    // file says 305 / 305.
    let mut independent = ModelParams::paper_driver();
    independent.bulge_m = 0.250;
    independent.roll_m = 0.380;
    check_against_fifteen(EffectKind::FaceCurvature, &[-55.0, 75.0], independent);
    // At the face centre the radii change nothing (the normal there is the same for any torus).
    let mut p = ModelParams::paper_driver();
    EffectKind::FaceCurvature.apply(&[-55.0, 75.0], &mut p);
    let d = common::deliveries()[0];
    assert_eq!((d.impact_y_m, d.impact_z_m), (0.0, 0.0));
    let a = ImpactModel::new(p).unwrap().solve(&d).unwrap();
    let b = ImpactModel::new(ModelParams::paper_driver())
        .unwrap()
        .solve(&d)
        .unwrap();
    assert!((a.ball_velocity_m_s - b.ball_velocity_m_s).norm() < 1e-12);
}

#[test]
fn inertia_axes_matches_the_fifteen_equations() {
    // A head 20 % stiffer about the vertical axis and 15 % softer about the heel-toe axis
    // than the paper driver (Table 1: I_xx = 2843, I_yy = 5679, I_zz = 4085 g cm²), products
    // unchanged. By hand from the definition: second moments of mass M_xx = (5679 + 4085 −
    // 2843)/2 = 3460.5, M_yy = (2843 + 4085 − 5679)/2 = 624.5; both scaled by 0.85; the
    // heel-toe spread M_zz = 1.2·5679 − 0.85·3460.5 = 3873.375; I_xx = 0.85·624.5 + M_zz.
    let mut independent = ModelParams::paper_driver();
    independent.club_inertia_kgm2[(0, 0)] = (0.85 * 624.5 + 3873.375) * 1e-7;
    independent.club_inertia_kgm2[(1, 1)] = 5679.0e-7 * 1.2;
    independent.club_inertia_kgm2[(2, 2)] = 4085.0e-7 * 0.85;
    check_against_fifteen(EffectKind::InertiaAxes, &[1.2, 0.85], independent);
    // Neutral at (1, 1); the other moments and the products are untouched.
    let mut p = ModelParams::paper_driver();
    EffectKind::InertiaAxes.apply(&[1.0, 1.0], &mut p);
    assert_eq!(p, ModelParams::paper_driver());
    EffectKind::InertiaAxes.apply(&[1.2, 0.85], &mut p);
    let q = ModelParams::paper_driver();
    assert_eq!(p.club_inertia_kgm2[(0, 1)], q.club_inertia_kgm2[(0, 1)]);
    assert_eq!(p.club_inertia_kgm2[(1, 2)], q.club_inertia_kgm2[(1, 2)]);
    // Neutral exactly, and commuting with inertia_scale.
    let mut a = ModelParams::paper_driver();
    EffectKind::InertiaAxes.apply(&[1.2, 0.85], &mut a);
    EffectKind::InertiaScale.apply(&[1.1], &mut a);
    let mut b = ModelParams::paper_driver();
    EffectKind::InertiaScale.apply(&[1.1], &mut b);
    EffectKind::InertiaAxes.apply(&[1.2, 0.85], &mut b);
    assert!((a.club_inertia_kgm2 - b.club_inertia_kgm2).norm() < 1e-15);
}

/// The engine with `kind` at `values` against the 15 equations solved, shot by shot, on a
/// model whose constants `reference(d)` sets from the effect's definition at that shot.
fn check_per_shot(kind: EffectKind, values: &[f64], reference: impl Fn(&Delivery) -> ModelParams) {
    let mut p = ModelParams::paper_driver();
    kind.apply(values, &mut p);
    let engine = ImpactModel::new(p).unwrap();
    let nominal = ImpactModel::new(ModelParams::paper_driver()).unwrap();
    let mut changed = 0.0f64;
    for d in common::deliveries() {
        let closed = engine.solve(&d).unwrap();
        let direct = solve_fifteen(&ImpactModel::new(reference(&d)).unwrap(), &d).unwrap();
        let dev = deviation(&closed, &direct);
        assert!(dev <= 1e-10, "{kind}: relative deviation {dev:e} at {d:?}");
        let base = nominal.solve(&d).unwrap();
        changed = changed.max((closed.ball_velocity_m_s - base.ball_velocity_m_s).norm());
    }
    assert!(
        changed > 0.05,
        "{kind} changed ball velocity by {changed} m/s"
    );
}

#[test]
fn cor_spot_matches_the_fifteen_equations_with_the_peak_where_it_is_put() {
    // Peak 3 mm high and 4 mm toward the toe, falloff 2e-4 per mm²: at each shot the COR is
    // 0.83 − c·((y − 3)² + (z − 4)²), written here from the definition.
    let (y0, z0, c) = (3.0, 4.0, 2e-4);
    check_per_shot(EffectKind::CorSpot, &[y0, z0, c], |d| {
        let (y, z) = (d.impact_y_m * 1e3, d.impact_z_m * 1e3);
        let mut r = ModelParams::paper_driver();
        r.cor = 0.83 - c * ((y - y0).powi(2) + (z - z0).powi(2));
        r
    });
    // Golden: at the peak the COR is the face's own, 5 mm away it is 0.83 − 25·c.
    let mut p = ModelParams::paper_driver();
    EffectKind::CorSpot.apply(&[y0, z0, c], &mut p);
    let m = ImpactModel::new(p).unwrap();
    let at = |y_mm: f64, z_mm: f64| {
        let d = Delivery {
            impact_y_m: y_mm * 1e-3,
            impact_z_m: z_mm * 1e-3,
            ..common::deliveries()[5]
        };
        let o = m.solve(&d).unwrap();
        // The library's laws at u1n: the speed terms are off, so e is the location's alone.
        o.cor_effective
    };
    assert!((at(3.0, 4.0) - 0.83).abs() < 1e-14);
    assert!((at(6.0, 8.0) - (0.83 - 25.0 * c)).abs() < 1e-14);
    // With the peak at the centre it is cor_radial, to the bit.
    let mut spot = ModelParams::paper_driver();
    EffectKind::CorSpot.apply(&[0.0, 0.0, c], &mut spot);
    let mut radial = ModelParams::paper_driver();
    EffectKind::CorRadial.apply(&[c], &mut radial);
    for d in common::deliveries() {
        let a = ImpactModel::new(spot.clone()).unwrap().solve(&d).unwrap();
        let b = ImpactModel::new(radial.clone()).unwrap().solve(&d).unwrap();
        assert_eq!(a.ball_velocity_m_s, b.ball_velocity_m_s);
    }
    // Two peaks on one shot add exactly: c₁|r − a₁|² + c₂|r − a₂|².
    let mut two = ModelParams::paper_driver();
    EffectKind::CorSpot.apply(&[3.0, 4.0, 1e-4], &mut two);
    EffectKind::CorSpot.apply(&[-5.0, 0.0, 5e-5], &mut two);
    let m2 = ImpactModel::new(two).unwrap();
    for d in common::deliveries() {
        let (y, z) = (d.impact_y_m * 1e3, d.impact_z_m * 1e3);
        let want = 0.83
            - 1e-4 * ((y - 3.0).powi(2) + (z - 4.0).powi(2))
            - 5e-5 * ((y + 5.0).powi(2) + z * z);
        let got = m2.solve(&d).unwrap().cor_effective;
        assert!((got - want).abs() < 1e-14, "{got} vs {want}");
    }
}

#[test]
fn shaft_fraction_adds_the_fraction_of_each_shots_shaft_mass() {
    // f = 0.034 (the paper's shaft A: 2.54 g of 74.5 g). Each delivery is given a shaft mass;
    // the reference head is 204 g + f·m_shaft at that shot.
    let f = 0.034;
    let shafts = [74.5, 60.3, 70.9, 120.0];
    let with_shaft = |i: usize, d: Delivery| Delivery {
        shaft_mass_g: Some(shafts[i % 4]),
        ..d
    };
    let mut p = ModelParams::paper_driver();
    EffectKind::ShaftFraction.apply(&[f], &mut p);
    let engine = ImpactModel::new(p).unwrap();
    for (i, d0) in common::deliveries().into_iter().enumerate() {
        let d = with_shaft(i, d0);
        let mut r = ModelParams::paper_driver();
        r.club_mass_kg += f * shafts[i % 4] * 1e-3;
        let direct = solve_fifteen(&ImpactModel::new(r).unwrap(), &d).unwrap();
        let dev = deviation(&engine.solve(&d).unwrap(), &direct);
        assert!(dev <= 1e-10, "deviation {dev:e} at {d:?}");
    }
    // Without a shaft mass the shot takes the paper's mean driver shaft, (74.5 + 60.3 + 70.9)/3
    // g: the same launch as added_mass of f times that.
    let d = common::deliveries()[3];
    assert_eq!(d.shaft_mass_g, None);
    let mut q = ModelParams::paper_driver();
    EffectKind::AddedMass.apply(&[f * (74.5 + 60.3 + 70.9) / 3.0], &mut q);
    let a = engine.solve(&d).unwrap().ball_velocity_m_s;
    let b = ImpactModel::new(q)
        .unwrap()
        .solve(&d)
        .unwrap()
        .ball_velocity_m_s;
    assert!((a - b).norm() < 1e-12 * b.norm(), "{a} vs {b}");
}

#[test]
fn kernel_matches_the_scalar_solve_with_every_library_effect_on() {
    for friction in [false, true] {
        let mut p = ModelParams::paper_driver();
        for kind in EffectKind::ALL {
            if kind == EffectKind::Friction && !friction {
                continue;
            }
            kind.apply(&common::active_values(kind.params()), &mut p);
        }
        let model = ImpactModel::new(p).unwrap();
        // The finite contact's travel over the face is on (the contact point moves, so the
        // kernel's per-lane face geometry must follow the scalar solve's).
        let d6 = common::deliveries()[6];
        assert!(
            (model.solve(&d6).unwrap().ball_spin_rad_s
                - model
                    .clone()
                    .without_travel()
                    .solve(&d6)
                    .unwrap()
                    .ball_spin_rad_s)
                .norm()
                > 1.0
        );
        let ys: Vec<f64> = (0..13).map(|i| (-24.0 + 4.0 * i as f64) * 1e-3).collect();
        let zs: Vec<f64> = (0..21).map(|i| (-40.0 + 4.0 * i as f64) * 1e-3).collect();
        for d0 in common::deliveries() {
            let grid = face_map(&model, &d0, &ys, &zs);
            for (iy, &y) in ys.iter().enumerate() {
                for (iz, &z) in zs.iter().enumerate() {
                    let k = iy * zs.len() + iz;
                    let d = Delivery {
                        impact_y_m: y,
                        impact_z_m: z,
                        ..d0
                    };
                    match model.solve(&d) {
                        Ok(o) => {
                            assert!(grid.valid[k]);
                            let l = o.launch();
                            for c in LaunchComponent::ALL {
                                let (got, want) = (grid.component(c)[k], l.get_si(c));
                                let dev = (got - want).abs();
                                assert!(
                                    dev <= 1e-12 * want.abs() || dev <= 1e-9,
                                    "{c:?} at ({y}, {z}): kernel {got} vs solve {want}"
                                );
                            }
                        }
                        Err(_) => assert!(!grid.valid[k]),
                    }
                }
            }
        }
    }
}

/// Fit `request` on `shots` from the nominal paper club; every fitted parameter must be within
/// three standard errors of the truth.
fn recovers(shots: &[smash::model::Shot], request: &str, truth: &[f64]) {
    let req = parse_effect_list(request).unwrap();
    let cal = calibrate(
        &common::paper_club(),
        shots,
        &req,
        &CalibrateOptions::default(),
        None,
    )
    .unwrap();
    assert_eq!(cal.params.len(), truth.len());
    for (p, want) in cal.params.iter().zip(truth) {
        let se = p.stderr.expect("identifiable");
        eprintln!("{} = {:.5} ± {:.5} (truth {want})", p.label(), p.value, se);
        assert!(
            (p.value - want).abs() < 3.0 * se,
            "{}: {} ± {se} vs truth {want}",
            p.label(),
            p.value
        );
        assert!(
            se < 0.2 * want.abs(),
            "{}: standard error {se} too large",
            p.label()
        );
    }
    // The effect explains what the nominal model misses: a chi² drop far beyond chance for one
    // parameter (Δχ² > 25 is a 5σ improvement).
    assert!(
        cal.chi2_before - cal.chi2 > 25.0,
        "chi² {} before, {} after",
        cal.chi2_before,
        cal.chi2
    );
}

#[test]
fn cor_power_hidden_in_the_shipped_synth_world_is_recovered() {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/synth/cor_power_world.toml");
    let cfg = smash::synth::read_config(&path).unwrap();
    assert_eq!(cfg.hidden[0].kind(), EffectKind::CorPower);
    let q = cfg.hidden[0].values()[0];
    let run = smash::synth::generate(&cfg, &common::paper_club()).unwrap();
    let shots: Vec<_> = run.shots.iter().map(|s| s.to_shot()).collect();
    recovers(&shots, "cor_power", &[q]);
}

#[test]
fn cor_level_and_hosel_mass_are_recovered_from_their_worlds() {
    let e = common::Experiment::default();
    let world = common::truth(vec![common::fx("cor_level", &[-0.02], None)]);
    recovers(&common::shots(&world, &e), "cor_level", &[-0.02]);
    let world = common::truth(vec![common::fx("hosel_mass", &[8.0], None)]);
    recovers(&common::shots(&world, &e), "hosel_mass", &[8.0]);
}

/// A driver delivery with the given loft and the ball at the face centre, no head rotation.
fn centre_delivery(loft_deg: f64) -> Delivery {
    Delivery {
        club_speed_m_s: 45.0,
        attack_angle_rad: 0.0,
        club_path_rad: 0.0,
        dynamic_loft_rad: loft_deg.to_radians(),
        face_angle_rad: 0.0,
        lie_tilt_rad: 0.0,
        club_omega_rad_s: Vector3::zeros(),
        impact_y_m: 0.0,
        impact_z_m: 0.0,
        shaft_mass_g: None,
    }
}

/// `contact_time`'s travel of the ball over the face (`smash::physics::laws::FiniteContact`),
/// against the invariants of its derivation. A head-on impact at the face centre of a head whose
/// CoM lies on the face normal has no tangential approach and no tangential impulse: no travel,
/// so the finite contact with and without the travel give the same launch. A lofted centre
/// strike moves the impulse up the face by `s·τ·|u1t|` with `s` between the never-spinning
/// ball's 1/2 and the gripping ball's 1/2 − 2/63 less the head's share (the contact's velocity
/// over the face, computed here from the delivery, not from the law). And the law is continuous
/// at `τ = 0`, where it is the paper's instantaneous impact.
#[test]
fn contact_time_travel_obeys_its_invariants() {
    let tau_ms = 0.45;
    let with_tau = |mut p: ModelParams| {
        EffectKind::ContactTime.apply(&[tau_ms], &mut p);
        ImpactModel::new(p).unwrap()
    };
    // Head-on, CoM on the normal through the face centre: no travel.
    let mut on_axis = ModelParams::paper_driver();
    on_axis.club_com_m = Vector3::new(on_axis.club_com_m.x, 0.0, 0.0);
    let m = with_tau(on_axis);
    let d = centre_delivery(0.0);
    let (a, b) = (
        m.solve(&d).unwrap(),
        m.clone().without_travel().solve(&d).unwrap(),
    );
    assert!((a.contact_from_club_com_m - b.contact_from_club_com_m).norm() < 1e-12);
    assert!((a.ball_velocity_m_s - b.ball_velocity_m_s).norm() < 1e-12);
    assert!((a.ball_spin_rad_s - b.ball_spin_rad_s).norm() < 1e-9);
    // Lofted centre strike on the paper's driver: the impulse moves up the face.
    let m = with_tau(ModelParams::paper_driver());
    let d = centre_delivery(12.0);
    let frame = m.delivery_frame(&d);
    let cf = m.face().contact(0.0, 0.0).unwrap();
    let r_c = cf.point_m - m.params().club_com_m;
    let u1 = frame.club_velocity_f_m_s + frame.club_omega_f_rad_s.cross(&r_c);
    let u1t = u1 - cf.normal * u1.dot(&cf.normal);
    let o = m.solve(&d).unwrap();
    let moved = frame.r_gf.transpose() * o.contact_from_club_com_m - r_c;
    let s = moved.dot(&cf.tangent_y) / (tau_ms * 1e-3 * u1t.norm());
    println!(
        "centre strike, 12° loft: travel {:.3} mm up the face = {s:.4}·τ·|u1t| (|u1t| {:.2} m/s)",
        moved.dot(&cf.tangent_y) * 1e3,
        u1t.norm()
    );
    assert!(
        u1t.dot(&cf.tangent_y) < 0.0,
        "the face slides down under the ball"
    );
    assert!(
        s > 0.42 && s < 0.5,
        "travel {} mm up the face = {s:.3}·τ·|u1t|",
        moved.dot(&cf.tangent_y) * 1e3
    );
    // Along the face, and mostly up it (the CoM's small offset from the normal adds a sideways
    // gear-effect impulse, so a little heel–toe travel).
    let up = moved.dot(&cf.tangent_y);
    assert!(moved.dot(&cf.normal).abs() < 1e-12 * up, "{moved}");
    assert!(moved.dot(&cf.tangent_z).abs() < 0.1 * up, "{moved}");
    // Continuous at τ = 0, and exactly the paper's impact there.
    let paper = ImpactModel::new(ModelParams::paper_driver()).unwrap();
    let mut p = ModelParams::paper_driver();
    EffectKind::ContactTime.apply(&[0.0], &mut p);
    assert_eq!(
        ImpactModel::new(p).unwrap().solve(&d).unwrap(),
        paper.solve(&d).unwrap()
    );
    let mut p = ModelParams::paper_driver();
    EffectKind::ContactTime.apply(&[1e-7], &mut p);
    let tiny = ImpactModel::new(p).unwrap().solve(&d).unwrap();
    let base = paper.solve(&d).unwrap();
    assert!(
        (tiny.ball_velocity_m_s - base.ball_velocity_m_s).norm() < 1e-6,
        "{} vs {}",
        tiny.ball_velocity_m_s,
        base.ball_velocity_m_s
    );
}
