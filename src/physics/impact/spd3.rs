//! The 3×3 symmetric positive definite solve of the collision law, by cofactors.

use nalgebra::{Matrix3, Vector3};

use crate::physics::laws::solve_sym3;

/// Solve `K x = b` for a symmetric positive definite 3×3 `K` by cofactors (no allocation): the
/// lanes' [`solve_sym3`] on one shot (its upper triangle; the same operations).
#[inline]
pub fn solve_spd3(k: &Matrix3<f64>, b: &Vector3<f64>) -> Vector3<f64> {
    let sym = [
        k[(0, 0)],
        k[(0, 1)],
        k[(0, 2)],
        k[(1, 1)],
        k[(1, 2)],
        k[(2, 2)],
    ];
    Vector3::from(solve_sym3::<f64>(&sym, &[b.x, b.y, b.z]))
}
