//! The closed-form 3 × 3 impact solve (`ImpactModel::solve`) against the paper's 15 equations
//! solved directly (`common::fifteen`), on random deliveries and random effect sets (no
//! friction: the 15 equations are the no-slip / tangential-restitution form). All 15 unknowns
//! must agree to 1e-9 relative (of the vector's magnitude).

use crate::common;

use common::fifteen::{solve_fifteen, FifteenSolution};
use nalgebra::Vector3;
use proptest::prelude::*;
use smash::physics::{ImpactError, ImpactModel, ModelParams};
use smash::{Delivery, ImpactOutcome};

fn paper_params() -> ModelParams {
    ModelParams::paper_driver()
}

/// The paper's driver with a random subset of the (friction-free) effects.
fn params_strategy() -> impl Strategy<Value = ModelParams> {
    let on = |p: f64| prop::bool::weighted(p);
    (
        (
            on(0.5),
            -0.03f64..0.06,
            on(0.5),
            -2.0e-3f64..2.0e-3,
            -2.0e-3f64..2.0e-3,
        ),
        (
            on(0.5),
            -0.4f64..0.4,
            on(0.5),
            -0.01f64..0.02,
            on(0.5),
            0.0f64..300.0,
        ),
        (on(0.5), -4.0f64..4.0, -4.0f64..4.0),
        (on(0.5), prop::array::uniform3(-6e-3f64..6e-3), 0.6f64..1.5),
        (0.2f64..0.5, 0.2f64..0.5, on(0.5), 0.0f64..1.0),
    )
        .prop_map(
            |(
                (am, dm, bo, dy, dz),
                (tr, et, cs, k, cr, c),
                (bias, loft, face),
                (co, com, scale),
                (bulge, roll, cp, q),
            )| {
                let mut p = paper_params();
                if cp {
                    p.cor_power_q = q;
                }
                if am {
                    p.club_mass_kg += dm;
                }
                if bo {
                    p.ball_offset_y_m = dy;
                    p.ball_offset_z_m = dz;
                }
                if tr {
                    p.tangential_restitution = et;
                }
                if cs {
                    p.cor_speed_k_s_per_m = k;
                }
                if cr {
                    p.cor_radial_c_per_m2 = c;
                }
                if bias {
                    p.loft_bias_rad = loft.to_radians();
                    p.face_bias_rad = face.to_radians();
                }
                if co {
                    p.club_com_m += Vector3::from(com);
                }
                p.club_inertia_kgm2 *= scale;
                p.bulge_m = bulge;
                p.roll_m = roll;
                p
            },
        )
}

fn delivery_strategy() -> impl Strategy<Value = Delivery> {
    (
        25.0f64..60.0,
        prop::array::uniform3(-8.0f64..8.0),
        5.0f64..35.0,
        -4.0f64..4.0,
        prop::array::uniform3(-40.0f64..40.0),
        -0.03f64..0.03,
        -0.045f64..0.045,
    )
        .prop_map(
            |(speed, [attack, path, face], loft, lie, omega, y, z)| Delivery {
                club_speed_m_s: speed,
                attack_angle_rad: attack.to_radians(),
                club_path_rad: path.to_radians(),
                dynamic_loft_rad: loft.to_radians(),
                face_angle_rad: face.to_radians(),
                lie_tilt_rad: lie.to_radians(),
                club_omega_rad_s: Vector3::from(omega),
                impact_y_m: y,
                impact_z_m: z,
                shaft_mass_g: None,
            },
        )
}

/// Largest relative deviation over the five unknown vectors (each relative to its magnitude).
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

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn closed_form_matches_fifteen_equations(p in params_strategy(), d in delivery_strategy()) {
        let model = ImpactModel::new(p).unwrap();
        match (model.solve(&d), solve_fifteen(&model, &d)) {
            (Ok(closed), Some(direct)) => {
                let dev = deviation(&closed, &direct);
                prop_assert!(dev <= 1e-9, "relative deviation {dev:e}\nclosed {closed:?}\ndirect {direct:?}");
            }
            (Err(_), None) => {}
            // The fifteen equations take the law's COR as given; the closed form refuses one
            // no collision has (outside (0, 1]: `cor_power` at a slow club), and only that.
            (Err(ImpactError::CorOutOfRange { cor }), Some(_)) => {
                prop_assert!(!(cor > 0.0 && cor <= 1.0), "refused a COR of {cor}");
            }
            (c, f) => prop_assert!(false, "one solve failed, the other not: {c:?} vs {f:?}"),
        }
    }
}

fn nominal_delivery() -> Delivery {
    Delivery {
        club_speed_m_s: 47.0,
        attack_angle_rad: (-1.0f64).to_radians(),
        club_path_rad: 1.5f64.to_radians(),
        dynamic_loft_rad: 12.5f64.to_radians(),
        face_angle_rad: 0.5f64.to_radians(),
        lie_tilt_rad: 0.5f64.to_radians(),
        club_omega_rad_s: Vector3::new(-2.0, 5.0, -10.0),
        impact_y_m: 0.008,
        impact_z_m: -0.012,
        shaft_mass_g: None,
    }
}

/// The comparison can fail: a small change in any effect of the direct model (or a missing
/// one) is seen far above the 1e-9 tolerance.
#[test]
fn comparison_detects_a_different_model() {
    let d = nominal_delivery();
    let mut base = paper_params();
    base.ball_offset_y_m = 0.5e-3;
    base.ball_offset_z_m = -0.07e-3;
    base.tangential_restitution = 0.1;
    base.cor_speed_k_s_per_m = 0.004;
    base.cor_radial_c_per_m2 = 50.0;
    let closed = ImpactModel::new(base.clone()).unwrap().solve(&d).unwrap();
    let same = solve_fifteen(&ImpactModel::new(base.clone()).unwrap(), &d).unwrap();
    assert!(deviation(&closed, &same) <= 1e-12);
    type Perturbation = (&'static str, fn(&mut ModelParams));
    let perturbations: [Perturbation; 6] = [
        ("cor", |p| p.cor += 1e-6),
        ("ball offset", |p| p.ball_offset_y_m = 0.0),
        ("tangential restitution", |p| p.tangential_restitution = 0.0),
        ("cor speed", |p| p.cor_speed_k_s_per_m = 0.0),
        ("cor radial", |p| p.cor_radial_c_per_m2 = 0.0),
        ("com", |p| p.club_com_m.y += 1e-6),
    ];
    for (what, perturb) in perturbations {
        let mut p = base.clone();
        perturb(&mut p);
        let direct = solve_fifteen(&ImpactModel::new(p).unwrap(), &d).unwrap();
        let dev = deviation(&closed, &direct);
        assert!(
            dev > 1e-8,
            "changing {what} went unnoticed (deviation {dev:e})"
        );
    }
}
