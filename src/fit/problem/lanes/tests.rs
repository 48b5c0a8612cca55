//! Unit tests of the lane evaluation.

use super::*;
use crate::lanes::W;

/// The contact frames the lanes compute are the scalar [`FaceGeometry::contact`]'s, bit for
/// bit, across the face and just off it (where a lane off the face must be flagged), for
/// the paper driver's face and a flatter and a rounder one.
#[test]
fn lane_contact_frames_are_the_scalar_ones() {
    let faces = [(0.3048, 0.2540), (0.5, 0.4), (0.12, 0.1)]
        .map(|(b, r)| FaceGeometry::new(b, r).expect("valid face"));
    let mut checked = (0, 0);
    for face in &faces {
        let roll = face.roll_m();
        let bulge = face.bulge_m();
        // Up to 10 % beyond the roll radius and the heel–toe radius, and some NaN.
        let ys: Vec<f64> = (-44..=44).map(|k| roll * 1.1 * k as f64 / 40.0).collect();
        let zs: Vec<f64> = (-44..=44).map(|k| bulge * 1.1 * k as f64 / 40.0).collect();
        let mut pts: Vec<(f64, f64)> = ys
            .iter()
            .flat_map(|&y| zs.iter().map(move |&z| (y, z)))
            .collect();
        pts.extend([(f64::NAN, 0.0), (0.0, f64::NAN), (0.01, -0.02)]);
        for quad in pts.chunks(W) {
            let mut y = V::splat(0.0);
            let mut z = V::splat(0.0);
            for (l, &(a, b)) in quad.iter().enumerate() {
                (y.0[l], z.0[l]) = (a, b);
            }
            let (on_face, cf) = face.contact_on(y, z);
            for (l, &(a, b)) in quad.iter().enumerate() {
                let on = on_face.0[l] != 0;
                match face.contact(a, b) {
                    Err(_) => {
                        assert!(!on, "({a}, {b}) is off the face");
                        checked.1 += 1;
                    }
                    Ok(want) => {
                        assert!(on, "({a}, {b}) is on the face");
                        let got = [cf.point_m, cf.normal, cf.tangent_y, cf.tangent_z];
                        let want = [want.point_m, want.normal, want.tangent_y, want.tangent_z];
                        for (g, w) in got.iter().zip(&want) {
                            for c in 0..3 {
                                assert_eq!(g[c].0[l].to_bits(), w[c].to_bits(), "({a}, {b})");
                            }
                        }
                        checked.0 += 1;
                    }
                }
            }
        }
    }
    // Both kinds of location were seen.
    assert!(checked.0 > 10_000 && checked.1 > 100, "{checked:?}");
}
