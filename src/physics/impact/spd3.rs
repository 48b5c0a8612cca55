//! The 3×3 symmetric positive definite solve of the collision law, by cofactors.

use nalgebra::{Matrix3, Vector3};

/// Solve `K x = b` for a symmetric positive definite 3×3 `K` by cofactors (no allocation).
#[inline]
pub fn solve_spd3(k: &Matrix3<f64>, b: &Vector3<f64>) -> Vector3<f64> {
    let (a, bb, c) = (k[(0, 0)], k[(0, 1)], k[(0, 2)]);
    let (d, e) = (k[(1, 1)], k[(1, 2)]);
    let f = k[(2, 2)];
    let c00 = d * f - e * e;
    let c01 = c * e - bb * f;
    let c02 = bb * e - c * d;
    let c11 = a * f - c * c;
    let c12 = bb * c - a * e;
    let c22 = a * d - bb * bb;
    let inv_det = 1.0 / (a * c00 + bb * c01 + c * c02);
    Vector3::new(
        (c00 * b.x + c01 * b.y + c02 * b.z) * inv_det,
        (c01 * b.x + c11 * b.y + c12 * b.z) * inv_det,
        (c02 * b.x + c12 * b.y + c22 * b.z) * inv_det,
    )
}
