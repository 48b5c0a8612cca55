//! The physical parameters of an impact model ([`ModelParams`]) and their validation: what a
//! club file, the effect library or a fit produces before [`super::ImpactModel::new`] builds a
//! model from them.

use nalgebra::{Matrix3, Vector3};

use super::user_terms::{self as user, UserTerms};

/// Physical parameters of one impact model, SI units, before validation.
///
/// Every field is a plain number; [`ImpactModel::new`] validates them and precomputes what the
/// inner loop needs. The effect library (`crate::effects`) produces these from a club file.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelParams {
    /// Clubhead mass `m_c`, kg (> 0).
    pub club_mass_kg: f64,
    /// Clubhead CoM relative to the centre of face, `r_C/CoF`, in F, m.
    pub club_com_m: Vector3<f64>,
    /// Clubhead inertia tensor about its CoM, F axes, kg·m² (symmetric positive definite).
    pub club_inertia_kgm2: Matrix3<f64>,
    /// Normal coefficient of restitution at the reference speed and face centre, in (0, 1].
    pub cor: f64,
    /// Face bulge radius, m (> 0).
    pub bulge_m: f64,
    /// Face roll radius, m (> 0).
    pub roll_m: f64,
    /// Ball mass `m_b`, kg (> 0).
    pub ball_mass_kg: f64,
    /// Ball radius, m (> 0).
    pub ball_radius_m: f64,
    /// Ball moment of inertia (isotropic), kg·m² (> 0).
    pub ball_inertia_kgm2: f64,
    /// Ball CoM shift `dy` along `y_I` of the contact point relative to the ball CoM, m.
    pub ball_offset_y_m: f64,
    /// Ball CoM shift `dz` along `z_I`, m.
    pub ball_offset_z_m: f64,
    /// Tangential restitution `e_t`, in [−1, 1]; 0 is the paper's no-slip condition.
    pub tangential_restitution: f64,
    /// Change of `e_t` per unit tangent of the contact point's incidence `|u1t|/u1n`
    /// (`tangential_compliance`; 0: constant `e_t`). The effective `e_t` must stay in [−1, 1].
    pub tangential_restitution_slope: f64,
    /// Gear restitution `e_g`, in [−1, 1]: the part of the tangential velocity that the normal
    /// impulse alone drives at the contact point (the gear effect, through the coupling terms of
    /// the collision matrix) which the gripping contact returns (`tangential_compliance`; 0: the
    /// paper's no slip, −1: no tangential grip at all).
    pub gear_restitution: f64,
    /// Coulomb friction coefficient `mu` (> 0), or `None` for unlimited friction.
    pub friction_mu: Option<f64>,
    /// COR slope with normal approach speed `k`, s/m.
    pub cor_speed_k_s_per_m: f64,
    /// Exponent `q` of the COR's power law in normal approach speed,
    /// `e = cor·(u1n / 48.77 m/s)^(−q)` (0: off).
    pub cor_power_q: f64,
    /// COR falloff with squared distance `c = Σ cᵢ`, 1/m² ([`super::laws::Restitution`]).
    pub cor_radial_c_per_m2: f64,
    /// First moment of the falloffs' peaks `m = Σ cᵢ·aᵢ` (y, z), 1/m (0: peaks at the centre).
    pub cor_radial_moment_per_m: [f64; 2],
    /// `m₀ = −Σ cᵢ·|aᵢ|²` of the falloffs' peaks (0: peaks at the centre).
    pub cor_radial_offset: f64,
    /// Added to the delivered dynamic loft, rad.
    pub loft_bias_rad: f64,
    /// Added to the delivered face angle, rad.
    pub face_bias_rad: f64,
    /// Where the shaft joins the head (top of the hosel bore, on the shaft axis), in F, m: the
    /// point a `hosel_mass` effect puts its mass. Geometry only; the impact does not read it.
    pub hosel_m: Vector3<f64>,
    /// Contact time `τ` of a finite contact, s (0: the paper's instantaneous impact; the
    /// `contact_time` effect, [`super::laws::FiniteContact`]).
    pub contact_time_s: f64,
    /// Terms of user-defined effects (`crate::effects::user`), evaluated per shot: mass and
    /// geometry before the solve, `cor`/`et`/`mu` inside the laws. Empty: the library's laws
    /// run unchanged.
    pub user: UserTerms,
}

/// Default hosel position of a driver in the face frame F, mm: 20 mm behind the face plane,
/// 25 mm above and 55 mm heelward of the face centre. An estimate from the proportions of a
/// 460 cm³ driver head (heel–toe length near the rules' 127 mm limit, USGA/R&A Equipment Rules
/// Appendix II 1b; the shaft axis enters at the heel end of the crown), not a measurement of
/// any club: give `hosel_mm` in the club file when it is known.
pub const DRIVER_HOSEL_MM: [f64; 3] = [-20.0, 25.0, -55.0];

impl ModelParams {
    /// The paper's driver and ball (its Table 1), nominal: the values of
    /// `configs/clubs/paper_driver.toml` (a test checks they agree), for tests, benches and
    /// examples that need a realistic club without reading a file.
    pub fn paper_driver() -> Self {
        Self {
            club_mass_kg: 0.204,
            club_com_m: Vector3::new(-0.0423, 0.0029, 0.001),
            club_inertia_kgm2: Matrix3::new(
                2843.0, -733.0, 530.2, -733.0, 5679.0, 0.5, 530.2, 0.5, 4085.0,
            ) * 1e-7,
            cor: 0.83,
            bulge_m: 0.305,
            roll_m: 0.305,
            ball_mass_kg: 0.0459,
            ball_radius_m: 0.0213,
            ball_inertia_kgm2: 83.63e-7,
            ball_offset_y_m: 0.0,
            ball_offset_z_m: 0.0,
            tangential_restitution: 0.0,
            tangential_restitution_slope: 0.0,
            gear_restitution: 0.0,
            friction_mu: None,
            cor_speed_k_s_per_m: 0.0,
            cor_power_q: 0.0,
            cor_radial_c_per_m2: 0.0,
            cor_radial_moment_per_m: [0.0; 2],
            cor_radial_offset: 0.0,
            loft_bias_rad: 0.0,
            face_bias_rad: 0.0,
            hosel_m: Vector3::from(DRIVER_HOSEL_MM) * 1e-3,
            contact_time_s: 0.0,
            user: UserTerms::default(),
        }
    }
}

impl ModelParams {
    /// Check that every parameter is physical (the face radii are checked by
    /// [`super::FaceGeometry::new`]); the first fault found is returned.
    pub fn validate(&self) -> Result<(), ParamError> {
        let p = self;
        let pos = |v: f64| v.is_finite() && v > 0.0;
        check(pos(p.club_mass_kg), "club mass", || {
            format!("must be finite and > 0, got {} g", p.club_mass_kg * 1e3)
        })?;
        check(
            p.club_com_m.iter().all(|v| v.is_finite()),
            "club centre of mass",
            || "every component must be finite".into(),
        )?;
        validate_inertia(&p.club_inertia_kgm2, "club inertia tensor")?;
        check(
            p.cor.is_finite() && p.cor > 0.0 && p.cor <= 1.0,
            "club cor",
            || format!("must be in (0, 1], got {}", p.cor),
        )?;
        check(pos(p.ball_mass_kg), "ball mass", || {
            format!("must be finite and > 0, got {} g", p.ball_mass_kg * 1e3)
        })?;
        check(pos(p.ball_radius_m), "ball radius", || {
            format!("must be finite and > 0, got {} mm", p.ball_radius_m * 1e3)
        })?;
        check(pos(p.ball_inertia_kgm2), "ball inertia", || {
            format!(
                "must be finite and > 0, got {} g·cm²",
                p.ball_inertia_kgm2 * 1e7
            )
        })?;
        check(
            p.ball_offset_y_m.is_finite() && p.ball_offset_z_m.is_finite(),
            "ball offset",
            || "must be finite".into(),
        )?;
        check(
            p.ball_offset_y_m.hypot(p.ball_offset_z_m) < p.ball_radius_m,
            "ball offset",
            || "must be smaller than the ball radius".into(),
        )?;
        check(
            p.tangential_restitution.is_finite() && p.tangential_restitution.abs() <= 1.0,
            "tangential restitution",
            || format!("must be in [-1, 1], got {}", p.tangential_restitution),
        )?;
        check(
            p.gear_restitution.is_finite() && p.gear_restitution.abs() <= 1.0,
            "gear restitution",
            || format!("must be in [-1, 1], got {}", p.gear_restitution),
        )?;
        if let Some(mu) = p.friction_mu {
            check(pos(mu), "friction mu", || {
                format!("must be finite and > 0, got {mu}")
            })?;
        }
        check(!p.user.overflow, "user-defined effects", || {
            format!(
                "more than {} user-defined quantities on one model",
                user::MAX_TERMS
            )
        })?;
        check(
            p.hosel_m.iter().all(|v| v.is_finite()),
            "club hosel position",
            || "every component must be finite".into(),
        )?;
        check(
            p.contact_time_s.is_finite() && p.contact_time_s >= 0.0 && p.contact_time_s <= 0.01,
            "contact time",
            || {
                format!(
                    "must be in [0, 10] ms, got {} ms",
                    crate::units::Num(p.contact_time_s * 1e3)
                )
            },
        )?;
        for (v, name) in [
            (p.cor_speed_k_s_per_m, "cor speed slope"),
            (
                p.tangential_restitution_slope,
                "tangential restitution slope",
            ),
            (p.cor_power_q, "cor power exponent"),
            (p.cor_radial_c_per_m2, "cor radial falloff"),
            (p.cor_radial_moment_per_m[0], "cor peak moment y"),
            (p.cor_radial_moment_per_m[1], "cor peak moment z"),
            (p.cor_radial_offset, "cor peak offset"),
            (p.loft_bias_rad, "loft bias"),
            (p.face_bias_rad, "face bias"),
        ] {
            check(v.is_finite(), name, || format!("must be finite, got {v}"))?;
        }
        Ok(())
    }
}

/// Why a set of model parameters is not physical.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{quantity}: {problem}")]
pub struct ParamError {
    /// The quantity at fault, as named in files (`club.mass_g`, `club.inertia_gcm2`, …).
    pub quantity: &'static str,
    /// What is wrong and what is allowed.
    pub problem: String,
}

fn check(
    ok: bool,
    quantity: &'static str,
    problem: impl FnOnce() -> String,
) -> Result<(), ParamError> {
    if ok {
        Ok(())
    } else {
        Err(ParamError {
            quantity,
            problem: problem(),
        })
    }
}

/// A moment of inertia given in kg·m², as printed in messages: in g·cm² (the unit of the
/// files' `inertia_gcm2` keys), to 6 significant digits.
fn gcm2(kgm2: f64) -> String {
    crate::units::Num(format!("{:.5e}", kgm2 * 1e7).parse().unwrap_or(kgm2 * 1e7)).to_string()
}

/// Check that `inertia` is a physical inertia tensor: finite, symmetric, positive definite, and
/// its principal moments satisfy the triangle inequality (each at most the sum of the others).
pub fn validate_inertia(inertia: &Matrix3<f64>, quantity: &'static str) -> Result<(), ParamError> {
    // A fit builds many models a second from the same few tensors: the last tensor that passed
    // on this thread is remembered by its bits, and the same bits pass again without another
    // eigen-decomposition (the outcome is a function of the bits, so nothing changes).
    thread_local! {
        static LAST_VALID: std::cell::Cell<Option<[u64; 9]>> = const { std::cell::Cell::new(None) };
    }
    let bits: [u64; 9] = std::array::from_fn(|k| inertia.as_slice()[k].to_bits());
    if LAST_VALID.with(|c| c.get()) == Some(bits) {
        return Ok(());
    }
    validate_inertia_afresh(inertia, quantity)?;
    LAST_VALID.with(|c| c.set(Some(bits)));
    Ok(())
}

/// [`validate_inertia`] without the memory of the last tensor that passed.
fn validate_inertia_afresh(
    inertia: &Matrix3<f64>,
    quantity: &'static str,
) -> Result<(), ParamError> {
    check(inertia.iter().all(|v| v.is_finite()), quantity, || {
        "every entry must be a finite number".into()
    })?;
    let scale = inertia.amax();
    check(scale > 0.0, quantity, || "the tensor is zero".into())?;
    let asym = (inertia - inertia.transpose()).amax();
    check(asym <= 1e-9 * scale, quantity, || {
        format!(
            "the tensor must be symmetric (largest |I_ij − I_ji| is {:.3} g·cm²)",
            asym * 1e7
        )
    })?;
    let eig = inertia.symmetric_eigenvalues();
    let (min, max) = (eig.min(), eig.max());
    check(min > 0.0, quantity, || {
        format!(
            "the tensor must be positive definite (principal moments {}, {}, {} g·cm²)",
            gcm2(eig[0]),
            gcm2(eig[1]),
            gcm2(eig[2])
        )
    })?;
    let sum = eig.sum();
    check(max <= sum - max + 1e-9 * sum, quantity, || {
        format!(
            "principal moments {}, {}, {} g·cm² violate the triangle inequality \
             (the largest must not exceed the sum of the other two)",
            gcm2(eig[0]),
            gcm2(eig[1]),
            gcm2(eig[2])
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The files give inertia in g·cm² (`club.inertia_gcm2`): the principal moments in its
    /// messages are in that unit, not in the kg·m² held inside.
    #[test]
    fn inertia_messages_are_in_the_keys_unit() {
        let gcm2 = |v: f64| v * 1e-7;
        let triangle =
            Matrix3::from_diagonal(&Vector3::new(gcm2(1000.0), gcm2(1000.0), gcm2(3000.0)));
        let e = validate_inertia(&triangle, "club.inertia_gcm2").unwrap_err();
        assert!(e.problem.contains("g·cm²"), "{e}");
        for m in ["1000", "3000"] {
            assert!(e.problem.contains(m), "{m} missing: {e}");
        }
        assert!(!e.problem.contains("e-4"), "{e}");
        let indefinite =
            Matrix3::from_diagonal(&Vector3::new(gcm2(2843.5), gcm2(-12.25), gcm2(4085.0)));
        let e = validate_inertia(&indefinite, "club.inertia_gcm2").unwrap_err();
        assert!(
            e.problem.contains("-12.25") && e.problem.contains("2843.5"),
            "{e}"
        );
        assert!(e.problem.contains("g·cm²"), "{e}");
    }

    #[test]
    fn inertia_validation_rejects_unphysical_tensors() {
        let ok = Matrix3::from_diagonal(&Vector3::new(3.0, 4.0, 5.0));
        assert!(validate_inertia(&ok, "I").is_ok());
        let triangle = Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, 3.0));
        assert!(validate_inertia(&triangle, "I")
            .unwrap_err()
            .problem
            .contains("triangle"));
        let indefinite = Matrix3::new(3.0, 5.0, 0.0, 5.0, 4.0, 0.0, 0.0, 0.0, 5.0);
        assert!(validate_inertia(&indefinite, "I")
            .unwrap_err()
            .problem
            .contains("positive definite"));
        let asym = Matrix3::new(3.0, 0.1, 0.0, 0.0, 4.0, 0.0, 0.0, 0.0, 5.0);
        assert!(validate_inertia(&asym, "I")
            .unwrap_err()
            .problem
            .contains("symmetric"));
        let nan = Matrix3::new(f64::NAN, 0.0, 0.0, 0.0, 4.0, 0.0, 0.0, 0.0, 5.0);
        assert!(validate_inertia(&nan, "I").is_err());
    }
}
