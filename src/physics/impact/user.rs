//! The impact with user-defined effects (`crate::effects::user`): each shot's mass and geometry
//! from the effects' pre-solve terms ([`ImpactModel::shot`]), then the contact with their `cor`,
//! `et` and `mu`, one shot at a time.

use nalgebra::{Matrix3, Vector3};

use super::{
    ContactInputs, DeliveryFrame, FaceOutcome, ImpactError, ImpactModel, ImpactOutcome,
    ModelParams, ShotConsts,
};
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
    /// The shot's constants of the contact solve.
    pub consts: ShotConsts<f64>,
}

impl ImpactModel {
    /// [`ImpactModel::solve`] with user-defined effects: the shot's mass and geometry, then the
    /// impact with the user-defined `cor`, `et` and `mu`, through the contact solve the fits'
    /// lanes run ([`ImpactModel::solve_contact_shot`]), so both give the same bits.
    pub(super) fn solve_user(&self, d: &Delivery) -> Result<ImpactOutcome, ImpactError> {
        let s = self.shot(d)?;
        let frame = if self.laws.user.sets_orientation() {
            let r_fg = s.r_gf.transpose();
            DeliveryFrame {
                r_gf: s.r_gf,
                club_velocity_f_m_s: r_fg * d.club_velocity_m_s(),
                club_omega_f_rad_s: r_fg * d.club_omega_rad_s,
                ..self.delivery_frame(d)
            }
        } else {
            self.delivery_frame(d)
        };
        let cf = self.face.contact(d.impact_y_m, d.impact_z_m)?;
        let arr = |v: &Vector3<f64>| [v.x, v.y, v.z];
        let (v_c, w_c) = (frame.club_velocity_f_m_s, frame.club_omega_f_rad_s);
        let x = ContactInputs::of(&frame, &cf, d.impact_y_m, d.impact_z_m);
        let mut vars = user::delivery_vars(d);
        let mut valid = true;
        let sol = self.solve_contact_shot(&x, &s.consts, &mut vars, &mut valid);
        let u1n = sol.normal_approach_speed_m_s;
        if !(u1n > crate::limits::MIN_NORMAL_APPROACH_M_S) {
            return Err(ImpactError::NotApproaching {
                normal_speed_m_s: u1n,
            });
        }
        if !valid {
            // The same evaluation again, to name the term whose value is not allowed.
            let mut vars = user::delivery_vars(d);
            vars[user::VAR_U1N as usize] = u1n;
            vars[user::VAR_UT as usize] =
                laws::tangential_speed(&arr(&x_u1(&x, &s)), &x.normal, u1n);
            let t = &self.laws.tangential;
            let e = self.laws.restitution.cor(u1n, d.impact_y_m, d.impact_z_m);
            self.laws
                .user
                .contact_checked(&mut vars, e, t.e_t, t.mu.unwrap_or(f64::INFINITY))?;
            return Err(ImpactError::NonFinite);
        }
        if !sol.cor_allowed {
            return Err(ImpactError::CorOutOfRange {
                cor: sol.cor_effective,
            });
        }
        let impulse = Vector3::from(sol.impulse_n_s);
        let r_c = Vector3::from(sol.contact_from_club_com_m);
        FaceOutcome {
            ball_velocity_m_s: Vector3::from(sol.ball_velocity_f_m_s),
            ball_spin_rad_s: Vector3::from(sol.ball_spin_f_rad_s),
            club_velocity_after_m_s: v_c - impulse / s.club_mass_kg,
            club_omega_after_rad_s: w_c - s.club_inv_inertia * r_c.cross(&impulse),
            impulse_n_s: impulse,
            contact_from_club_com_m: r_c,
            contact_from_ball_com_m: Vector3::from(sol.contact_from_ball_com_m),
            normal: cf.normal,
            normal_approach_speed_m_s: u1n,
            cor_effective: sol.cor_effective,
            slipped: sol.slipped,
            club_speed_m_s: d.club_speed_m_s,
        }
        .into_ground(&frame.r_gf)
    }

    /// The model for one delivery with its user-defined mass and geometry evaluated
    /// ([`ImpactModel::shot_consts_of`], the lanes' own definition, and the loft and face
    /// terms). A quantity no term changed keeps the model's own value, bit for bit.
    pub fn shot(&self, d: &Delivery) -> Result<ShotModel, ImpactError> {
        let p = &self.params;
        let mut vars = user::delivery_vars(d);
        let mut valid = true;
        let consts = self.shot_consts_of::<f64>(&mut vars, &mut valid);
        let base = pre_solve_base(p, d);
        if !valid {
            // Name the cause: a term's value, or the ball offset.
            self.laws.user.pre_solve(&user::delivery_vars(d), base)?;
            let [oy, oz] = consts.ball_offset_m;
            return Err(ImpactError::UserBallOffset {
                offset_mm: oy.hypot(oz) * 1e3,
                radius_mm: p.ball_radius_m * 1e3,
            });
        }
        let mut s = ShotModel {
            laws: self.laws,
            r_gf: self.face_orientation(d),
            club_com_m: Vector3::from(consts.club_com_m),
            club_mass_kg: consts.club_mass_kg,
            club_inv_inertia: self.club_inv_inertia,
            consts,
        };
        s.laws.collision.inv_mass_sum = consts.collision.inv_mass_sum;
        s.laws.collision.club_inv_inertia = consts.collision.club_inv_inertia;
        [s.laws.ball.offset_y_m, s.laws.ball.offset_z_m] = consts.ball_offset_m;
        if !self.laws.user.has_pre_solve() {
            return Ok(s);
        }
        let pre = self.laws.user.pre_solve(&user::delivery_vars(d), base)?;
        if pre.inertia_scale != base.inertia_scale {
            s.club_inv_inertia /= pre.inertia_scale;
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
}

/// The approach velocity `u1 = v_c + ω_c × r_c` of one shot at its contact point (for the
/// message of a user-defined term whose value is not allowed).
fn x_u1(x: &ContactInputs<f64>, s: &ShotModel) -> Vector3<f64> {
    let r_c = Vector3::from(x.point_m) - s.club_com_m;
    Vector3::from(x.club_velocity_f_m_s) + Vector3::from(x.club_omega_f_rad_s).cross(&r_c)
}
