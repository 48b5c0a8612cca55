//! The finite contact (`contact_time`): the head's turning and the ball's travel over the face
//! while the impulse is delivered, to first order in the contact time. See [`FiniteContact`].

use super::{cross, dot, sym_mul, CollisionLanes, Real, Sym3, Vec3};
use crate::lanes::each3;

/// The instantaneous law [`FiniteContact::impact`] wraps: the impulse on the ball (and whether
/// friction limited it) for a collision matrix `k`, a unit normal `n`, an approach velocity `u`
/// and its normal part `un`. A closure of that signature is one; the model's own law is a type
/// whose method is always inlined, so that on the lanes it is compiled with the caller's
/// instruction set (a closure called twice may be kept out of line).
pub trait InstantLaw<R: Real> {
    /// The impulse and the slip mask.
    fn impulse(&self, k: &Sym3<R>, n: &Vec3<R>, u: &Vec3<R>, un: R) -> (Vec3<R>, R::Mask);
}

impl<R: Real, F: Fn(&Sym3<R>, &Vec3<R>, &Vec3<R>, R) -> (Vec3<R>, R::Mask)> InstantLaw<R> for F {
    #[inline(always)]
    fn impulse(&self, k: &Sym3<R>, n: &Vec3<R>, u: &Vec3<R>, un: R) -> (Vec3<R>, R::Mask) {
        self(k, n, u, un)
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

impl<R: Real> FiniteImpact<R> {
    /// The instantaneous impact (`τ = 0`): the law's impulse `p` (and whether it slipped) at the
    /// first contact, levers `r_c` (head) and `r_b` (ball) unmoved.
    #[inline(always)]
    pub fn at_first_contact(p: Vec3<R>, slipped: R::Mask, r_c: Vec3<R>, r_b: Vec3<R>) -> Self {
        FiniteImpact {
            impulse: p,
            ball_angular_impulse: cross(&r_b, &p),
            slipped,
            r_c,
            r_b,
        }
    }
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
        law: impl InstantLaw<R>,
        collision: &CollisionLanes<R>,
        radius_m: f64,
        g: &ContactGeometry<R>,
    ) -> FiniteImpact<R> {
        let n = &g.normal;
        let k = collision.matrix(&g.r_c, &g.r_b);
        let (p, slip) = law.impulse(&k, n, &g.u1, g.u1n);
        if self.tau_s == 0.0 {
            return FiniteImpact::at_first_contact(p, slip, g.r_c, g.r_b);
        }
        let dw = sym_mul(&collision.club_inv_inertia, &cross(&g.r_c, &p));
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
        let (pf, slip) = law.impulse(&k, &n, &u1r, u1nr);
        let lf = cross(&r_b, &pf);
        FiniteImpact {
            impulse: turned(&theta, &pf),
            ball_angular_impulse: turned(&theta, &lf),
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
        inv_mass_sum: R,
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
        let f: Vec3<R> = each3(|i| g.u1[i] * a - (p[i] * inv_mass_sum + wr[i]) * b);
        let fn_ = dot(&f, n);
        let d: Vec3<R> = each3(|i| fn_ * n[i] - f[i]);
        // Tilt of the normal over d on the face's curvature.
        let [tzx, tzz] = g.tangent_z_xz;
        let ty = &g.tangent_y;
        let cy = (d[0] * ty[0] + d[1] * ty[1] + d[2] * ty[2]) * self.roll_curvature_per_m;
        let cz = (d[0] * tzx + d[2] * tzz) * self.bulge_curvature_per_m;
        let dn = [ty[0] * cy + tzx * cz, ty[1] * cy, ty[2] * cy + tzz * cz];
        let m = [n[0] + dn[0], n[1] + dn[1], n[2] + dn[2]];
        let inv = R::splat(1.0) / dot(&m, &m).sqrt();
        let n2 = each3(|i| m[i] * inv);
        // The ball's lever: the radius along the new normal, its offset turned by φ = n × dn.
        let o: Vec3<R> = each3(|i| g.r_b[i] + n[i] * radius_m);
        let po = cross(&cross(n, &dn), &o);
        let r_b: Vec3<R> = each3(|i| o[i] + po[i] - n2[i] * radius_m);
        let r_c: Vec3<R> = each3(|i| g.r_c[i] + d[i]);
        let wd = cross(&g.w_c, &d);
        let u1: Vec3<R> = each3(|i| g.u1[i] + wd[i]);
        (r_c, r_b, n2, u1)
    }
}

/// `v` turned by the small angle `theta`: `v + θ×v`.
#[inline(always)]
fn turned<R: Real>(theta: &Vec3<R>, v: &Vec3<R>) -> Vec3<R> {
    let t = cross(theta, v);
    [v[0] + t[0], v[1] + t[1], v[2] + t[2]]
}
