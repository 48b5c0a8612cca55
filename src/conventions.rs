//! Where and how a launch monitor defines the delivery, and its conversion to the model's own
//! convention: exactly, once per shot, with the club's own face geometry and centre of mass.
//!
//! The model's delivery (docs/conventions.md) is the velocity of the clubhead's centre of mass
//! and the orientation of the face frame `F` at the centre of the face. Monitors define theirs
//! elsewhere:
//!
//! - **Loft and face angle** at the face centre (camera monitors: the face plane they see) or
//!   at the centre-point of contact (TrackMan: the direction of the face normal where the ball
//!   is struck, so an off-centre strike's angles already hold the bulge and roll rotation
//!   there). The contact-point angles give the normal `n` there in `G`; the face-centre angles
//!   are the `δ`, `φ` (at the shot's lie tilt `λ`) whose frame turns the face's own normal at
//!   that location, `x_I` in `F`, onto `n`: with `m = R_x(−λ)·x_I`, `h = |(m_x, m_y)|` and
//!   `γ = atan2(m_y, m_x)`, `sin δ_c = h·sin(δ + γ)` gives `δ`, and `φ = φ_c − atan2(w_z, w_x)`
//!   with `w = R_z(δ)·m` (the frame is `R_GF = R_y(−φ)·R_z(δ)·R_x(−λ)`). Closed form: no
//!   iteration.
//! - **Speed, attack angle and path** of the centre of mass (the model's), of the head's
//!   geometric centre (TrackMan: close to the CoM; a club file gives no separate geometric
//!   centre, so smash takes it to be the CoM), or of the face centre (camera monitors). A point
//!   `P` of the head moves with `v_P = v_C + ω × (P − C)`, so the face centre's velocity gives
//!   the CoM's as `v_C = v_CoF + ω × (R_GF · r_C/CoF)` with the clubhead spin `ω` of the shot.
//!   No export gives `ω` (the imported `club_omega_*` are 0), and with `ω = 0` every point of
//!   the head has one velocity: the conversion is then exact and changes nothing.
//! - **Measured or derived**: some radars compute the face angle from the launch direction and
//!   the path instead of measuring it (e.g. `φ = (azimuth − 0.25·path)/0.75`). Such a face
//!   angle holds no information the launch direction does not, and compared as a measurement
//!   it makes the monitor's formula a finding (its face share against the model's, on every
//!   off-centre strike its neglect of bulge and gear effect). smash treats it as not measured:
//!   `compare` and `predict` use the face angle at which the club's model launches the ball in
//!   the measured direction (a one-dimensional root of `azimuth(φ) − measured`, to rounding);
//!   that shot's launch direction is then spent on its face angle, so `compare` draws no
//!   azimuth finding from it and no trend against that face angle, which carries the launch
//!   direction's noise ([`drop_derived_findings`]). `diagnose` and `calibrate` leave such
//!   shots out (`ShotTable::leave_out_derived`): a fit on them would fit the monitor's
//!   formula.
//!
//! [`to_model`] applies all three to a table's shots, in that order, and returns what it did.

use std::fmt;

use nalgebra::Vector3;

use crate::club::ClubSpec;
pub use crate::model::convention::*;
use crate::model::Shot;
use crate::physics::{face_orientation, Delivery, FaceError, FaceGeometry, ImpactModel};

/// Why a shot cannot be brought to the model's convention.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ConventionError {
    /// The impact location is off the face.
    #[error(transparent)]
    Face(#[from] FaceError),
    /// No face-centre orientation turns the face normal at the contact point onto the stated
    /// one (a loft near ±90°).
    #[error(
        "no face-centre loft gives a dynamic loft of {loft_deg:.3}° at the contact point \
         (impact y = {y_mm} mm): the loft must be well inside ±90°"
    )]
    Loft {
        /// Contact-point loft, deg.
        loft_deg: f64,
        /// Impact height, mm.
        y_mm: f64,
    },
    /// A face angle derived from the launch, without a measured launch.
    #[error("the face angle is derived from the launch, but the shot has no measured launch")]
    NoLaunch,
    /// No face angle launches the ball in the measured direction.
    #[error(
        "no face angle within ±{limit_deg}° of the monitor's {face_deg:.2}° gives the measured \
         launch direction {azimuth_deg:.2}° with this club"
    )]
    NoFaceAngle {
        /// The monitor's (derived) face angle, deg.
        face_deg: f64,
        /// Measured launch direction, deg.
        azimuth_deg: f64,
        /// How far from the monitor's value the search went, deg.
        limit_deg: f64,
    },
    /// The club's model of a group cannot be built.
    #[error("{0}")]
    Model(String),
    /// The model cannot solve the shot.
    #[error("{0}")]
    Impact(String),
}

/// Face-centre loft and face angle `(δ, φ)`, rad, of a face whose normal at the impact location
/// `(y_m, z_m)` points at the contact-point loft and face angle `(loft_c, face_c)`, rad, at lie
/// tilt `lie_rad` (module docs).
pub fn face_centre_angles(
    face: &FaceGeometry,
    impact_y_m: f64,
    impact_z_m: f64,
    (loft_c_rad, face_c_rad): (f64, f64),
    lie_rad: f64,
) -> Result<(f64, f64), ConventionError> {
    let x_i = face.contact(impact_y_m, impact_z_m)?.normal;
    let (sl, cl) = lie_rad.sin_cos();
    // m = R_x(−λ)·x_I.
    let m = Vector3::new(x_i.x, x_i.y * cl + x_i.z * sl, -x_i.y * sl + x_i.z * cl);
    let h = m.x.hypot(m.y);
    let gamma = m.y.atan2(m.x);
    let s = loft_c_rad.sin() / h;
    if !(s.abs() < 1.0) {
        return Err(ConventionError::Loft {
            loft_deg: loft_c_rad.to_degrees(),
            y_mm: impact_y_m * 1e3,
        });
    }
    let loft = s.asin() - gamma;
    let (sd, cd) = loft.sin_cos();
    let w = Vector3::new(m.x * cd - m.y * sd, m.x * sd + m.y * cd, m.z);
    let face_angle = face_c_rad - w.z.atan2(w.x);
    Ok((loft, face_angle))
}

/// Contact-point loft and face angle, rad, of a face at face-centre angles `(δ, φ)` and lie
/// tilt `lie_rad`, struck at `(y_m, z_m)`: the direction of the face normal there, in `G`.
/// The inverse of [`face_centre_angles`] (what a monitor with TrackMan's definitions reports).
pub fn contact_point_angles(
    face: &FaceGeometry,
    impact_y_m: f64,
    impact_z_m: f64,
    (loft_rad, face_rad): (f64, f64),
    lie_rad: f64,
) -> Result<(f64, f64), FaceError> {
    let x_i = face.contact(impact_y_m, impact_z_m)?.normal;
    let n = face_orientation(loft_rad, face_rad, lie_rad) * x_i;
    Ok((n.y.clamp(-1.0, 1.0).asin(), n.z.atan2(n.x)))
}

/// The CoM velocity in `G`, m/s, of a head whose face centre moves with `v_cof` (m/s, `G`) and
/// spins with `omega` (rad/s, `G`), its face frame turned by `r_gf` and its CoM at `com_f`
/// (m, in `F`, from the face centre): `v_C = v_CoF + ω × (R_GF·r_C/CoF)`.
pub fn com_velocity_from_face_centre(
    v_cof: Vector3<f64>,
    omega: Vector3<f64>,
    r_gf: &nalgebra::Matrix3<f64>,
    com_f: Vector3<f64>,
) -> Vector3<f64> {
    v_cof + omega.cross(&(r_gf * com_f))
}

/// Speed, attack angle and path of a velocity in `G` (the inverse of
/// [`Delivery::club_velocity_m_s`]).
fn speed_attack_path(v: Vector3<f64>) -> (f64, f64, f64) {
    (v.norm(), v.y.atan2(v.x.hypot(v.z)), v.z.atan2(v.x))
}

/// Largest distance from the monitor's derived face angle searched for the model's, rad (30°:
/// a derived face angle is the launch direction rescaled, never this far from the model's).
const DERIVED_SEARCH_RAD: f64 = 30.0 * std::f64::consts::PI / 180.0;

/// The face angle, rad, at which `model` launches the ball of delivery `d` (its face angle
/// aside) at `azimuth_rad`: Newton's method on `azimuth(φ)`, started at `d`'s face angle, with
/// central differences of 1e-6 rad, to 1e-13 rad of azimuth.
pub fn face_angle_for_azimuth(
    model: &ImpactModel,
    d: &Delivery,
    azimuth_rad: f64,
) -> Result<f64, ConventionError> {
    let az = |phi: f64| -> Result<f64, ConventionError> {
        let mut x = *d;
        x.face_angle_rad = phi;
        let out = model
            .solve(&x)
            .map_err(|e| ConventionError::Impact(e.to_string()))?;
        Ok(out.launch().azimuth_rad)
    };
    let start = d.face_angle_rad;
    let fail = || ConventionError::NoFaceAngle {
        face_deg: start.to_degrees(),
        azimuth_deg: azimuth_rad.to_degrees(),
        limit_deg: DERIVED_SEARCH_RAD.to_degrees(),
    };
    let h = 1e-6;
    let mut phi = start;
    for _ in 0..50 {
        let f = az(phi)? - azimuth_rad;
        if f.abs() < 1e-13 {
            return Ok(phi);
        }
        let slope = (az(phi + h)? - az(phi - h)?) / (2.0 * h);
        if !(slope.abs() > 1e-6) {
            return Err(fail());
        }
        phi -= f / slope;
        if !((phi - start).abs() <= DERIVED_SEARCH_RAD) {
            return Err(fail());
        }
    }
    Err(fail())
}

/// One shot brought to the model's convention by `model` (its group's): angles to the face
/// centre, velocity to the CoM, a derived face angle to the model's (module docs).
pub fn shot_to_model(
    model: &ImpactModel,
    shot: &Shot,
    conv: DeliveryConvention,
) -> Result<Shot, ConventionError> {
    let mut d = shot.delivery;
    if conv.face_at == FacePoint::ContactPoint {
        let (loft, face) = face_centre_angles(
            model.face(),
            d.impact_y_m,
            d.impact_z_m,
            (d.dynamic_loft_rad, d.face_angle_rad),
            d.lie_tilt_rad,
        )?;
        d.dynamic_loft_rad = loft;
        d.face_angle_rad = face;
    }
    if conv.velocity_at == VelocityPoint::FaceCentre {
        let r_gf = face_orientation(d.dynamic_loft_rad, d.face_angle_rad, d.lie_tilt_rad);
        let v = com_velocity_from_face_centre(
            d.club_velocity_m_s(),
            d.club_omega_rad_s,
            &r_gf,
            model.params().club_com_m,
        );
        let (s, a, p) = speed_attack_path(v);
        d.club_speed_m_s = s;
        d.attack_angle_rad = a;
        d.club_path_rad = p;
    }
    if conv.face_angle_from == FaceAngleSource::Launch {
        let launch = shot.measured.ok_or(ConventionError::NoLaunch)?;
        d.face_angle_rad = face_angle_for_azimuth(model, &d, launch.azimuth_rad)?;
    }
    Ok(Shot {
        delivery: d,
        ..shot.clone()
    })
}

/// What [`to_model`] did: how many shots were in each convention.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ConventionSummary {
    /// Shots.
    pub shots: usize,
    /// Shots whose loft and face angle were at the contact point (converted).
    pub contact_point: usize,
    /// Shots whose speed and path were of the geometric centre (taken as the CoM's).
    pub geometric_centre: usize,
    /// Shots whose speed and path were of the face centre (converted with their `ω`).
    pub face_centre_velocity: usize,
    /// Of those, shots with a clubhead spin (the others need no change).
    pub face_centre_with_spin: usize,
    /// Shots whose face angle the monitor derived from the launch (replaced by the model's;
    /// their launch direction tests nothing).
    pub derived_face: usize,
    /// The club's bulge and roll radii, mm (what the angles were converted with).
    pub bulge_roll_mm: (f64, f64),
}

impl ConventionSummary {
    /// Are all shots in the model's own convention (nothing converted)?
    pub fn is_native(&self) -> bool {
        self.contact_point + self.geometric_centre + self.face_centre_velocity + self.derived_face
            == 0
    }

    /// One line per convention met, each under 100 columns (none when native).
    pub fn lines(&self) -> Vec<String> {
        let n = self.shots;
        let mut out = Vec::new();
        let (b, r) = self.bulge_roll_mm;
        if self.contact_point > 0 {
            out.push(format!(
                "conventions: {} of {n} shots: loft and face angle at the contact point,",
                self.contact_point
            ));
            out.push(format!(
                "  converted to the face centre with the club's bulge {b} mm and roll {r} mm"
            ));
        }
        if self.geometric_centre > 0 {
            out.push(format!(
                "conventions: {} of {n} shots: speed and path of the geometric centre, taken as \
                 the CoM's",
                self.geometric_centre
            ));
        }
        if self.face_centre_velocity > 0 {
            out.push(format!(
                "conventions: {} of {n} shots: speed and path of the face centre, moved to the CoM",
                self.face_centre_velocity
            ));
            out.push(format!(
                "  with club_omega ({} with a clubhead spin; without one they are the CoM's)",
                self.face_centre_with_spin
            ));
        }
        if self.derived_face > 0 {
            out.push(format!(
                "conventions: {} of {n} shots: face angle derived by the monitor from the launch:",
                self.derived_face
            ));
            out.push(
                "  replaced by the model's for the measured launch direction; no azimuth finding"
                    .to_owned(),
            );
            out.push(
                "  and no trend against face_angle_deg is drawn from them (both restate the launch)"
                    .to_owned(),
            );
        }
        out
    }
}

impl fmt::Display for ConventionSummary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for l in self.lines() {
            writeln!(f, "{l}")?;
        }
        Ok(())
    }
}

/// Drop from a comparison's `findings` those a derived face angle makes: every azimuth finding
/// (the launch direction was spent on the face angle) and every trend against
/// `face_angle_deg` (estimated from the measured launch direction, so it carries that
/// measurement's noise: errors-in-variables), including one appended to a bias finding.
pub fn drop_derived_findings(findings: &mut Vec<crate::compare::Finding>) {
    use crate::compare::Pattern;
    findings.retain(|f| {
        f.component != "azimuth_deg" && !matches!(f.pattern, Pattern::Trend("face_angle_deg"))
    });
    for f in findings.iter_mut() {
        for word in [", rises with face_angle_deg", ", falls with face_angle_deg"] {
            if let Some(at) = f.text.find(word) {
                f.text.truncate(at);
            }
        }
    }
}

/// A shot that could not be converted: its index and why.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("shot '{shot_id}': {source}")]
pub struct ShotConventionError {
    /// Index of the shot.
    pub index: usize,
    /// Its id.
    pub shot_id: String,
    /// Why.
    pub source: ConventionError,
}

/// Every shot brought to the model's convention with the model of its group of `club`
/// (`conventions[i]` is shot `i`'s; a shorter list leaves the rest as they are, in the model's
/// convention). Pure; each shot is converted once: the shots returned are in the model's own
/// convention.
pub fn to_model(
    club: &ClubSpec,
    shots: &[Shot],
    conventions: &[DeliveryConvention],
) -> Result<(Vec<Shot>, ConventionSummary), ShotConventionError> {
    let p = &club.nominal;
    let mut summary = ConventionSummary {
        shots: shots.len(),
        bulge_roll_mm: (p.bulge_m * 1e3, p.roll_m * 1e3),
        ..ConventionSummary::default()
    };
    let mut models = std::collections::BTreeMap::new();
    let mut out = Vec::with_capacity(shots.len());
    for (i, shot) in shots.iter().enumerate() {
        let conv = conventions.get(i).copied().unwrap_or_default();
        let err = |source| ShotConventionError {
            index: i,
            shot_id: shot.id.clone(),
            source,
        };
        if conv == DeliveryConvention::default() {
            out.push(shot.clone());
            continue;
        }
        if !models.contains_key(&shot.group) {
            let m = club
                .model_for_group(&shot.group)
                .map_err(|e| err(ConventionError::Model(e.to_string())))?;
            models.insert(shot.group.clone(), m);
        }
        let model = &models[&shot.group];
        out.push(shot_to_model(model, shot, conv).map_err(err)?);
        summary.contact_point += usize::from(conv.face_at == FacePoint::ContactPoint);
        summary.geometric_centre += usize::from(conv.velocity_at == VelocityPoint::GeometricCentre);
        if conv.velocity_at == VelocityPoint::FaceCentre {
            summary.face_centre_velocity += 1;
            summary.face_centre_with_spin +=
                usize::from(shot.delivery.club_omega_rad_s != Vector3::zeros());
        }
        summary.derived_face += usize::from(conv.face_angle_from == FaceAngleSource::Launch);
    }
    Ok((out, summary))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::ModelParams;

    fn face() -> FaceGeometry {
        FaceGeometry::new(0.305, 0.254).unwrap()
    }

    /// Face-centre angles to the contact point and back, over the face and a range of
    /// deliveries: the same angles to rounding, and the face frame turns the contact normal
    /// onto the contact-point direction.
    #[test]
    fn contact_point_and_face_centre_are_inverse() {
        let f = face();
        for &(y, z) in &[(0.0, 0.0), (0.012, -0.025), (-0.015, 0.03), (0.02, 0.02)] {
            for &(loft, fa, lie) in &[
                (10.0f64, 0.0f64, 0.0f64),
                (14.0, -4.0, 3.0),
                (25.0, 6.0, -5.0),
            ] {
                let a = (loft.to_radians(), fa.to_radians());
                let lie = lie.to_radians();
                let c = contact_point_angles(&f, y, z, a, lie).unwrap();
                let back = face_centre_angles(&f, y, z, c, lie).unwrap();
                assert!((back.0 - a.0).abs() < 1e-13 && (back.1 - a.1).abs() < 1e-13);
                let n = face_orientation(back.0, back.1, lie) * f.contact(y, z).unwrap().normal;
                let want = Vector3::new(c.0.cos() * c.1.cos(), c.0.sin(), c.0.cos() * c.1.sin());
                assert!((n - want).norm() < 1e-13, "{n} vs {want}");
            }
        }
    }

    /// A toe strike on a square face: the normal there turns toward the toe by asin(z/B) (the
    /// torus's heel-to-toe circle at y = 0 has radius B), so the contact-point face angle is
    /// that much open and the loft is unchanged; a strike above the centre adds asin(y/R).
    #[test]
    fn toe_and_crown_strikes_turn_the_normal_by_the_radii() {
        let f = face();
        let c = contact_point_angles(&f, 0.0, 0.02, (0.0, 0.0), 0.0).unwrap();
        assert!((c.1 - (0.02f64 / 0.305).asin()).abs() < 1e-14, "{c:?}");
        assert!(c.0.abs() < 1e-15);
        let c = contact_point_angles(&f, 0.015, 0.0, (0.0, 0.0), 0.0).unwrap();
        assert!((c.0 - (0.015f64 / 0.254).asin()).abs() < 1e-14, "{c:?}");
        assert!(c.1.abs() < 1e-15);
        // Read the other way: an open contact-point face at the toe is square at the centre.
        let (loft, fa) =
            face_centre_angles(&f, 0.0, 0.02, (0.0, (0.02f64 / 0.305).asin()), 0.0).unwrap();
        assert!(loft.abs() < 1e-15 && fa.abs() < 1e-14, "{loft} {fa}");
    }

    #[test]
    fn a_loft_out_of_reach_is_an_error() {
        let f = face();
        // Off the heel-toe centre the normal leans sideways, so no loft reaches 89.9° there.
        let e = face_centre_angles(&f, 0.0, 0.03, (89.9f64.to_radians(), 0.0), 0.0);
        assert!(matches!(e, Err(ConventionError::Loft { .. })), "{e:?}");
    }

    /// `v_P = v_C + ω × (P − C)`: from the face centre back to the CoM, and no change without
    /// spin.
    #[test]
    fn face_centre_velocity_moves_to_the_com_by_the_spin() {
        let r = face_orientation(0.2, 0.05, 0.01);
        let com = Vector3::new(-0.04, 0.003, 0.01);
        let v_c = Vector3::new(45.0, -1.0, 2.0);
        let w = Vector3::new(5.0, -30.0, 12.0);
        let v_cof = v_c + w.cross(&(r * (-com)));
        let back = com_velocity_from_face_centre(v_cof, w, &r, com);
        assert!((back - v_c).norm() < 1e-12);
        assert_eq!(
            com_velocity_from_face_centre(v_cof, Vector3::zeros(), &r, com),
            v_cof
        );
    }

    /// A face angle derived from the launch is replaced by the one the model needs: on a shot
    /// the model itself launched, that is the true face angle.
    #[test]
    fn a_derived_face_angle_becomes_the_models() {
        let model = ImpactModel::new(ModelParams::paper_driver()).unwrap();
        let d = Delivery {
            club_speed_m_s: 44.0,
            attack_angle_rad: 0.03,
            club_path_rad: 0.05,
            dynamic_loft_rad: 0.22,
            face_angle_rad: -0.03,
            lie_tilt_rad: 0.0,
            club_omega_rad_s: Vector3::zeros(),
            impact_y_m: 0.006,
            impact_z_m: 0.011,
            shaft_mass_g: None,
        };
        let az = model.solve(&d).unwrap().launch().azimuth_rad;
        let radar = Delivery {
            face_angle_rad: (az - 0.25 * d.club_path_rad) / 0.75,
            ..d
        };
        let phi = face_angle_for_azimuth(&model, &radar, az).unwrap();
        assert!(
            (phi - d.face_angle_rad).abs() < 1e-10,
            "{phi} vs {}",
            d.face_angle_rad
        );
        assert!((radar.face_angle_rad - d.face_angle_rad).abs() > 1e-3);
    }
}
