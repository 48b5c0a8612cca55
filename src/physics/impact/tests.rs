//! Unit tests of the impact solve.

use super::*;
use approx::assert_relative_eq;

#[test]
fn cofactor_solve_matches_lu() {
    let k = Matrix3::new(26.7, 1.3, -0.4, 1.3, 80.2, 2.1, -0.4, 2.1, 77.9);
    let b = Vector3::new(40.0, -3.0, 1.5);
    let x = solve_spd3(&k, &b);
    let lu = k.lu().solve(&b).unwrap();
    assert_relative_eq!(x, lu, max_relative = 1e-14);
    assert_relative_eq!(k * x, b, max_relative = 1e-13);
}

/// A delivery frame made from the trigonometry of other biases ([`Delivery::frame_trig`],
/// reused for the angles the model's biases leave) is the one made afresh, bit for bit, for
/// every combination of a loft and a face bias the same as, or other than, the trigonometry's.
#[test]
fn frames_from_reused_trigonometry_are_the_fresh_ones_bit_for_bit() {
    let d = Delivery {
        club_speed_m_s: 44.7,
        attack_angle_rad: -0.021,
        club_path_rad: 0.034,
        dynamic_loft_rad: 0.23,
        face_angle_rad: -0.017,
        lie_tilt_rad: 0.052,
        club_omega_rad_s: Vector3::new(1.5, -3.0, 8.0),
        impact_y_m: 0.004,
        impact_z_m: -0.006,
        shaft_mass_g: None,
    };
    let bits = |f: &DeliveryFrame| {
        let mut v: Vec<u64> = f.r_gf.iter().map(|x| x.to_bits()).collect();
        v.extend(f.club_velocity_f_m_s.iter().map(|x| x.to_bits()));
        v.extend(f.club_omega_f_rad_s.iter().map(|x| x.to_bits()));
        v.extend([f.loft_bias_rad.to_bits(), f.face_bias_rad.to_bits()]);
        v
    };
    let model = |loft: f64, face: f64| {
        let mut params = ModelParams::paper_driver();
        params.loft_bias_rad = loft;
        params.face_bias_rad = face;
        ImpactModel::new(params).expect("a valid model")
    };
    let unbiased = model(0.0, 0.0).delivery_frame(&d);
    for made in [d.frame_trig(0.0, 0.0), d.frame_trig(0.011, -0.007)] {
        for (loft, face) in [(0.0, 0.0), (0.011, 0.0), (0.0, -0.007), (0.011, -0.007)] {
            let m = model(loft, face);
            let fresh = m.delivery_frame(&d);
            assert_eq!(
                bits(&fresh),
                bits(&m.delivery_frame_from(&d, &made)),
                "loft {loft} face {face}"
            );
            assert_eq!(fresh.r_gf == unbiased.r_gf, loft == 0.0 && face == 0.0);
        }
    }
}
