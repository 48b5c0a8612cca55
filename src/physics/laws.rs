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

mod finite_contact;
#[cfg(test)]
use crate::lanes::V;
pub use finite_contact::{
    ContactGeometry, FiniteContact, FiniteImpact, InstantLaw, HERTZ_MEAN_SPIN_UP,
};

/// Reference normal approach speed of the speed-dependent COR laws, m/s: 109 mph, the
/// reference speed of `docs/conventions.md` (`cor_speed`, `cor_power`).
pub const COR_REFERENCE_SPEED_M_S: f64 = 48.77;

/// A 3-vector of [`Real`]s (components in the face frame F unless said otherwise).
pub type Vec3<R> = [R; 3];

/// A symmetric 3×3 matrix: `[xx, xy, xz, yy, yz, zz]`.
pub type Sym3<R> = [R; 6];

#[inline(always)]
pub(crate) fn dot<R: Real>(a: &Vec3<R>, b: &Vec3<R>) -> R {
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
pub(crate) fn sym_mul<R: Real>(k: &Sym3<R>, v: &Vec3<R>) -> Vec3<R> {
    [
        k[0] * v[0] + k[1] * v[1] + k[2] * v[2],
        k[1] * v[0] + k[3] * v[1] + k[4] * v[2],
        k[2] * v[0] + k[4] * v[1] + k[5] * v[2],
    ]
}

/// The normal coefficient of restitution of one impact:
///
/// ```text
/// e = cor·(u1n / v_ref)^(−q) − k·(u1n − v_ref) − Σᵢ cᵢ·|r − aᵢ|²      v_ref = 48.77 m/s
///   = cor·(u1n / v_ref)^(−q) − k·(u1n − v_ref) − (c·|r|² − 2·r·m − m₀)
/// ```
///
/// `cor` is the face's COR (club file `cor`, plus `cor_level`), `q` the `cor_power` exponent,
/// `k` the `cor_speed` slope; `r = (y, z)` the impact location. Each falloff `cᵢ·|r − aᵢ|²`
/// is centred on its peak `aᵢ` (`cor_radial`: the face centre; `cor_spot`: a peak of its own);
/// they add exactly when kept as `c = Σ cᵢ`, `m = Σ cᵢ·aᵢ` and `m₀ = −Σ cᵢ·|aᵢ|²`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Restitution {
    /// COR at the reference speed and the face centre.
    pub cor: f64,
    /// Power-law exponent `q` on the normal approach speed (0: off).
    pub power_q: f64,
    /// Linear slope `k` with normal approach speed, s/m.
    pub speed_k_s_per_m: f64,
    /// Falloff `c = Σ cᵢ` with squared distance, 1/m².
    pub radial_c_per_m2: f64,
    /// First moment of the falloffs' peaks, `m = Σ cᵢ·aᵢ` (y, z), 1/m (0: every peak at the
    /// face centre).
    pub radial_moment_per_m: [f64; 2],
    /// `m₀ = −Σ cᵢ·|aᵢ|²` (dimensionless; 0: every peak at the face centre).
    pub radial_offset: f64,
}

impl Restitution {
    /// The law of a model's parameters (their COR constants).
    pub fn of(p: &super::ModelParams) -> Self {
        Self {
            cor: p.cor,
            power_q: p.cor_power_q,
            speed_k_s_per_m: p.cor_speed_k_s_per_m,
            radial_c_per_m2: p.cor_radial_c_per_m2,
            radial_moment_per_m: p.cor_radial_moment_per_m,
            radial_offset: p.cor_radial_offset,
        }
    }

    /// `e` for normal approach speed `u1n_m_s` at the impact location `(y_m, z_m)`.
    #[inline(always)]
    pub fn cor<R: Real>(&self, u1n_m_s: R, y_m: R, z_m: R) -> R {
        if self.power_q == 0.0 {
            self.cor_with::<R, false>(u1n_m_s, y_m, z_m)
        } else {
            self.cor_with::<R, true>(u1n_m_s, y_m, z_m)
        }
    }

    /// [`Restitution::cor`] with the power term switched at compile time: `POWER` must be
    /// `self.power_q != 0.0` (with `q = 0` both give the same bits, since `x^0 = 1` exactly).
    /// Inner loops use it so that the common case carries no `pow` call.
    #[inline(always)]
    pub fn cor_with<R: Real, const POWER: bool>(&self, u1n_m_s: R, y_m: R, z_m: R) -> R {
        let base = if POWER {
            (u1n_m_s / COR_REFERENCE_SPEED_M_S).powf(-self.power_q) * self.cor
        } else {
            R::splat(self.cor)
        };
        let [my, mz] = self.radial_moment_per_m;
        // With every peak at the centre (m = 0, m₀ = 0) the last two terms add exact zeros.
        base - (u1n_m_s - COR_REFERENCE_SPEED_M_S) * self.speed_k_s_per_m
            - (y_m * y_m + z_m * z_m) * self.radial_c_per_m2
            + (y_m * my + z_m * mz) * 2.0
            + self.radial_offset
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
        let (dy, dz) = (R::splat(self.offset_y_m), R::splat(self.offset_z_m));
        self.lever_with(dy, dz, n, t_y, t_z_xz)
    }

    /// [`BallContact::lever`] with the offsets `dy`, `dz` (m) given per lane (a shot's own, set
    /// by user-defined effects); the model's offsets give its bits.
    #[inline(always)]
    pub fn lever_with<R: Real>(
        &self,
        dy: R,
        dz: R,
        n: &Vec3<R>,
        t_y: &Vec3<R>,
        t_z_xz: &[R; 2],
    ) -> Vec3<R> {
        let nr = -self.radius_m;
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
    /// The constants on lanes: every lane the model's values (a shot whose own mass and inertia
    /// user-defined effects set has its own, [`CollisionLanes`]).
    #[inline(always)]
    pub fn lanes<R: Real>(&self) -> CollisionLanes<R> {
        let [a, b, c, d, e, f] = self.club_inv_inertia;
        let s = R::splat;
        CollisionLanes {
            inv_mass_sum: s(self.inv_mass_sum),
            club_inv_inertia: [s(a), s(b), s(c), s(d), s(e), s(f)],
            ball_inv_inertia: self.ball_inv_inertia,
        }
    }

    /// `K` for lever arms `r_c` (contact from clubhead CoM) and `r_b` (contact from ball CoM).
    #[inline(always)]
    pub fn matrix<R: Real>(&self, r_c: &Vec3<R>, r_b: &Vec3<R>) -> Sym3<R> {
        self.lanes::<R>().matrix(r_c, r_b)
    }
}

/// [`CollisionMatrix`] with the clubhead's mass and inertia given per lane: a shot's own, when
/// user-defined effects (or `shaft_fraction`) set them shot by shot. A lane holding the model's
/// values gives the model's bits (`x·splat(c)` is `x·c`).
#[derive(Debug, Clone, Copy)]
pub struct CollisionLanes<R> {
    /// `1/m_c + 1/m_b`, 1/kg.
    pub inv_mass_sum: R,
    /// Symmetrised inverse clubhead inertia in F, `[xx, xy, xz, yy, yz, zz]`, 1/(kg·m²).
    pub club_inv_inertia: [R; 6],
    /// `1/I_b`, 1/(kg·m²).
    pub ball_inv_inertia: f64,
}

impl<R: Real> CollisionLanes<R> {
    /// `K` for lever arms `r_c` (contact from clubhead CoM) and `r_b` (contact from ball CoM).
    #[inline(always)]
    pub fn matrix(&self, r_c: &Vec3<R>, r_b: &Vec3<R>) -> Sym3<R> {
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

/// The tangential law with the impact's COR `e`: the instantaneous law a finite contact wraps
/// (a type rather than a closure so that it is always inlined, see [`InstantLaw`]). `FRICTION`
/// must be `law.mu.is_some()`.
pub struct LawWithCor<'a, R, const FRICTION: bool> {
    /// The law.
    pub law: &'a TangentialLaw,
    /// The COR.
    pub e: R,
}

impl<R: Real, const FRICTION: bool> InstantLaw<R> for LawWithCor<'_, R, FRICTION> {
    #[inline(always)]
    fn impulse(&self, k: &Sym3<R>, n: &Vec3<R>, u: &Vec3<R>, un: R) -> (Vec3<R>, R::Mask) {
        self.law.impulse::<R, FRICTION>(k, n, u, un, self.e)
    }
}

/// The tangential law with the impact's COR `e` and the `e_t` and `mu` user-defined effects
/// set per lane (`tangential_compliance`'s rise with the incidence added to that `e_t`): the
/// instantaneous law of an impact with user-defined contact terms. `FRICTION` must be
/// `law.mu.is_some()` or a term sets `mu`.
pub struct LawWithUser<'a, R, const FRICTION: bool> {
    /// The law (its `e_t_slope` and `e_g`).
    pub law: &'a TangentialLaw,
    /// The COR.
    pub e: R,
    /// Tangential restitution before the incidence rise.
    pub e_t: R,
    /// Friction coefficient (infinite: none).
    pub mu: R,
}

impl<R: Real, const FRICTION: bool> InstantLaw<R> for LawWithUser<'_, R, FRICTION> {
    #[inline(always)]
    fn impulse(&self, k: &Sym3<R>, n: &Vec3<R>, u: &Vec3<R>, un: R) -> (Vec3<R>, R::Mask) {
        let law = self.law;
        let e_t = if law.e_t_slope == 0.0 {
            self.e_t
        } else {
            tangential_speed(u, n, un) / un * law.e_t_slope + self.e_t
        };
        TangentialLaw::impulse_with::<R, FRICTION>(k, n, u, un, self.e, e_t, law.e_g, self.mu)
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
            radial_moment_per_m: [0.3, -0.45],
            radial_offset: -150.0 * (0.002f64.powi(2) + 0.003f64.powi(2)),
        };
        let u = [40.0, 45.5, 48.77, 52.0];
        let y = [0.0, 0.01, -0.02, 0.003];
        let z = [0.0, -0.005, 0.01, 0.009];
        let v = law.cor(V(u), V(y), V(z));
        for i in 0..4 {
            assert_eq!(v.0[i].to_bits(), law.cor(u[i], y[i], z[i]).to_bits());
        }
        // At the reference speed and the peak (2, −3) mm the COR is the face's own.
        assert!((law.cor(48.77, 0.002, -0.003) - 0.83).abs() < 1e-15);
        // 5 mm from the peak it has fallen by c·r².
        let off = law.cor(48.77, 0.002 + 0.003, -0.003 - 0.004);
        assert!((off - (0.83 - 150.0 * 25e-6)).abs() < 1e-15);
    }

    #[test]
    fn power_law_matches_its_formula() {
        let law = Restitution {
            cor: 0.8,
            power_q: 0.2,
            speed_k_s_per_m: 0.0,
            radial_c_per_m2: 0.0,
            radial_moment_per_m: [0.0; 2],
            radial_offset: 0.0,
        };
        let e = law.cor(2.0 * 48.77, 0.0, 0.0);
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
