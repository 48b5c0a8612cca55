//! The model's physical laws, each written once.
//!
//! Every law is a small `Copy` type holding its constants (SI units) with one evaluation that is
//! generic over [`Real`]: a plain `f64` for the scalar solve ([`super::ImpactModel::solve`], one
//! shot at a time) and a vector of lanes for the face-map kernel
//! ([`crate::sweep::FaceMapKernel`]), or for any batch of shots. Both paths call the same code,
//! so a law cannot be changed in one and forgotten in the other.
//!
//! | law | type | where the effects enter |
//! |---|---|---|
//! | normal restitution | [`Restitution`] | `cor_level`, `cor_speed`, `cor_radial`, `cor_power` |
//! | ball lever arm | [`BallContact`] | `ball_offset` |
//! | collision matrix (masses, inertias) | [`CollisionMatrix`] | `added_mass`, `hosel_mass`, `com_offset`, `inertia_scale`, `compression_lever` (the ball's inertia; composed into [`super::ModelParams`] once, see `crate::effects`) |
//! | tangential law (approach and gear-effect parts) | [`TangentialLaw`] | `tangential_restitution`, `friction`, `tangential_compliance` |
//! | finite contact | [`FiniteContact`] | `contact_time` (the head turning and the ball travelling over the face while in contact) |
//!
//! Geometry biases (`loft_bias`, `face_bias`) act on the delivered angles in
//! [`super::ImpactModel::face_orientation`], which both paths call.
//!
//! Only `+ − × ÷ √` (and `powf` when a `cor_power` exponent is set) are used, never fused
//! multiply–add, so every code path gives the same bits for the same inputs.

pub use super::real::Real;
#[cfg(test)]
use crate::lanes::V;

/// Reference normal approach speed of the speed-dependent COR laws, m/s: 109 mph, the
/// reference speed of `docs/conventions.md` (`cor_speed`, `cor_power`).
pub const COR_REFERENCE_SPEED_M_S: f64 = 48.77;

/// A 3-vector of [`Real`]s (components in the face frame F unless said otherwise).
pub type Vec3<R> = [R; 3];

/// A symmetric 3×3 matrix: `[xx, xy, xz, yy, yz, zz]`.
pub type Sym3<R> = [R; 6];

#[inline(always)]
fn dot<R: Real>(a: &Vec3<R>, b: &Vec3<R>) -> R {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `a × b`, with the operations of nalgebra's `cross` (so the scalar solve and the lanes agree
/// to the bit).
#[inline(always)]
pub fn cross<R: Real>(a: &Vec3<R>, b: &Vec3<R>) -> Vec3<R> {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[inline(always)]
fn sym_mul<R: Real>(k: &Sym3<R>, v: &Vec3<R>) -> Vec3<R> {
    [
        k[0] * v[0] + k[1] * v[1] + k[2] * v[2],
        k[1] * v[0] + k[3] * v[1] + k[4] * v[2],
        k[2] * v[0] + k[4] * v[1] + k[5] * v[2],
    ]
}

/// The normal coefficient of restitution of one impact:
///
/// ```text
/// e = cor·(u1n / v_ref)^(−q) − k·(u1n − v_ref) − c·(y² + z²)      v_ref = 48.77 m/s
/// ```
///
/// `cor` is the face's COR (club file `cor`, plus `cor_level`), `q` the `cor_power` exponent,
/// `k` the `cor_speed` slope and `c` the `cor_radial` falloff; `y`, `z` the impact location.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Restitution {
    /// COR at the reference speed and the face centre.
    pub cor: f64,
    /// Power-law exponent `q` on the normal approach speed (0: off).
    pub power_q: f64,
    /// Linear slope `k` with normal approach speed, s/m.
    pub speed_k_s_per_m: f64,
    /// Falloff `c` with squared distance from the face centre, 1/m².
    pub radial_c_per_m2: f64,
}

impl Restitution {
    /// `e` for normal approach speed `u1n_m_s` at squared distance `r2_m2` from the face centre.
    #[inline(always)]
    pub fn cor<R: Real>(&self, u1n_m_s: R, r2_m2: R) -> R {
        if self.power_q == 0.0 {
            self.cor_with::<R, false>(u1n_m_s, r2_m2)
        } else {
            self.cor_with::<R, true>(u1n_m_s, r2_m2)
        }
    }

    /// [`Restitution::cor`] with the power term switched at compile time: `POWER` must be
    /// `self.power_q != 0.0` (with `q = 0` both give the same bits, since `x^0 = 1` exactly).
    /// Inner loops use it so that the common case carries no `pow` call.
    #[inline(always)]
    pub fn cor_with<R: Real, const POWER: bool>(&self, u1n_m_s: R, r2_m2: R) -> R {
        let base = if POWER {
            (u1n_m_s / COR_REFERENCE_SPEED_M_S).powf(-self.power_q) * self.cor
        } else {
            R::splat(self.cor)
        };
        base - (u1n_m_s - COR_REFERENCE_SPEED_M_S) * self.speed_k_s_per_m
            - r2_m2 * self.radial_c_per_m2
    }
}

/// The contact point relative to the ball's centre of mass, `r_b = −radius·n + dy·y_I + dz·z_I`
/// (the paper's `[−21.3 0 0]` mm in the impact frame, plus the `ball_offset` effect).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BallContact {
    /// Ball radius, m.
    pub radius_m: f64,
    /// Offset `dy` along `y_I`, m.
    pub offset_y_m: f64,
    /// Offset `dz` along `z_I`, m.
    pub offset_z_m: f64,
}

impl BallContact {
    /// `r_b` from the unit normal `n`, the impact-frame tangent `t_y` and the horizontal
    /// tangent `t_z`, given by its x and z components (`z_I = (−z, 0, X)/ρ` has no y component:
    /// `docs/conventions.md`, face geometry).
    #[inline(always)]
    pub fn lever<R: Real>(&self, n: &Vec3<R>, t_y: &Vec3<R>, t_z_xz: &[R; 2]) -> Vec3<R> {
        let (nr, dy, dz) = (-self.radius_m, self.offset_y_m, self.offset_z_m);
        [
            n[0] * nr + t_y[0] * dy + t_z_xz[0] * dz,
            n[1] * nr + t_y[1] * dy,
            n[2] * nr + t_y[2] * dy + t_z_xz[1] * dz,
        ]
    }
}

/// The collision matrix
/// `K = (1/m_c + 1/m_b)·1 − [r_c]× I_c⁻¹ [r_c]× − [r_b]× I_b⁻¹ [r_b]×` (isotropic ball), which
/// maps an impulse on the ball to the change of the contact points' relative velocity. Every
/// mass and inertia effect reaches the impact through it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CollisionMatrix {
    /// `1/m_c + 1/m_b`, 1/kg.
    pub inv_mass_sum: f64,
    /// Symmetrised inverse clubhead inertia in F, `[xx, xy, xz, yy, yz, zz]`, 1/(kg·m²).
    pub club_inv_inertia: [f64; 6],
    /// `1/I_b`, 1/(kg·m²).
    pub ball_inv_inertia: f64,
}

impl CollisionMatrix {
    /// `K` for lever arms `r_c` (contact from clubhead CoM) and `r_b` (contact from ball CoM).
    #[inline(always)]
    pub fn matrix<R: Real>(&self, r_c: &Vec3<R>, r_b: &Vec3<R>) -> Sym3<R> {
        // −[r_c]× J [r_c]× = Cᵀ J C with C = [r_c]×, whose columns are
        // c0 = (0, a2, −a1), c1 = (−a2, 0, a0), c2 = (a1, −a0, 0).
        let [a0, a1, a2] = *r_c;
        let [jxx, jxy, jxz, jyy, jyz, jzz] = self.club_inv_inertia;
        let jc0y = a2 * jyy - a1 * jyz;
        let jc0z = a2 * jyz - a1 * jzz;
        let jc1x = a0 * jxz - a2 * jxx;
        let jc1y = a0 * jyz - a2 * jxy;
        let jc1z = a0 * jzz - a2 * jxz;
        let jc2x = a1 * jxx - a0 * jxy;
        let jc2y = a1 * jxy - a0 * jyy;
        let jc2z = a1 * jxz - a0 * jyz;
        let m00 = a2 * jc0y - a1 * jc0z;
        let m01 = a2 * jc1y - a1 * jc1z;
        let m02 = a2 * jc2y - a1 * jc2z;
        let m11 = a0 * jc1z - a2 * jc1x;
        let m12 = a0 * jc2z - a2 * jc2x;
        let m22 = a1 * jc2x - a0 * jc2y;
        // −[r_b]× I_b⁻¹ [r_b]× = (|r_b|²·1 − r_b r_bᵀ)/I_b.
        let ib = self.ball_inv_inertia;
        let [bx, by, bz] = *r_b;
        let rb2 = bx * bx + by * by + bz * bz;
        let ims = self.inv_mass_sum;
        [
            m00 + ims + (rb2 - bx * bx) * ib,
            m01 - bx * by * ib,
            m02 - bx * bz * ib,
            m11 + ims + (rb2 - by * by) * ib,
            m12 - by * bz * ib,
            m22 + ims + (rb2 - bz * bz) * ib,
        ]
    }
}

/// Solve `K x = b` for a symmetric positive definite `K` by cofactors (no allocation, no branch).
#[inline(always)]
pub fn solve_sym3<R: Real>(k: &Sym3<R>, b: &Vec3<R>) -> Vec3<R> {
    let [a, bb, c, d, e, f] = *k;
    let c00 = d * f - e * e;
    let c01 = c * e - bb * f;
    let c02 = bb * e - c * d;
    let c11 = a * f - c * c;
    let c12 = bb * c - a * e;
    let c22 = a * d - bb * bb;
    let inv_det = R::splat(1.0) / (a * c00 + bb * c01 + c * c02);
    [
        (c00 * b[0] + c01 * b[1] + c02 * b[2]) * inv_det,
        (c01 * b[0] + c11 * b[1] + c12 * b[2]) * inv_det,
        (c02 * b[0] + c12 * b[1] + c22 * b[2]) * inv_det,
    ]
}

/// The impulse of one impact from the normal restitution and the tangential law:
///
/// ```text
/// K P = u1 + e·u1n·n + e_t·u1t − e_g·(K·n)_t·P_n0        u1t = u1 − u1n·n
///                                                         P_n0 = (1 + e)·u1n / (n·K·n)
/// ```
///
/// i.e. the contact point leaves with the tangential velocity `u_t' = −e_t·u1t − e_g·Δ_g`,
/// where `Δ_g = −(K·n)_t·P_n0` is the tangential velocity the normal impulse alone would add
/// (the gear effect: the off-diagonal terms of `K` turn a normal push into tangential motion of
/// the contact point). `e_t = e_g = 0` is the paper's no slip. A gripping, compliant contact
/// restores the two parts differently (see `crate::effects::tangential_compliance`): `e_t` is
/// the free rebound of the tangential spring, `e_g` its response to being driven by the normal
/// force. With friction `mu`, gross slip where that impulse's tangential part exceeds `mu·P_n`:
/// `P = P_n·(n + mu·ŝ)`, `ŝ = u1_t/|u1_t|`, `P_n = (1 + e)·u1n / (n·K·(n + mu·ŝ))`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TangentialLaw {
    /// Tangential restitution `e_t` at normal incidence.
    pub e_t: f64,
    /// Change of `e_t` per unit tangent of the incidence, `|u1t|/u1n` (the
    /// `tangential_compliance` effect; 0: a constant `e_t`).
    pub e_t_slope: f64,
    /// Gear restitution `e_g` (the `tangential_compliance` effect; 0: none).
    pub e_g: f64,
    /// Coulomb friction coefficient, or `None` for unlimited friction.
    pub mu: Option<f64>,
}

impl TangentialLaw {
    /// The impulse on the ball and whether friction limited it (slip), from the collision matrix
    /// `k`, unit normal `n`, approach velocity `u1`, its normal part `u1n` and the COR `e`.
    /// `FRICTION` must be `self.mu.is_some()` (a constant so that lanes without friction carry
    /// no slip code).
    #[inline(always)]
    pub fn impulse<R: Real, const FRICTION: bool>(
        &self,
        k: &Sym3<R>,
        n: &Vec3<R>,
        u1: &Vec3<R>,
        u1n: R,
        e: R,
    ) -> (Vec3<R>, R::Mask) {
        // `tangential_compliance`: e_t rises with the tangent of the incidence, |u1t|/u1n.
        let e_t = if self.e_t_slope == 0.0 {
            R::splat(self.e_t)
        } else {
            tangential_speed(u1, n, u1n) / u1n * self.e_t_slope + self.e_t
        };
        Self::impulse_with::<R, FRICTION>(
            k,
            n,
            u1,
            u1n,
            e,
            e_t,
            self.e_g,
            R::splat(self.mu.unwrap_or(f64::INFINITY)),
        )
    }

    /// [`TangentialLaw::impulse`] with `e_t` and `mu` given per lane (as user-defined effects
    /// set them) and the gear restitution `e_g`; `mu` is read only when `FRICTION`.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub fn impulse_with<R: Real, const FRICTION: bool>(
        k: &Sym3<R>,
        n: &Vec3<R>,
        u1: &Vec3<R>,
        u1n: R,
        e: R,
        e_t: R,
        e_g: f64,
        mu: R,
    ) -> (Vec3<R>, R::Mask) {
        let u1t = [u1[0] - u1n * n[0], u1[1] - u1n * n[1], u1[2] - u1n * n[2]];
        let eu = e * u1n;
        let b = if e_g == 0.0 {
            [
                u1[0] + eu * n[0] + u1t[0] * e_t,
                u1[1] + eu * n[1] + u1t[1] * e_t,
                u1[2] + eu * n[2] + u1t[2] * e_t,
            ]
        } else {
            // The gear-effect drive: (K·n)_t·P_n0, scaled by e_g.
            let kn = sym_mul(k, n);
            let knn = dot(&kn, n);
            let s = (e + 1.0) * u1n / knn * e_g;
            [
                u1[0] + eu * n[0] + u1t[0] * e_t - (kn[0] - knn * n[0]) * s,
                u1[1] + eu * n[1] + u1t[1] * e_t - (kn[1] - knn * n[1]) * s,
                u1[2] + eu * n[2] + u1t[2] * e_t - (kn[2] - knn * n[2]) * s,
            ]
        };
        let p = solve_sym3(k, &b);
        if !FRICTION {
            return (p, R::no());
        }
        let pn = dot(&p, n);
        let pt = [p[0] - pn * n[0], p[1] - pn * n[1], p[2] - pn * n[2]];
        let pt_norm = dot(&pt, &pt).sqrt();
        let ut = dot(&u1t, &u1t).sqrt();
        let zero = R::splat(0.0);
        let slip = pt_norm.gt(pn * mu) & ut.gt(zero);
        let f = mu / ut;
        let dir = [n[0] + u1t[0] * f, n[1] + u1t[1] * f, n[2] + u1t[2] * f];
        let pn_slip = (e + 1.0) * u1n / dot(n, &sym_mul(k, &dir));
        (
            [
                R::select(slip, dir[0] * pn_slip, p[0]),
                R::select(slip, dir[1] * pn_slip, p[1]),
                R::select(slip, dir[2] * pn_slip, p[2]),
            ],
            slip,
        )
    }
}

/// Impulse-weighted mean, over a Hertz impact of duration `τ`, of `∫₀ᵗ s dt'` where `s(t)` is
/// the fraction of the impulse delivered by `t`, divided by `τ`: `1/9` (integrating the
/// one-body Hertz impact `m·δ̈ = −k·δ^1.5` gives 0.11111; a half-sine force pulse would give
/// 1/8; recomputed in the tests). The head's mean rotation at the
/// impulse's centroid is `θ̄ = τ·(ω₀/2 + Δω/9)` (see [`FiniteContact`]).
pub const HERTZ_MEAN_SPIN_UP: f64 = 1.0 / 9.0;

/// The contact geometry and approach of one impact (or of each lane of impacts), all in the face
/// frame `F` at first contact: what [`FiniteContact::impact`] needs.
#[derive(Debug, Clone, Copy)]
pub struct ContactGeometry<R> {
    /// Unit face normal `x_I` at the first contact.
    pub normal: Vec3<R>,
    /// Unit tangent `y_I` (up the face).
    pub tangent_y: Vec3<R>,
    /// The `x` and `z` components of the horizontal tangent `z_I` (its `y` component is 0).
    pub tangent_z_xz: [R; 2],
    /// First contact point relative to the clubhead CoM, m.
    pub r_c: Vec3<R>,
    /// First contact point relative to the ball CoM, m.
    pub r_b: Vec3<R>,
    /// Approach velocity `u1` of the club's contact point relative to the ball, m/s.
    pub u1: Vec3<R>,
    /// Its normal part `u1·n`, m/s.
    pub u1n: R,
    /// The head's angular velocity before impact, rad/s.
    pub w_c: Vec3<R>,
}

/// What [`FiniteContact::impact`] gives, in the face frame `F` at first contact.
#[derive(Debug, Clone, Copy)]
pub struct FiniteImpact<R: Real> {
    /// Impulse on the ball, N·s.
    pub impulse: Vec3<R>,
    /// The ball's angular impulse about its centre, N·m·s.
    pub ball_angular_impulse: Vec3<R>,
    /// Whether friction limited the impulse.
    pub slipped: R::Mask,
    /// Where the impulse acts, relative to the clubhead CoM, m (the first contact point moved
    /// by the ball's mean travel; the head's angular impulse is `r_c × P`).
    pub r_c: Vec3<R>,
    /// Where the impulse acts, relative to the ball CoM, m.
    pub r_b: Vec3<R>,
}

/// A finite contact of duration `τ` (the `contact_time` effect), to first order in `τ`.
///
/// The momentum model treats the impact as instantaneous. During a real contact of a few tenths
/// of a millisecond two things move while the impulse is delivered, and this law takes both to
/// first order in `τ`, at the impulse's centroid (the impulse-weighted mean over the pulse).
///
/// **The head turns.** Its angular velocity goes from `ω₀` (the delivered one) to `ω₀ + Δω`,
/// `Δω = −I_c⁻¹(r_c × P)`, as the impulse `P` builds up. The impulse-weighted mean of the angle
/// turned is `θ̄ = ∫θ dP / P = τ·(ω₀/2 + Δω/9)`: for the one-body Hertz impact the impulse's
/// centroid is at `τ/2` (the pulse is nearly symmetric) and the weighted mean of `∫₀ᵗ s dt'`
/// (`s` the fraction of the impulse delivered by `t`) is `τ/9` ([`HERTZ_MEAN_SPIN_UP`]). To first
/// order the impulse is delivered by the face turned by `θ̄`: in that face's frame the approach
/// velocity is `u1 − θ̄×u1` (the restitution keeps the first-contact COR), the impulse `P_f`
/// follows from the same tangential law and collision matrix (both fixed to the head), and the
/// impulse and the ball's angular impulse are turned back by `θ̄` (`v ↦ v + θ̄×v`).
///
/// **The ball travels over the face.** At first touch the ball is at rest and the face point
/// under it moves with the approach velocity `u1`; its tangential part `u1t` slides the face
/// beneath the ball. The contact patch stays under the ball's *centre* (a sphere on a face whose
/// radii are ten times its own; rolling or sticking does not pin it to one point of the face):
/// it moves over the face with the velocity of the ball's centre relative to the face point
/// under it, `−(u1 − s(t)·g)_t`, where `g = (1/m_c + 1/m_b)·P + (I_c⁻¹(r_c × P)) × r_c` is what
/// the whole impulse `P` takes off the face point's velocity relative to the ball's centre (the
/// ball's and head's translation and the head's turning; unlike the contact *surfaces'* slip,
/// the ball's spin does not enter) and `s(t)` the fraction of the impulse delivered by `t`. The
/// impulse-weighted mean position of the impulse on the face is then, with the same two Hertz
/// constants as the turning,
///
/// ```text
/// d̄ = −τ·(u1/2 − g/9)_t
/// ```
///
/// For a gripping ball on a heavy head `P_t ≈ (2/7)·m_b·u1t` (rolling at release), so
/// `d̄ ≈ −τ·(1/2 − 2/63)·u1t = −0.468·τ·u1t`; a shear spring that gives energy back (Mindlin,
/// `e_t > 0`) takes a larger `P_t` and a slightly shorter travel, a ball sliding throughout a
/// smaller `P_t` and a longer one (at most `τ/2`, when the ball never moves). This is the
/// rolling of a ball over the face of Cross (*Am. J. Phys.* 70, 2002; *The Physics of Golf*,
/// ch. 5: a ball rolls up a lofted face during impact) and of the oblique Hertz contact of Maw,
/// Barber & Fawcett (*Wear* 38, 1976), whose contact patch follows the sphere's centre (Johnson,
/// *Contact Mechanics*, 1985, §7.2); the compliant world of `crate::synth::contact` integrates
/// it, and a constant travel fitted there came out at `0.48·τ·u1t` (`docs/compliant-worlds.md`).
/// On the face's curvature the point `d̄` away has a normal tilted by `κ·d̄` (bulge `1/B` along
/// the face's horizontal tangent, roll `1/Rr` along the other; the curvature at the face centre:
/// it varies by `(y/Rr)²`, a fraction of a percent, over the face), which changes the direction
/// of the normal impulse by `|d̄|/B`, a few tenths of a degree, and the gear effect's lever by
/// `d̄`. So the impulse is computed at the moved point: lever `r_c + d̄`, normal
/// `(n + κ·d̄)/|n + κ·d̄|`, the ball's lever `−R·n'` (plus its `ball_offset`, turned with the
/// normal), the approach of that face point `u1 + ω₀×d̄`, and the collision matrix there; then
/// the head's turning as above. The head recoils about the moved point (`r_c + d̄`).
///
/// `P` and `Δω` in `θ̄` and `d̄` are those of the instantaneous impulse (a first pass of the
/// law). Neglected: terms of order `τ²`, the contact point's own move while the head turns
/// (`≈ θ̄×r_c`, a few tenths of a millimetre) and the ball's compression (`compression_lever`,
/// a ball of inertia `I_b·R/(R − δ̄)`, in the collision matrix and the spin alike, so not part of
/// this law). At the face centre with a head-on delivery (`u1t = 0`, `g_t = 0`) there is no
/// travel; with `τ = 0` the law is the paper's instantaneous impact, bit for bit. Checked against
/// the compliant contact of `crate::synth::contact` in `tests/contact_world.rs`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FiniteContact {
    /// Contact time `τ`, s (0: the instantaneous impact of the paper).
    pub tau_s: f64,
    /// Heel–toe curvature of the face, `1/bulge`, 1/m.
    pub bulge_curvature_per_m: f64,
    /// Crown–sole curvature of the face, `1/roll`, 1/m.
    pub roll_curvature_per_m: f64,
    /// Whether the ball's travel over the face is part of the contact (true in every model;
    /// false leaves the head's turning alone, for comparisons: `ImpactModel::without_travel`).
    pub travel: bool,
}

impl FiniteContact {
    /// The impulse on the ball, the ball's angular impulse and where they act (in the face frame
    /// at first contact), and whether friction limited the impulse. `impulse(k, n, u, u·n)` is
    /// the instantaneous law (the tangential law with the COR) for a collision matrix, a unit
    /// normal and an approach velocity; with `τ = 0` it is called once, at the first contact,
    /// and its result returned as is. `collision` gives the collision matrix at a contact point
    /// and the head's inverse inertia; `radius_m` is the ball's radius.
    #[inline(always)]
    pub fn impact<R: Real>(
        &self,
        impulse: impl Fn(&Sym3<R>, &Vec3<R>, &Vec3<R>, R) -> (Vec3<R>, R::Mask),
        collision: &CollisionMatrix,
        radius_m: f64,
        g: &ContactGeometry<R>,
    ) -> FiniteImpact<R> {
        let n = &g.normal;
        let k = collision.matrix(&g.r_c, &g.r_b);
        let (p, slip) = impulse(&k, n, &g.u1, g.u1n);
        if self.tau_s == 0.0 {
            return FiniteImpact {
                impulse: p,
                ball_angular_impulse: cross(&g.r_b, &p),
                slipped: slip,
                r_c: g.r_c,
                r_b: g.r_b,
            };
        }
        let jm: Sym3<R> = collision.club_inv_inertia.map(R::splat);
        let dw = sym_mul(&jm, &cross(&g.r_c, &p));
        let (a, b) = (0.5 * self.tau_s, HERTZ_MEAN_SPIN_UP * self.tau_s);
        let theta = [
            g.w_c[0] * a - dw[0] * b,
            g.w_c[1] * a - dw[1] * b,
            g.w_c[2] * a - dw[2] * b,
        ];
        let (r_c, r_b, n, u1) = if self.travel {
            self.travelled(collision.inv_mass_sum, radius_m, g, &p, &dw)
        } else {
            (g.r_c, g.r_b, *n, g.u1)
        };
        let tu = cross(&theta, &u1);
        let u1r = [u1[0] - tu[0], u1[1] - tu[1], u1[2] - tu[2]];
        let u1nr = dot(&u1r, &n);
        let k = if self.travel {
            collision.matrix(&r_c, &r_b)
        } else {
            k
        };
        let (pf, slip) = impulse(&k, &n, &u1r, u1nr);
        let lf = cross(&r_b, &pf);
        let turn = |v: &Vec3<R>| {
            let t = cross(&theta, v);
            [v[0] + t[0], v[1] + t[1], v[2] + t[2]]
        };
        FiniteImpact {
            impulse: turn(&pf),
            ball_angular_impulse: turn(&lf),
            slipped: slip,
            r_c,
            r_b,
        }
    }

    /// The ball's mean travel over the face (type docs): the moved point's lever from the
    /// head's CoM and from the ball's, its unit normal and its approach velocity, from the
    /// first pass's impulse `p` and the head's angular velocity change `dw = I_c⁻¹(r_c × p)`.
    #[inline(always)]
    fn travelled<R: Real>(
        &self,
        inv_mass_sum: f64,
        radius_m: f64,
        g: &ContactGeometry<R>,
        p: &Vec3<R>,
        dw: &Vec3<R>,
    ) -> (Vec3<R>, Vec3<R>, Vec3<R>, Vec3<R>) {
        let n = &g.normal;
        let wr = cross(dw, &g.r_c);
        let (a, b) = (0.5 * self.tau_s, HERTZ_MEAN_SPIN_UP * self.tau_s);
        // The face's mean travel under the ball, τ·(u1/2 − g/9), and the ball's: minus its
        // tangential part.
        let f: Vec3<R> = std::array::from_fn(|i| g.u1[i] * a - (p[i] * inv_mass_sum + wr[i]) * b);
        let fn_ = dot(&f, n);
        let d: Vec3<R> = std::array::from_fn(|i| fn_ * n[i] - f[i]);
        // Tilt of the normal over d on the face's curvature.
        let [tzx, tzz] = g.tangent_z_xz;
        let ty = &g.tangent_y;
        let cy = (d[0] * ty[0] + d[1] * ty[1] + d[2] * ty[2]) * self.roll_curvature_per_m;
        let cz = (d[0] * tzx + d[2] * tzz) * self.bulge_curvature_per_m;
        let dn = [ty[0] * cy + tzx * cz, ty[1] * cy, ty[2] * cy + tzz * cz];
        let m = [n[0] + dn[0], n[1] + dn[1], n[2] + dn[2]];
        let inv = R::splat(1.0) / dot(&m, &m).sqrt();
        let n2 = m.map(|c| c * inv);
        // The ball's lever: the radius along the new normal, its offset turned by φ = n × dn.
        let o: Vec3<R> = std::array::from_fn(|i| g.r_b[i] + n[i] * radius_m);
        let po = cross(&cross(n, &dn), &o);
        let r_b: Vec3<R> = std::array::from_fn(|i| o[i] + po[i] - n2[i] * radius_m);
        let r_c: Vec3<R> = std::array::from_fn(|i| g.r_c[i] + d[i]);
        let wd = cross(&g.w_c, &d);
        let u1: Vec3<R> = std::array::from_fn(|i| g.u1[i] + wd[i]);
        (r_c, r_b, n2, u1)
    }
}

/// The tangential approach speed `|u1 − u1n·n|` (the `ut_m_s` of user-defined effects), with
/// the operations of [`TangentialLaw::impulse`].
#[inline(always)]
pub fn tangential_speed<R: Real>(u1: &Vec3<R>, n: &Vec3<R>, u1n: R) -> R {
    let u1t = [u1[0] - u1n * n[0], u1[1] - u1n * n[1], u1[2] - u1n * n[2]];
    dot(&u1t, &u1t).sqrt()
}

/// Every law of one validated model (see [`super::ImpactModel::laws`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Laws {
    /// Normal restitution.
    pub restitution: Restitution,
    /// Ball lever arm.
    pub ball: BallContact,
    /// Collision matrix constants.
    pub collision: CollisionMatrix,
    /// Tangential law.
    pub tangential: TangentialLaw,
    /// Finite contact time.
    pub contact: FiniteContact,
    /// User-defined terms (`crate::effects::user`): `cor`, `et`, `mu` evaluated with
    /// [`crate::physics::user_terms::UserTerms::contact`] after the library's restitution, and before
    /// the tangential law; mass and geometry per shot before the solve. Empty: unused.
    pub user: crate::physics::user_terms::UserTerms,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lanes_and_scalars_give_the_same_bits() {
        let law = Restitution {
            cor: 0.83,
            power_q: 0.12,
            speed_k_s_per_m: 0.003,
            radial_c_per_m2: 150.0,
        };
        let u = [40.0, 45.5, 48.77, 52.0];
        let r2 = [0.0, 1e-4, 4e-4, 9e-5];
        let v = law.cor(V(u), V(r2));
        for i in 0..4 {
            assert_eq!(v.0[i].to_bits(), law.cor(u[i], r2[i]).to_bits());
        }
        // At the reference speed and centre the COR is the face's own.
        assert_eq!(law.cor(48.77, 0.0), 0.83);
    }

    #[test]
    fn power_law_matches_its_formula() {
        let law = Restitution {
            cor: 0.8,
            power_q: 0.2,
            speed_k_s_per_m: 0.0,
            radial_c_per_m2: 0.0,
        };
        let e = law.cor(2.0 * 48.77, 0.0);
        assert!((e - 0.8 * 2f64.powf(-0.2)).abs() < 1e-15);
    }

    #[test]
    fn sym3_solve_inverts() {
        let k = [26.7, 1.3, -0.4, 80.2, 2.1, 77.9];
        let b = [40.0, -3.0, 1.5];
        let x = solve_sym3(&k, &b);
        let back = sym_mul(&k, &x);
        for i in 0..3 {
            assert!((back[i] - b[i]).abs() < 1e-12);
        }
    }
}
