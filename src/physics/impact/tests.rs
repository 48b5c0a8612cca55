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
