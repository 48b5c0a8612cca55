//! The contact mechanics of an impact, in the face frame `F`, on one shot (`R = f64`) or on
//! lanes of shots: lever arms, approach velocity, COR (with user-defined `cor`, `et`, `mu`),
//! collision matrix, impulse, and the ball's velocity and spin. The one definition the scalar
//! solve ([`ImpactModel::solve_in`], [`ImpactModel::solve`] with user-defined effects) and the
//! fits' lanes run.

use nalgebra::Vector3;

use super::{ball_response, cross, DeliveryFrame, ImpactModel, Real, ShotConsts, Vec3};
use crate::physics::face::ContactFrame;
use crate::physics::laws::{
    tangential_speed, ContactGeometry, FiniteImpact, InstantLaw, LawWithUser,
};
use crate::physics::user_terms::{NV, VAR_U1N, VAR_UT};

/// What [`ImpactModel::solve_contact`] needs of one impact (or of each lane of impacts), all in
/// the face frame `F`: the delivery frame's clubhead velocities and the contact frame at the
/// impact location `(y_m, z_m)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactInputs<R> {
    /// Clubhead CoM velocity, m/s.
    pub club_velocity_f_m_s: Vec3<R>,
    /// Clubhead angular velocity, rad/s.
    pub club_omega_f_rad_s: Vec3<R>,
    /// Contact point relative to the centre of face, m.
    pub point_m: Vec3<R>,
    /// Unit face normal `x_I`.
    pub normal: Vec3<R>,
    /// Unit tangent `y_I`.
    pub tangent_y: Vec3<R>,
    /// The `x` and `z` components of the tangent `z_I` (its `y` component is 0).
    pub tangent_z_xz: [R; 2],
    /// Impact location up the face, m.
    pub y_m: R,
    /// Impact location toward the toe, m.
    pub z_m: R,
}

impl ContactInputs<f64> {
    /// One impact's inputs: the delivery frame's clubhead velocities and the contact frame `cf`
    /// at the impact location `(y_m, z_m)` (what the scalar solves hand the contact solve).
    pub fn of(frame: &DeliveryFrame, cf: &ContactFrame, y_m: f64, z_m: f64) -> Self {
        let arr = |v: &Vector3<f64>| [v.x, v.y, v.z];
        Self {
            club_velocity_f_m_s: arr(&frame.club_velocity_f_m_s),
            club_omega_f_rad_s: arr(&frame.club_omega_f_rad_s),
            point_m: arr(&cf.point_m),
            normal: arr(&cf.normal),
            tangent_y: arr(&cf.tangent_y),
            tangent_z_xz: [cf.tangent_z.x, cf.tangent_z.z],
            y_m,
            z_m,
        }
    }
}

/// Whether a COR `e` is one a collision can have, lane by lane: in (0, 1]. A library law can
/// leave that range at some deliveries (`cor_power` at a slow club speed, `cor_radial` far from
/// the centre); every path that solves an impact refuses it there.
#[inline(always)]
pub fn cor_allowed<R: Real>(e: R) -> R::Mask {
    e.gt(R::splat(0.0)) & !e.gt(R::splat(1.0))
}

/// The contact mechanics of [`ImpactModel::solve_contact`], face frame `F`, SI units.
#[derive(Debug, Clone, Copy)]
pub struct ContactSolution<R: Real> {
    /// Where the impulse acts relative to the clubhead CoM, m (the impact location's point on the
    /// face, moved by the ball's travel over it during a finite contact, `contact_time`).
    pub contact_from_club_com_m: Vec3<R>,
    /// Where the impulse acts relative to the ball CoM, m.
    pub contact_from_ball_com_m: Vec3<R>,
    /// Normal approach speed `u1·n`, m/s (the impact is valid only where it is > 0).
    pub normal_approach_speed_m_s: R,
    /// Normal COR used.
    pub cor_effective: R,
    /// Whether that COR is one a collision can have ([`cor_allowed`]).
    pub cor_allowed: R::Mask,
    /// Impulse on the ball, N·s.
    pub impulse_n_s: Vec3<R>,
    /// Whether friction limited the tangential impulse.
    pub slipped: R::Mask,
    /// Ball CoM velocity after impact, m/s.
    pub ball_velocity_f_m_s: Vec3<R>,
    /// Ball angular velocity after impact, rad/s.
    pub ball_spin_f_rad_s: Vec3<R>,
}

impl ImpactModel {
    /// The contact mechanics of an impact in the face frame `F`, on one shot (`R = f64`, inside
    /// [`ImpactModel::solve_in`]) or on lanes of shots (`R = V`, the fits' batched evaluation):
    /// lever arms, approach velocity, COR, collision matrix, impulse, and the ball's velocity
    /// and spin in `F`. The one definition both paths use. It does not check that the club
    /// approaches the ball (`normal_approach_speed_m_s` above
    /// [`crate::limits::MIN_NORMAL_APPROACH_M_S`]) or that the result is finite: the caller does.
    #[inline(always)]
    pub fn solve_contact<R: Real>(&self, x: &ContactInputs<R>) -> ContactSolution<R> {
        debug_assert!(
            !self.laws.user.has_contact(),
            "a model with user-defined contact terms solves through solve_contact_shot"
        );
        let shot = self.shot_consts::<R>();
        let (mut vars, mut valid) = ([R::splat(0.0); NV], !R::no());
        self.solve_contact_shot(x, &shot, &mut vars, &mut valid)
    }

    /// [`ImpactModel::solve_contact`] of shots with constants of their own (`shot`:
    /// [`ImpactModel::shot_consts_of`]) and with the model's user-defined `cor`, `et` and `mu`
    /// terms evaluated on `vars` (each lane's delivery variables at its impact location; the
    /// approach speeds are written here). Lanes whose user-defined values are not allowed are
    /// cleared from `valid`. The one definition of an impact's contact mechanics, on one shot
    /// and on the lanes, with or without user-defined effects.
    #[inline(always)]
    pub fn solve_contact_shot<R: Real>(
        &self,
        x: &ContactInputs<R>,
        shot: &ShotConsts<R>,
        vars: &mut [R; NV],
        valid: &mut R::Mask,
    ) -> ContactSolution<R> {
        let friction = self.laws.tangential.mu.is_some() || self.laws.user.sets_mu();
        if friction {
            self.solve_contact_with::<R, true>(x, shot, vars, valid)
        } else {
            self.solve_contact_with::<R, false>(x, shot, vars, valid)
        }
    }

    /// The contact solve; `FRICTION` is whether a friction limit applies (the model's or a
    /// user-defined `mu`).
    #[inline(always)]
    fn solve_contact_with<R: Real, const FRICTION: bool>(
        &self,
        x: &ContactInputs<R>,
        shot: &ShotConsts<R>,
        vars: &mut [R; NV],
        valid: &mut R::Mask,
    ) -> ContactSolution<R> {
        let p = &self.params;
        let com = &shot.club_com_m;
        let r_c = [
            x.point_m[0] - com[0],
            x.point_m[1] - com[1],
            x.point_m[2] - com[2],
        ];
        let wr = cross(&x.club_omega_f_rad_s, &r_c);
        let v_c = &x.club_velocity_f_m_s;
        let u1 = [v_c[0] + wr[0], v_c[1] + wr[1], v_c[2] + wr[2]];
        let n = &x.normal;
        let u1n = u1[0] * n[0] + u1[1] * n[1] + u1[2] * n[2];
        let laws = &self.laws;
        let mut e = laws.restitution.cor(u1n, x.y_m, x.z_m);
        let mut e_t = R::splat(laws.tangential.e_t);
        let mut mu = R::splat(laws.tangential.mu.unwrap_or(f64::INFINITY));
        if laws.user.has_contact() {
            vars[VAR_U1N as usize] = u1n;
            vars[VAR_UT as usize] = tangential_speed(&u1, n, u1n);
            (e, e_t, mu) = laws.user.contact(vars, [e, e_t, mu], valid);
        }
        // z_I = (−z, 0, X)/ρ: its y component is exactly 0.
        let [dy, dz] = shot.ball_offset_m;
        let r_b = laws
            .ball
            .lever_with(dy, dz, n, &x.tangent_y, &x.tangent_z_xz);
        let collision = &shot.collision;
        // The tangential law with this impact's e, e_t and mu (without user-defined terms the
        // law's own, the same operations as `TangentialLaw::impulse`).
        let law = LawWithUser::<R, FRICTION> {
            law: &laws.tangential,
            e,
            e_t,
            mu,
        };
        // The instantaneous law, wrapped by the finite contact (`contact_time`; with τ = 0 it is
        // the law itself at the first contact, bit for bit).
        let fi = if laws.contact.tau_s == 0.0 {
            // What `FiniteContact::impact` returns for τ = 0, the same operations, written out
            // so that the tangential law is inlined here.
            let k = collision.matrix(&r_c, &r_b);
            let (impulse, slipped) = law.impulse(&k, n, &u1, u1n);
            FiniteImpact::at_first_contact(impulse, slipped, r_c, r_b)
        } else {
            let geometry = ContactGeometry {
                normal: *n,
                tangent_y: x.tangent_y,
                tangent_z_xz: x.tangent_z_xz,
                r_c,
                r_b,
                u1,
                u1n,
                w_c: x.club_omega_f_rad_s,
            };
            laws.contact
                .impact(law, collision, laws.ball.radius_m, &geometry)
        };
        let (impulse, ball_angular_impulse, slipped) =
            (fi.impulse, fi.ball_angular_impulse, fi.slipped);
        let (v_b, w_b) = ball_response(
            p.ball_mass_kg,
            laws.collision.ball_inv_inertia,
            &impulse,
            &ball_angular_impulse,
        );
        ContactSolution {
            cor_allowed: cor_allowed(e),
            contact_from_club_com_m: fi.r_c,
            contact_from_ball_com_m: fi.r_b,
            normal_approach_speed_m_s: u1n,
            cor_effective: e,
            impulse_n_s: impulse,
            slipped,
            ball_velocity_f_m_s: v_b,
            ball_spin_f_rad_s: w_b,
        }
    }
}
