//! The impulse–momentum impact between clubhead and ball, reduced to one 3×3 solve.
//!
//! With the contact point relative to the clubhead CoM `r_c = p − r_C/CoF`, relative to the ball
//! CoM `r_b = −radius·x_I + dy·y_I + dz·z_I`, and `[a]×` the cross-product matrix:
//!
//! ```text
//! K   = (1/m_c + 1/m_b)·1 − [r_c]× I_c⁻¹ [r_c]× − [r_b]× I_b⁻¹ [r_b]×
//! u1  = v_c + ω_c × r_c               contact-point velocity of club minus ball, before
//! u1n = u1·n > 0                      (the club approaches the ball)
//! K P = u1 + e·u1n·n + e_t·(u1 − u1n·n)
//! v_b = P/m_b,  ω_b = I_b⁻¹(r_b × P),  v_c' = v_c − P/m_c,  ω_c' = ω_c − I_c⁻¹(r_c × P)
//! ```
//!
//! This is the paper's Eqs. 1–9 (impulse and momentum for club and ball, restitution along the
//! normal, no slip along the face when `e_t = 0`). Optional extensions, all off by default:
//! a tangential restitution `e_t`; Coulomb friction `mu` (gross slip when the no-slip tangential
//! impulse exceeds `mu·P_n`); a COR falling with normal approach speed,
//! `e = cor − k·(u1n − 48.77 m/s)`; a COR falling with distance from the face centre,
//! `e = cor − c·(y² + z²)`; and loft and face-angle biases added to the delivered angles.
//!
//! The solve is done in the face frame `F`, where the clubhead inertia is constant, and the
//! results are rotated to the ground frame `G`.

use nalgebra::{Matrix3, Vector3};

use super::delivery::{face_orientation, Delivery, FrameTrig};
use super::face::{ContactFrame, FaceError, FaceGeometry};
use super::launch::Launch;
use super::laws::{
    BallContact, CollisionMatrix, FiniteContact, Laws, Real, Restitution, TangentialLaw, Vec3,
};
pub use super::params::{validate_inertia, ModelParams, ParamError, DRIVER_HOSEL_MM};
use super::user_terms::UserEvalError;
use crate::lanes::each3;

mod contact;
mod shot;
mod user;
pub use contact::{cor_allowed, ContactInputs, ContactSolution};
pub use shot::ShotConsts;
pub use user::{pre_solve_base, ShotModel};

/// Reference normal approach speed of the `cor_speed` effect, m/s (`docs/conventions.md`).
pub const COR_SPEED_REFERENCE_M_S: f64 = super::laws::COR_REFERENCE_SPEED_M_S;

/// Why one impact cannot be computed.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum ImpactError {
    /// The impact location is not on the face torus.
    #[error(transparent)]
    OffFace(#[from] FaceError),
    /// The clubhead's contact point does not move toward the ball along the face normal.
    #[error(
        "the club does not approach the ball: normal approach speed is {} m/s (must exceed {} \
         m/s; check club speed, attack angle, path, loft and face angle)",
        crate::limits::fmt_value(*normal_speed_m_s),
        crate::limits::fmt_value(crate::limits::MIN_NORMAL_APPROACH_M_S)
    )]
    NotApproaching {
        /// `u1·n`, m/s.
        normal_speed_m_s: f64,
    },
    /// The restitution law gives a COR no collision has at this impact.
    #[error(
        "the club's restitution law gives a COR of {} at this impact, outside (0, 1]: its COR \
         effects (cor_power, cor_speed, cor_radial, cor_spot, …) leave the range at this club \
         speed or impact location; check their values",
        crate::limits::fmt_value(*cor)
    )]
    CorOutOfRange {
        /// The COR the law gives.
        cor: f64,
    },
    /// The solve produced a non-finite number (parameters at the edge of floating point).
    #[error("the impact solve produced a non-finite result; check the club's masses, inertia and face radii")]
    NonFinite,
    /// A user-defined effect's expression gave a value its quantity does not allow.
    #[error(transparent)]
    User(#[from] UserEvalError),
    /// A user-defined effect moved the ball's contact offset out of the ball.
    #[error(
        "user-defined effects put the ball contact offset at {offset_mm} mm from the centre line, \
         beyond the ball radius {radius_mm} mm"
    )]
    UserBallOffset {
        /// |(dy, dz)|, mm.
        offset_mm: f64,
        /// Ball radius, mm.
        radius_mm: f64,
    },
}

/// A validated impact model with precomputed inverse inertias. Cheap to clone.
#[derive(Debug, Clone, PartialEq)]
pub struct ImpactModel {
    params: ModelParams,
    face: FaceGeometry,
    club_inv_inertia: Matrix3<f64>,
    inv_mass_sum: f64,
    laws: Laws,
}

/// What an impact needs from a delivery apart from the impact location, for one pair of loft and
/// face biases (see [`ImpactModel::delivery_frame`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DeliveryFrame {
    /// Orientation `R_GF` of the face at impact (biases applied).
    pub r_gf: Matrix3<f64>,
    /// Clubhead CoM velocity in F, m/s.
    pub club_velocity_f_m_s: Vector3<f64>,
    /// Clubhead angular velocity in F, rad/s.
    pub club_omega_f_rad_s: Vector3<f64>,
    /// Clubhead CoM speed, m/s.
    pub club_speed_m_s: f64,
    /// Loft bias the frame was made with, rad.
    pub loft_bias_rad: f64,
    /// Face-angle bias the frame was made with, rad.
    pub face_bias_rad: f64,
    /// The delivery (user-defined effects read it per shot).
    pub delivery: Delivery,
}

/// Everything the impact produces, in the ground frame `G`, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactOutcome {
    /// Ball CoM velocity after impact, m/s.
    pub ball_velocity_m_s: Vector3<f64>,
    /// Ball angular velocity after impact, rad/s.
    pub ball_spin_rad_s: Vector3<f64>,
    /// Clubhead CoM velocity after impact, m/s.
    pub club_velocity_after_m_s: Vector3<f64>,
    /// Clubhead angular velocity after impact, rad/s.
    pub club_omega_after_rad_s: Vector3<f64>,
    /// Impulse on the ball, N·s.
    pub impulse_n_s: Vector3<f64>,
    /// Where the impulse acts relative to the clubhead CoM, m (the impact location's point on the
    /// face, moved by the ball's travel over it during a finite contact, `contact_time`).
    pub contact_from_club_com_m: Vector3<f64>,
    /// Where the impulse acts relative to the ball CoM, m.
    pub contact_from_ball_com_m: Vector3<f64>,
    /// Unit face normal at the contact point.
    pub normal: Vector3<f64>,
    /// Normal approach speed `u1·n`, m/s.
    pub normal_approach_speed_m_s: f64,
    /// Normal COR used for this impact (after `cor_speed` and `cor_radial`).
    pub cor_effective: f64,
    /// Whether friction limited the tangential impulse (gross slip).
    pub slipped: bool,
    /// Clubhead CoM speed before impact, m/s.
    pub club_speed_m_s: f64,
}

/// An [`ImpactOutcome`] still in the face frame `F` (the normal approach speed, COR, slip flag
/// and club speed are frame-free): what the built-in and the user-defined solves both produce.
struct FaceOutcome {
    ball_velocity_m_s: Vector3<f64>,
    ball_spin_rad_s: Vector3<f64>,
    club_velocity_after_m_s: Vector3<f64>,
    club_omega_after_rad_s: Vector3<f64>,
    impulse_n_s: Vector3<f64>,
    contact_from_club_com_m: Vector3<f64>,
    contact_from_ball_com_m: Vector3<f64>,
    normal: Vector3<f64>,
    normal_approach_speed_m_s: f64,
    cor_effective: f64,
    slipped: bool,
    club_speed_m_s: f64,
}

impl FaceOutcome {
    /// Rotates the vectors to the ground frame `G` (`r_gf` maps `F` to `G`), refusing any
    /// non-finite ball or club velocity.
    fn into_ground(self, r_gf: &Matrix3<f64>) -> Result<ImpactOutcome, ImpactError> {
        let finite = |v: &Vector3<f64>| v.iter().all(|x| x.is_finite());
        let moving = [
            &self.ball_velocity_m_s,
            &self.ball_spin_rad_s,
            &self.club_velocity_after_m_s,
            &self.club_omega_after_rad_s,
        ];
        if !moving.into_iter().all(finite) {
            return Err(ImpactError::NonFinite);
        }
        Ok(ImpactOutcome {
            ball_velocity_m_s: r_gf * self.ball_velocity_m_s,
            ball_spin_rad_s: r_gf * self.ball_spin_rad_s,
            club_velocity_after_m_s: r_gf * self.club_velocity_after_m_s,
            club_omega_after_rad_s: r_gf * self.club_omega_after_rad_s,
            impulse_n_s: r_gf * self.impulse_n_s,
            contact_from_club_com_m: r_gf * self.contact_from_club_com_m,
            contact_from_ball_com_m: r_gf * self.contact_from_ball_com_m,
            normal: r_gf * self.normal,
            normal_approach_speed_m_s: self.normal_approach_speed_m_s,
            cor_effective: self.cor_effective,
            slipped: self.slipped,
            club_speed_m_s: self.club_speed_m_s,
        })
    }
}

/// `a × b`, in the component order nalgebra uses (so the scalar solve keeps its bits).
#[inline(always)]
fn cross<R: Real>(a: &Vec3<R>, b: &Vec3<R>) -> Vec3<R> {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

impl ImpactOutcome {
    /// Launch conditions of the ball.
    #[inline]
    pub fn launch(&self) -> Launch {
        Launch::from_ball_state(&self.ball_velocity_m_s, &self.ball_spin_rad_s)
    }

    /// Smash factor: ball speed over clubhead speed.
    #[inline]
    pub fn smash_factor(&self) -> f64 {
        self.ball_velocity_m_s.norm() / self.club_speed_m_s
    }
}

impl ImpactModel {
    /// Validate `params` and precompute the inverse inertia.
    pub fn new(params: ModelParams) -> Result<Self, ParamError> {
        params.validate()?;
        let p = &params;
        let face = FaceGeometry::new(p.bulge_m, p.roll_m).map_err(|e| ParamError {
            quantity: "club face",
            problem: e.to_string(),
        })?;
        let club_inv_inertia = p
            .club_inertia_kgm2
            .try_inverse()
            .ok_or_else(|| ParamError {
                quantity: "club inertia tensor",
                problem: "the tensor is singular".into(),
            })?;
        let inv_mass_sum = 1.0 / p.club_mass_kg + 1.0 / p.ball_mass_kg;
        let j = &club_inv_inertia;
        let sym = |a: usize, b: usize| 0.5 * (j[(a, b)] + j[(b, a)]);
        let laws = Laws {
            restitution: Restitution::of(p),
            ball: BallContact {
                radius_m: p.ball_radius_m,
                offset_y_m: p.ball_offset_y_m,
                offset_z_m: p.ball_offset_z_m,
            },
            collision: CollisionMatrix {
                inv_mass_sum,
                club_inv_inertia: [
                    j[(0, 0)],
                    sym(0, 1),
                    sym(0, 2),
                    j[(1, 1)],
                    sym(1, 2),
                    j[(2, 2)],
                ],
                ball_inv_inertia: 1.0 / p.ball_inertia_kgm2,
            },
            tangential: TangentialLaw {
                e_t: p.tangential_restitution,
                e_t_slope: p.tangential_restitution_slope,
                e_g: p.gear_restitution,
                mu: p.friction_mu,
            },
            contact: FiniteContact {
                tau_s: p.contact_time_s,
                bulge_curvature_per_m: 1.0 / p.bulge_m,
                roll_curvature_per_m: 1.0 / p.roll_m,
                travel: true,
            },
            user: p.user,
        };
        Ok(Self {
            params,
            face,
            club_inv_inertia,
            inv_mass_sum,
            laws,
        })
    }

    /// The same model with a finite contact (`contact_time`) that turns the head but leaves out
    /// the ball's travel over the face ([`FiniteContact`]): the first-order law before the
    /// travel was derived, kept to measure what the travel adds (`tests/contact_world.rs`).
    pub fn without_travel(mut self) -> Self {
        self.laws.contact.travel = false;
        self
    }

    /// The validated parameters.
    pub fn params(&self) -> &ModelParams {
        &self.params
    }

    /// The model's laws (restitution, ball lever arm, collision matrix, tangential law), for
    /// evaluation on one shot or on lanes of many.
    pub fn laws(&self) -> &Laws {
        &self.laws
    }

    /// The face geometry.
    pub fn face(&self) -> &FaceGeometry {
        &self.face
    }

    /// Inverse clubhead inertia in F, 1/(kg·m²).
    pub fn club_inv_inertia(&self) -> &Matrix3<f64> {
        &self.club_inv_inertia
    }

    /// Orientation `R_GF` of the face at impact, with the loft and face biases applied.
    #[inline]
    pub fn face_orientation(&self, d: &Delivery) -> Matrix3<f64> {
        face_orientation(
            d.dynamic_loft_rad + self.params.loft_bias_rad,
            d.face_angle_rad + self.params.face_bias_rad,
            d.lie_tilt_rad,
        )
    }

    /// The delivery's part of an impact that does not depend on where the ball meets the face:
    /// the face orientation (with this model's loft and face biases) and the clubhead's
    /// velocities in the face frame. A fit computes it once per shot (and per bias) and reuses
    /// it for every evaluation and every impact-location node ([`ImpactModel::solve_in`]).
    #[inline]
    pub fn delivery_frame(&self, d: &Delivery) -> DeliveryFrame {
        let p = &self.params;
        self.delivery_frame_of(d, &d.frame_trig(p.loft_bias_rad, p.face_bias_rad))
    }

    /// [`ImpactModel::delivery_frame`] from the trigonometry `trig` of the delivery `d` made for
    /// any biases ([`Delivery::frame_trig`]): only what this model's biases change is computed
    /// again. The same bits as [`ImpactModel::delivery_frame`].
    #[inline]
    pub fn delivery_frame_from(&self, d: &Delivery, trig: &FrameTrig) -> DeliveryFrame {
        let p = &self.params;
        self.delivery_frame_of(
            d,
            &d.frame_trig_from(trig, p.loft_bias_rad, p.face_bias_rad),
        )
    }

    /// The delivery frame of `d` from its trigonometry for this model's biases.
    #[inline]
    fn delivery_frame_of(&self, d: &Delivery, trig: &FrameTrig) -> DeliveryFrame {
        let r_gf = trig.face_orientation();
        let r_fg = r_gf.transpose();
        let v_c_g = trig.club_velocity_m_s;
        DeliveryFrame {
            r_gf,
            club_velocity_f_m_s: r_fg * v_c_g,
            club_omega_f_rad_s: r_fg * d.club_omega_rad_s,
            club_speed_m_s: d.club_speed_m_s,
            loft_bias_rad: self.params.loft_bias_rad,
            face_bias_rad: self.params.face_bias_rad,
            delivery: *d,
        }
    }

    /// Solve one impact.
    #[inline]
    pub fn solve(&self, d: &Delivery) -> Result<ImpactOutcome, ImpactError> {
        if !self.laws.user.is_empty() {
            return self.solve_user(d);
        }
        let frame = self.delivery_frame(d);
        let cf = self.face.contact(d.impact_y_m, d.impact_z_m)?;
        self.solve_in(&frame, &cf, d.impact_y_m, d.impact_z_m)
    }

    /// Solve one impact from a precomputed delivery frame (made by [`ImpactModel::delivery_frame`]
    /// of a model with the same loft and face biases) and the contact frame of this model's face
    /// at the impact location `(y_m, z_m)`. [`ImpactModel::solve`] is exactly this, so both give
    /// the same bits.
    #[inline]
    pub fn solve_in(
        &self,
        frame: &DeliveryFrame,
        cf: &ContactFrame,
        y_m: f64,
        z_m: f64,
    ) -> Result<ImpactOutcome, ImpactError> {
        debug_assert!(
            frame.loft_bias_rad == self.params.loft_bias_rad
                && frame.face_bias_rad == self.params.face_bias_rad
        );
        if !self.laws.user.is_empty() {
            // User-defined effects read the whole delivery, per shot.
            return self.solve_user(&Delivery {
                impact_y_m: y_m,
                impact_z_m: z_m,
                ..frame.delivery
            });
        }
        let p = &self.params;
        let r_gf = frame.r_gf;
        let v_c = frame.club_velocity_f_m_s;
        let w_c = frame.club_omega_f_rad_s;
        let s = self.solve_contact(&ContactInputs::of(frame, cf, y_m, z_m));
        let u1n = s.normal_approach_speed_m_s;
        if !(u1n > crate::limits::MIN_NORMAL_APPROACH_M_S) {
            return Err(ImpactError::NotApproaching {
                normal_speed_m_s: u1n,
            });
        }
        if !s.cor_allowed {
            return Err(ImpactError::CorOutOfRange {
                cor: s.cor_effective,
            });
        }
        let (e, slipped) = (s.cor_effective, s.slipped);
        let n = cf.normal;
        let r_c = Vector3::from(s.contact_from_club_com_m);
        let r_b = Vector3::from(s.contact_from_ball_com_m);
        let impulse = Vector3::from(s.impulse_n_s);
        let v_b = Vector3::from(s.ball_velocity_f_m_s);
        let w_b = Vector3::from(s.ball_spin_f_rad_s);
        FaceOutcome {
            ball_velocity_m_s: v_b,
            ball_spin_rad_s: w_b,
            club_velocity_after_m_s: v_c - impulse / p.club_mass_kg,
            club_omega_after_rad_s: w_c - self.club_inv_inertia * r_c.cross(&impulse),
            impulse_n_s: impulse,
            contact_from_club_com_m: r_c,
            contact_from_ball_com_m: r_b,
            normal: n,
            normal_approach_speed_m_s: u1n,
            cor_effective: e,
            slipped,
            club_speed_m_s: frame.club_speed_m_s,
        }
        .into_ground(&r_gf)
    }

    /// The collision matrix `K` (any frame in which `r_c`, `r_b` and the inertia agree: F here).
    #[inline]
    pub fn k_matrix(&self, r_c: &Vector3<f64>, r_b: &Vector3<f64>) -> Matrix3<f64> {
        let rc_x = r_c.cross_matrix();
        let inv_ib = 1.0 / self.params.ball_inertia_kgm2;
        // −[r_b]× I_b⁻¹ [r_b]× = (|r_b|²·1 − r_b r_bᵀ) / I_b for an isotropic ball.
        let ball_term = (Matrix3::identity() * r_b.norm_squared() - r_b * r_b.transpose()) * inv_ib;
        Matrix3::identity() * self.inv_mass_sum - rc_x * self.club_inv_inertia * rc_x + ball_term
    }
}

/// The ball's velocity and spin from the impulse and the angular impulse about its centre of
/// mass, in whatever frame they are given: the one definition the built-in and the user-defined
/// solves share, so that both give the same bits. Multiplied by the reciprocals (one scalar
/// division a call, none a lane), a rounding of the quotient away from dividing by `m_b` and
/// `I_b`.
#[inline(always)]
pub(crate) fn ball_response<R: Real>(
    ball_mass_kg: f64,
    ball_inv_inertia_per_kgm2: f64,
    impulse_n_s: &[R; 3],
    angular_impulse_n_m_s: &[R; 3],
) -> ([R; 3], [R; 3]) {
    let inv_mb = 1.0 / ball_mass_kg;
    (
        each3(|i| impulse_n_s[i] * inv_mb),
        each3(|i| angular_impulse_n_m_s[i] * ball_inv_inertia_per_kgm2),
    )
}

mod spd3;
pub use spd3::solve_spd3;

#[cfg(test)]
mod tests;
