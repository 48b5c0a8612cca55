//! The fits' lanes with user-defined terms and `shaft_fraction` are the scalar solve, bit for
//! bit (`ImpactModel::shot_consts_of` and `ImpactModel::solve_contact_shot` on lanes against the
//! same functions on one shot, which `ImpactModel::solve` runs). A test binary of its own: it
//! registers user-defined effects, which would otherwise become default candidates of other
//! tests' diagnoses in the same process.

use nalgebra::Vector3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use smash::lanes::{Real, V, W};
use smash::physics::impact::{ContactInputs, ImpactModel};
use smash::physics::user_terms::{delivery_vars, NV};
use smash::physics::{Delivery, ModelParams};

/// The user-defined terms of `tests/data/lane_path_effects.toml` (every kind the fits'
/// lanes take) plus `shaft_fraction`, at the given values.
fn model(values: [f64; 5], friction: bool) -> ImpactModel {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/lane_path_effects.toml");
    smash::data::effect_defs::read_effect_defs(&path).expect("definitions read");
    let mut p = ModelParams::paper_driver();
    let names = [
        "my_cor_power",
        "my_shaft_mass",
        "my_com_shift",
        "my_friction",
    ];
    for (k, name) in names.iter().enumerate() {
        if *name == "my_friction" && !friction {
            continue;
        }
        let e = smash::effects::user::lookup(name).expect("registered");
        e.apply(&[values[k]], &mut p);
    }
    smash::effects::EffectKind::ShaftFraction.apply(&[values[4]], &mut p);
    ImpactModel::new(p).expect("a valid model")
}

/// Each delivery's contact inputs on `m`'s face, and the same as lanes (one a delivery).
fn contact_inputs(
    m: &ImpactModel,
    shots: &[Delivery],
) -> (Vec<ContactInputs<f64>>, ContactInputs<V>) {
    let inputs: Vec<ContactInputs<f64>> = shots
        .iter()
        .map(|d| {
            let f = m.delivery_frame(d);
            let cf = m
                .face()
                .contact(d.impact_y_m, d.impact_z_m)
                .expect("on the face");
            ContactInputs::of(&f, &cf, d.impact_y_m, d.impact_z_m)
        })
        .collect();
    let lane = |f: &dyn Fn(&ContactInputs<f64>) -> f64| V(std::array::from_fn(|l| f(&inputs[l])));
    let x = ContactInputs::<V> {
        club_velocity_f_m_s: std::array::from_fn(|a| lane(&|c| c.club_velocity_f_m_s[a])),
        club_omega_f_rad_s: std::array::from_fn(|a| lane(&|c| c.club_omega_f_rad_s[a])),
        point_m: std::array::from_fn(|a| lane(&|c| c.point_m[a])),
        normal: std::array::from_fn(|a| lane(&|c| c.normal[a])),
        tangent_y: std::array::from_fn(|a| lane(&|c| c.tangent_y[a])),
        tangent_z_xz: std::array::from_fn(|a| lane(&|c| c.tangent_z_xz[a])),
        y_m: lane(&|c| c.y_m),
        z_m: lane(&|c| c.z_m),
    };
    (inputs, x)
}

/// Every lane of the lane solve with user-defined terms and a shaft fraction is its shot's
/// scalar solve, bit for bit: the shot constants, the impulse, the ball's velocity and spin,
/// and which shots a term's value refuses. Random deliveries, impact locations and shaft
/// masses, with and without friction; some parameter values put terms out of their range.
#[test]
fn lanes_with_user_terms_are_the_scalar_solve_bit_for_bit() {
    let mut rng = ChaCha8Rng::seed_from_u64(45);
    let (mut lanes_checked, mut refused) = (0, 0);
    for trial in 0..200 {
        let values = [
            rng.random_range(0.0..0.3),
            rng.random_range(0.0..0.06),
            rng.random_range(-0.1..0.1),
            rng.random_range(0.05..1.5),
            rng.random_range(0.0..0.05),
        ];
        let m = model(values, trial % 2 == 0);
        let shots: Vec<Delivery> = (0..W)
            .map(|_| Delivery {
                club_speed_m_s: rng.random_range(30.0..55.0),
                attack_angle_rad: rng.random_range(-0.08..0.08),
                club_path_rad: rng.random_range(-0.08..0.08),
                dynamic_loft_rad: rng.random_range(0.1..0.3),
                face_angle_rad: rng.random_range(-0.06..0.06),
                lie_tilt_rad: rng.random_range(-0.05..0.05),
                club_omega_rad_s: Vector3::new(0.0, rng.random_range(-5.0..5.0), 0.0),
                impact_y_m: rng.random_range(-0.012..0.012),
                impact_z_m: rng.random_range(-0.02..0.02),
                // A shaft mass far above any real one drives the head mass out of range.
                shaft_mass_g: Some(if trial % 10 == 7 {
                    9.0e5
                } else {
                    rng.random_range(40.0..130.0)
                }),
            })
            .collect();
        let (inputs, x) = contact_inputs(&m, &shots);
        let rows: Vec<[f64; NV]> = shots.iter().map(delivery_vars).collect();
        let mut vars: [V; NV] = std::array::from_fn(|k| V(std::array::from_fn(|l| rows[l][k])));
        let mut valid = !V::no();
        let c = m.shot_consts_of(&mut vars, &mut valid);
        let s = m.solve_contact_shot(&x, &c, &mut vars, &mut valid);
        for l in 0..W {
            let mut v1 = rows[l];
            let mut ok = true;
            let c1 = m.shot_consts_of::<f64>(&mut v1, &mut ok);
            let s1 = m.solve_contact_shot(&inputs[l], &c1, &mut v1, &mut ok);
            assert_eq!(valid.0[l] != 0, ok, "trial {trial} lane {l}: validity");
            if !ok {
                refused += 1;
                assert!(
                    m.solve(&shots[l]).is_err(),
                    "the scalar solve refuses it too"
                );
                continue;
            }
            let bits = |a: &[f64]| a.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
            let lane_of = |v: &[V]| v.iter().map(|x| x.0[l]).collect::<Vec<_>>();
            assert_eq!(
                bits(&lane_of(&[c.collision.inv_mass_sum, c.club_mass_kg])),
                bits(&[c1.collision.inv_mass_sum, c1.club_mass_kg])
            );
            assert_eq!(bits(&lane_of(&c.club_com_m)), bits(&c1.club_com_m));
            assert_eq!(
                bits(&lane_of(&s.impulse_n_s)),
                bits(&s1.impulse_n_s),
                "trial {trial} lane {l}"
            );
            assert_eq!(
                bits(&lane_of(&s.ball_velocity_f_m_s)),
                bits(&s1.ball_velocity_f_m_s)
            );
            assert_eq!(
                bits(&lane_of(&s.ball_spin_f_rad_s)),
                bits(&s1.ball_spin_f_rad_s)
            );
            assert_eq!(
                bits(&lane_of(&[s.cor_effective])),
                bits(&[s1.cor_effective])
            );
            // And the scalar solve of the delivery runs exactly this.
            let o = m.solve(&shots[l]).expect("solves");
            assert_eq!(
                o.normal_approach_speed_m_s.to_bits(),
                s1.normal_approach_speed_m_s.to_bits()
            );
            lanes_checked += 1;
        }
    }
    assert!(
        lanes_checked > 600 && refused >= 1,
        "{lanes_checked} lanes, {refused} refused"
    );
}
