//! The impact with user-defined effects (`crate::effects::user`): each shot's mass and geometry
//! from the effects' pre-solve terms ([`ImpactModel::shot`]), then the contact with their `cor`,
//! `et` and `mu`, one shot at a time.

use nalgebra::{Matrix3, Vector3};

use super::{FaceOutcome, ImpactError, ImpactModel, ImpactOutcome, ModelParams};
use crate::physics::delivery::{face_orientation, Delivery};
use crate::physics::laws::{self, Laws};
use crate::physics::user_terms as user;

/// The base values of the pre-solve quantities for a model with parameters `p` and delivery
/// `d` (file units).
pub fn pre_solve_base(p: &ModelParams, d: &Delivery) -> user::PreSolve {
    user::PreSolve {
        club_mass_g: p.club_mass_kg * 1e3,
        ball_d_mm: [p.ball_offset_y_m * 1e3, p.ball_offset_z_m * 1e3],
        com_d_mm: [0.0; 3],
        inertia_scale: 1.0,
        loft_deg: (d.dynamic_loft_rad + p.loft_bias_rad).to_degrees(),
        face_deg: (d.face_angle_rad + p.face_bias_rad).to_degrees(),
    }
}

/// An [`ImpactModel`] for one delivery, with its user-defined mass and geometry applied
/// ([`ImpactModel::shot`]).
#[derive(Debug, Clone, Copy)]
pub struct ShotModel {
    /// The laws with the shot's mass, inertia and ball offsets.
    pub laws: Laws,
    /// Face orientation `R_GF` with the shot's loft and face angle.
    pub r_gf: Matrix3<f64>,
    /// Clubhead CoM, F, m.
    pub club_com_m: Vector3<f64>,
    /// Clubhead mass, kg.
    pub club_mass_kg: f64,
    /// Inverse clubhead inertia, F, 1/(kg·m²).
    pub club_inv_inertia: Matrix3<f64>,
}

impl ImpactModel {
    /// [`ImpactModel::solve`] with user-defined effects: the shot's mass and geometry, then the
    /// impact with the user-defined `cor`, `et` and `mu`.
    pub(super) fn solve_user(&self, d: &Delivery) -> Result<ImpactOutcome, ImpactError> {
        if !self.laws.user.has_pre_solve() {
            let r_gf = self.face_orientation(d);
            return self.solve_with(
                d,
                &self.laws,
                r_gf,
                &self.params.club_com_m,
                self.params.club_mass_kg,
                &self.club_inv_inertia,
            );
        }
        let s = self.shot(d)?;
        self.solve_with(
            d,
            &s.laws,
            s.r_gf,
            &s.club_com_m,
            s.club_mass_kg,
            &s.club_inv_inertia,
        )
    }

    /// The model for one delivery with its user-defined mass and geometry evaluated
    /// ([`crate::physics::user_terms::UserTerms::pre_solve`]). A quantity no term changed keeps the
    /// model's own value, bit for bit.
    pub fn shot(&self, d: &Delivery) -> Result<ShotModel, ImpactError> {
        let p = &self.params;
        let base = pre_solve_base(p, d);
        let pre = self.laws.user.pre_solve(&user::delivery_vars(d), base)?;
        let mut s = ShotModel {
            laws: self.laws,
            r_gf: self.face_orientation(d),
            club_com_m: p.club_com_m,
            club_mass_kg: p.club_mass_kg,
            club_inv_inertia: self.club_inv_inertia,
        };
        if pre.club_mass_g != base.club_mass_g {
            s.club_mass_kg = pre.club_mass_g * 1e-3;
            s.laws.collision.inv_mass_sum = 1.0 / s.club_mass_kg + 1.0 / p.ball_mass_kg;
        }
        if pre.inertia_scale != base.inertia_scale {
            s.club_inv_inertia /= pre.inertia_scale;
            for c in &mut s.laws.collision.club_inv_inertia {
                *c /= pre.inertia_scale;
            }
        }
        if pre.com_d_mm != base.com_d_mm {
            s.club_com_m += pre.com_shift_m();
        }
        if pre.ball_d_mm != base.ball_d_mm {
            s.laws.ball.offset_y_m = pre.ball_d_mm[0] * 1e-3;
            s.laws.ball.offset_z_m = pre.ball_d_mm[1] * 1e-3;
            let offset = s.laws.ball.offset_y_m.hypot(s.laws.ball.offset_z_m);
            if !(offset < p.ball_radius_m) {
                return Err(ImpactError::UserBallOffset {
                    offset_mm: offset * 1e3,
                    radius_mm: p.ball_radius_m * 1e3,
                });
            }
        }
        if pre.loft_deg != base.loft_deg || pre.face_deg != base.face_deg {
            let loft = if pre.loft_deg != base.loft_deg {
                pre.loft_deg.to_radians()
            } else {
                d.dynamic_loft_rad + p.loft_bias_rad
            };
            let face = if pre.face_deg != base.face_deg {
                pre.face_deg.to_radians()
            } else {
                d.face_angle_rad + p.face_bias_rad
            };
            s.r_gf = face_orientation(loft, face, d.lie_tilt_rad);
        }
        Ok(s)
    }

    /// The impact with given laws, face orientation, clubhead CoM, mass and inverse inertia.
    #[inline(always)]
    fn solve_with(
        &self,
        d: &Delivery,
        laws: &Laws,
        r_gf: Matrix3<f64>,
        club_com_m: &Vector3<f64>,
        club_mass_kg: f64,
        club_inv_inertia: &Matrix3<f64>,
    ) -> Result<ImpactOutcome, ImpactError> {
        let p = &self.params;
        let r_fg = r_gf.transpose();
        let v_c_g = d.club_velocity_m_s();
        let v_c = r_fg * v_c_g;
        let w_c = r_fg * d.club_omega_rad_s;

        let cf = self.face.contact(d.impact_y_m, d.impact_z_m)?;
        let n = cf.normal;
        let r_c = cf.point_m - club_com_m;

        let u1 = v_c + w_c.cross(&r_c);
        let u1n = u1.dot(&n);
        if !(u1n > crate::limits::MIN_NORMAL_APPROACH_M_S) {
            return Err(ImpactError::NotApproaching {
                normal_speed_m_s: u1n,
            });
        }
        let arr = |v: &Vector3<f64>| [v.x, v.y, v.z];
        let mut e = laws.restitution.cor(u1n, d.impact_y_m, d.impact_z_m);
        let mut tangential = laws.tangential;
        if laws.user.has_contact() {
            let mut vars = user::delivery_vars(d);
            vars[user::VAR_U1N as usize] = u1n;
            vars[user::VAR_UT as usize] = laws::tangential_speed(&arr(&u1), &arr(&n), u1n);
            let (e_u, et_u, mu_u) = laws.user.contact_checked(
                &mut vars,
                e,
                tangential.e_t,
                tangential.mu.unwrap_or(f64::INFINITY),
            )?;
            e = e_u;
            tangential.e_t = et_u;
            if laws.user.sets_mu() {
                tangential.mu = Some(mu_u);
            }
        }
        // z_I = (−z, 0, X)/ρ: its y component is exactly 0.
        let r_b_arr = laws.ball.lever(
            &arr(&n),
            &arr(&cf.tangent_y),
            &[cf.tangent_z.x, cf.tangent_z.z],
        );
        let geometry = laws::ContactGeometry {
            normal: arr(&n),
            tangent_y: arr(&cf.tangent_y),
            tangent_z_xz: [cf.tangent_z.x, cf.tangent_z.z],
            r_c: arr(&r_c),
            r_b: r_b_arr,
            u1: arr(&u1),
            u1n,
            w_c: arr(&w_c),
        };
        let (collision, radius) = (&laws.collision, laws.ball.radius_m);
        let fi = if tangential.mu.is_some() {
            laws.contact.impact(
                |k: &laws::Sym3<f64>, n: &[f64; 3], u: &[f64; 3], un: f64| {
                    tangential.impulse::<f64, true>(k, n, u, un, e)
                },
                collision,
                radius,
                &geometry,
            )
        } else {
            laws.contact.impact(
                |k: &laws::Sym3<f64>, n: &[f64; 3], u: &[f64; 3], un: f64| {
                    tangential.impulse::<f64, false>(k, n, u, un, e)
                },
                collision,
                radius,
                &geometry,
            )
        };
        let (impulse, ball_ang, slipped) = (fi.impulse, fi.ball_angular_impulse, fi.slipped);
        let (r_c, r_b) = (Vector3::from(fi.r_c), Vector3::from(fi.r_b));
        let impulse = Vector3::from(impulse);

        let (v_b, w_b) = super::ball_response(
            p.ball_mass_kg,
            laws.collision.ball_inv_inertia,
            &fi.impulse,
            &ball_ang,
        );
        FaceOutcome {
            ball_velocity_m_s: Vector3::from(v_b),
            ball_spin_rad_s: Vector3::from(w_b),
            club_velocity_after_m_s: v_c - impulse / club_mass_kg,
            club_omega_after_rad_s: w_c - club_inv_inertia * r_c.cross(&impulse),
            impulse_n_s: impulse,
            contact_from_club_com_m: r_c,
            contact_from_ball_com_m: r_b,
            normal: n,
            normal_approach_speed_m_s: u1n,
            cor_effective: e,
            slipped,
            club_speed_m_s: d.club_speed_m_s,
        }
        .into_ground(&r_gf)
    }
}
