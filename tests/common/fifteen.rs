//! The paper's Eqs. 1–9 as one 15 × 15 linear system, solved directly (nalgebra LU): an
//! independent check of the closed-form 3 × 3 reduction in `ImpactModel::solve`.
//!
//! Unknowns, all in the ground frame G: `x = [P, v_c', ω_c', v_b', ω_b']` (impulse on the ball,
//! clubhead CoM velocity and angular velocity after, ball velocity and spin after). With
//! `Δ' = (v_c' + ω_c' × r_c) − (v_b' + ω_b' × r_b)` the relative contact-point velocity after
//! impact and `u1` the one before (ball at rest), the 15 equations are
//!
//! ```text
//! m_c v_c' + P            = m_c v_c          (1)  clubhead linear momentum
//! I_c ω_c' + r_c × P      = I_c ω_c          (2)  clubhead angular momentum about its CoM
//! m_b v_b' − P            = 0                (3)  ball linear momentum (ball at rest)
//! I_b ω_b' − r_b × P      = 0                (4)  ball angular momentum about its CoM
//! Δ'·x_I                  = −e·(u1·x_I)      (5)  normal restitution
//! Δ'·y_I                  = −e_t·(u1·y_I)    (8)  no slip (e_t = 0) or tangential restitution
//! Δ'·z_I                  = −e_t·(u1·z_I)    (9)
//! ```
//!
//! using `a·(ω × r) = ω·(r × a)`. Everything is assembled in G (the clubhead inertia rotated as
//! `R I_c Rᵀ`), unlike the closed form, which works in the face frame F. `e` includes the
//! `cor_speed`, `cor_radial` and `cor_power` laws (and `cor_level` through `cor`); the ball offset enters through `r_b`. Friction (gross
//! slip) is not part of these equations.

#![allow(dead_code)]

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};
use smash::physics::ModelParams;
use smash::{Delivery, ImpactModel};

/// Reference normal approach speed of the speed-dependent COR laws (`docs/conventions.md`: 109 mph),
/// written here independently of the engine's constant.
const REFERENCE_SPEED_M_S: f64 = 48.77;

/// The clubhead with a point mass `dm_kg` rigidly attached at `at_m` (face frame), from first
/// principles: total mass, mass-weighted centre, and each body's inertia moved to the common
/// centre by the parallel-axis theorem `I_O = I_C + m·(|d|²·1 − d dᵀ)`, summed. (The engine's
/// `hosel_mass` uses the equivalent reduced-mass form; this is the independent check.)
pub fn with_point_mass(p: &ModelParams, dm_kg: f64, at_m: Vector3<f64>) -> ModelParams {
    let m = p.club_mass_kg;
    let total = m + dm_kg;
    let centre = (p.club_com_m * m + at_m * dm_kg) / total;
    let shift = |d: Vector3<f64>, mass: f64| {
        let mut s = Matrix3::zeros();
        for i in 0..3 {
            for j in 0..3 {
                let delta = if i == j { d.dot(&d) } else { 0.0 };
                s[(i, j)] = mass * (delta - d[i] * d[j]);
            }
        }
        s
    };
    let mut q = p.clone();
    q.club_mass_kg = total;
    q.club_inertia_kgm2 =
        p.club_inertia_kgm2 + shift(p.club_com_m - centre, m) + shift(at_m - centre, dm_kg);
    q.club_com_m = centre;
    q
}

/// The 15 unknowns, in G, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FifteenSolution {
    /// Impulse on the ball, N·s.
    pub impulse_n_s: Vector3<f64>,
    /// Clubhead CoM velocity after impact, m/s.
    pub club_velocity_after_m_s: Vector3<f64>,
    /// Clubhead angular velocity after impact, rad/s.
    pub club_omega_after_rad_s: Vector3<f64>,
    /// Ball velocity after impact, m/s.
    pub ball_velocity_m_s: Vector3<f64>,
    /// Ball spin after impact, rad/s.
    pub ball_spin_rad_s: Vector3<f64>,
}

/// Solve Eqs. 1–9 for `model` and `d`; `None` if the location is off the face or the club does
/// not approach the ball.
///
/// # Panics
/// If the model has friction (not part of these equations).
pub fn solve_fifteen(model: &ImpactModel, d: &Delivery) -> Option<FifteenSolution> {
    let p = model.params();
    assert!(
        p.friction_mu.is_none(),
        "the 15-equation form has no friction limit"
    );
    let r_gf = model.face_orientation(d);
    let cf = model.face().contact(d.impact_y_m, d.impact_z_m).ok()?;
    // Impact frame and lever arms in G.
    let n = r_gf * cf.normal;
    let ty = r_gf * cf.tangent_y;
    let tz = r_gf * cf.tangent_z;
    let r_c = r_gf * (cf.point_m - p.club_com_m);
    let r_b = -p.ball_radius_m * n + p.ball_offset_y_m * ty + p.ball_offset_z_m * tz;
    let i_c: Matrix3<f64> = r_gf * p.club_inertia_kgm2 * r_gf.transpose();
    let (m_c, m_b, i_b) = (p.club_mass_kg, p.ball_mass_kg, p.ball_inertia_kgm2);

    let v_c = d.club_velocity_m_s();
    let w_c = d.club_omega_rad_s;
    let u1 = v_c + w_c.cross(&r_c);
    let u1n = u1.dot(&n);
    if u1n.is_nan() || u1n <= 0.0 {
        return None;
    }
    // docs/conventions.md: e = cor·(u1n/48.77 m/s)^(−q) − k·(u1n − 48.77 m/s) − c·(y² + z²).
    let e = p.cor * (u1n / REFERENCE_SPEED_M_S).powf(-p.cor_power_q)
        - p.cor_speed_k_s_per_m * (u1n - REFERENCE_SPEED_M_S)
        - p.cor_radial_c_per_m2 * (d.impact_y_m.powi(2) + d.impact_z_m.powi(2));
    let e_t = p.tangential_restitution;

    // Column blocks of the unknowns.
    const P: usize = 0;
    const VC: usize = 3;
    const WC: usize = 6;
    const VB: usize = 9;
    const WB: usize = 12;
    let mut a = SMatrix::<f64, 15, 15>::zeros();
    let mut b = SVector::<f64, 15>::zeros();
    let eye = Matrix3::<f64>::identity();
    // (1)
    a.fixed_view_mut::<3, 3>(0, VC).copy_from(&(eye * m_c));
    a.fixed_view_mut::<3, 3>(0, P).copy_from(&eye);
    b.fixed_rows_mut::<3>(0).copy_from(&(m_c * v_c));
    // (2)
    a.fixed_view_mut::<3, 3>(3, WC).copy_from(&i_c);
    a.fixed_view_mut::<3, 3>(3, P)
        .copy_from(&r_c.cross_matrix());
    b.fixed_rows_mut::<3>(3).copy_from(&(i_c * w_c));
    // (3)
    a.fixed_view_mut::<3, 3>(6, VB).copy_from(&(eye * m_b));
    a.fixed_view_mut::<3, 3>(6, P).copy_from(&(-eye));
    // (4)
    a.fixed_view_mut::<3, 3>(9, WB).copy_from(&(eye * i_b));
    a.fixed_view_mut::<3, 3>(9, P)
        .copy_from(&(-r_b.cross_matrix()));
    // (5), (8), (9): Δ'·t = −coef·(u1·t).
    for (row, t, coef) in [(12, n, e), (13, ty, e_t), (14, tz, e_t)] {
        let rc_t = r_c.cross(&t);
        let rb_t = r_b.cross(&t);
        for k in 0..3 {
            a[(row, VC + k)] = t[k];
            a[(row, WC + k)] = rc_t[k];
            a[(row, VB + k)] = -t[k];
            a[(row, WB + k)] = -rb_t[k];
        }
        b[row] = -coef * u1.dot(&t);
    }
    let x = a.lu().solve(&b)?;
    let v = |i: usize| Vector3::new(x[i], x[i + 1], x[i + 2]);
    Some(FifteenSolution {
        impulse_n_s: v(P),
        club_velocity_after_m_s: v(VC),
        club_omega_after_rad_s: v(WC),
        ball_velocity_m_s: v(VB),
        ball_spin_rad_s: v(WB),
    })
}
