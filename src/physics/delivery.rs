//! Clubhead delivery at impact and the orientation of the face frame `F` in the ground frame `G`.
//!
//! Ground frame `G`: origin at the ball centre at address, `x` toward the target, `y` up,
//! `z = x × y` (right of the target line seen from behind the ball). The clubhead CoM velocity
//! is `v_c = S·(cos α cos β, sin α, cos α sin β)` from speed `S`, attack angle `α` (+ up) and
//! club path `β` (+ right of target). The face frame at impact follows from dynamic loft `δ`,
//! face angle `φ` (+ open) and lie tilt `λ` (+ toe up):
//!
//! ```text
//! x_F = (cos δ cos φ, sin δ, cos δ sin φ)
//! z0  = (−sin φ, 0, cos φ)            y0 = z0 × x_F
//! y_F = cos λ·y0 − sin λ·z0           z_F = sin λ·y0 + cos λ·z0
//! R_GF = [x_F y_F z_F]                (columns; maps F components to G)
//! ```

use nalgebra::{Matrix3, Vector3};

/// Clubhead state just before impact, where on the face it meets the ball, and the shaft's mass
/// when known. SI units (the shaft mass in g, as in files).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Delivery {
    /// Clubhead CoM speed `S`, m/s.
    pub club_speed_m_s: f64,
    /// Attack angle `α`, rad (+ up).
    pub attack_angle_rad: f64,
    /// Club path `β`, rad (+ right of target, in-to-out for a right-hander).
    pub club_path_rad: f64,
    /// Dynamic loft `δ` at impact, rad.
    pub dynamic_loft_rad: f64,
    /// Face angle `φ` at impact, rad (+ open, face pointing right of target).
    pub face_angle_rad: f64,
    /// Lie tilt `λ` at impact, rad (+ toe up).
    pub lie_tilt_rad: f64,
    /// Clubhead angular velocity in `G`, rad/s.
    pub club_omega_rad_s: Vector3<f64>,
    /// Impact location up the face from CoF, m (in the CoF tangent plane).
    pub impact_y_m: f64,
    /// Impact location toward the toe from CoF, m (in the CoF tangent plane).
    pub impact_z_m: f64,
    /// Mass of the shaft the club was swung with, g, when the shots file gives it (its
    /// `shaft_mass_g` column). The library's laws do not read it; user-defined effects may
    /// (`crate::physics::user_terms`, which supplies a default when it is `None`).
    pub shaft_mass_g: Option<f64>,
}

impl Delivery {
    /// Clubhead CoM velocity in `G`, m/s.
    #[inline]
    pub fn club_velocity_m_s(&self) -> Vector3<f64> {
        let (sa, ca) = self.attack_angle_rad.sin_cos();
        let (sb, cb) = self.club_path_rad.sin_cos();
        self.club_speed_m_s * Vector3::new(ca * cb, sa, ca * sb)
    }

    /// The sines and cosines of the face's angles (dynamic loft plus `loft_bias_rad`, face
    /// angle plus `face_bias_rad`, lie tilt) and the clubhead velocity in `G`: what a delivery
    /// frame is made of ([`FrameTrig`]).
    #[inline]
    pub fn frame_trig(&self, loft_bias_rad: f64, face_bias_rad: f64) -> FrameTrig {
        FrameTrig {
            loft: (self.dynamic_loft_rad + loft_bias_rad).sin_cos(),
            face: (self.face_angle_rad + face_bias_rad).sin_cos(),
            lie: self.lie_tilt_rad.sin_cos(),
            club_velocity_m_s: self.club_velocity_m_s(),
            loft_bias_rad,
            face_bias_rad,
        }
    }

    /// [`Delivery::frame_trig`] for other biases, reusing the parts of `made` (the same
    /// delivery's) that they leave: only a changed bias's angle has its sine and cosine taken
    /// again (a fit of a loft bias takes one `sin_cos` a shot instead of five). The same bits
    /// as [`Delivery::frame_trig`].
    #[inline]
    pub fn frame_trig_from(
        &self,
        made: &FrameTrig,
        loft_bias_rad: f64,
        face_bias_rad: f64,
    ) -> FrameTrig {
        let same = |a: f64, b: f64| a.to_bits() == b.to_bits();
        FrameTrig {
            loft: if same(loft_bias_rad, made.loft_bias_rad) {
                made.loft
            } else {
                (self.dynamic_loft_rad + loft_bias_rad).sin_cos()
            },
            face: if same(face_bias_rad, made.face_bias_rad) {
                made.face
            } else {
                (self.face_angle_rad + face_bias_rad).sin_cos()
            },
            loft_bias_rad,
            face_bias_rad,
            ..*made
        }
    }
}

/// The trigonometry of one delivery's frame for one pair of loft and face biases
/// ([`Delivery::frame_trig`]): `(sin, cos)` of the biased loft and face angle and of the lie
/// tilt, and the clubhead velocity in `G` (m/s), which no bias changes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameTrig {
    /// `(sin, cos)` of dynamic loft plus the loft bias.
    pub loft: (f64, f64),
    /// `(sin, cos)` of face angle plus the face bias.
    pub face: (f64, f64),
    /// `(sin, cos)` of the lie tilt.
    pub lie: (f64, f64),
    /// Clubhead CoM velocity in `G`, m/s.
    pub club_velocity_m_s: Vector3<f64>,
    /// Loft bias the angles were made with, rad.
    pub loft_bias_rad: f64,
    /// Face-angle bias the angles were made with, rad.
    pub face_bias_rad: f64,
}

impl FrameTrig {
    /// Rotation `R_GF` of these angles ([`face_orientation`]).
    #[inline]
    pub fn face_orientation(&self) -> Matrix3<f64> {
        orientation_of(self.loft, self.face, self.lie)
    }
}

/// Rotation `R_GF` whose columns are the face axes `x_F`, `y_F`, `z_F` in ground components.
#[inline]
pub fn face_orientation(
    dynamic_loft_rad: f64,
    face_angle_rad: f64,
    lie_tilt_rad: f64,
) -> Matrix3<f64> {
    orientation_of(
        dynamic_loft_rad.sin_cos(),
        face_angle_rad.sin_cos(),
        lie_tilt_rad.sin_cos(),
    )
}

/// [`face_orientation`] from the `(sin, cos)` of its three angles.
#[inline]
fn orientation_of(
    (sd, cd): (f64, f64),
    (sp, cp): (f64, f64),
    (sl, cl): (f64, f64),
) -> Matrix3<f64> {
    let x_f = Vector3::new(cd * cp, sd, cd * sp);
    let z0 = Vector3::new(-sp, 0.0, cp);
    let y0 = z0.cross(&x_f);
    let y_f = cl * y0 - sl * z0;
    let z_f = sl * y0 + cl * z0;
    Matrix3::from_columns(&[x_f, y_f, z_f])
}
