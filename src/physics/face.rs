//! Toroidal clubface with constant bulge (heel–toe) and roll (crown–sole) curvature.
//!
//! The face is a torus whose radius of curvature at the centre of face (CoF) is the bulge `B`
//! heel-to-toe and the roll `Rr` crown-to-sole: tube radius `r = Rr`, major radius `R = B − Rr`,
//! axis parallel to `y_F` through `(−B, 0, 0)`. For an impact location `(y, z)` measured in the
//! CoF tangent plane (up the face, toward the toe):
//!
//! ```text
//! s = sqrt(r² − y²)        ρ = R + s        X = sqrt(ρ² − z²)
//! p   = (X − B, y, z)                                   contact point in F
//! x_I = (s·X/ρ, y, s·z/ρ) / r                           unit outward normal
//! z_I = (−z, 0, X) / ρ                                  horizontal (heel–toe) tangent
//! y_I = z_I × x_I
//! ```
//!
//! This corrects two errata of the paper's Section 2.2.2 (see `docs/conventions.md`): taken literally
//! its Eq. 10 has a heel–toe radius of bulge + roll, and its normal is not of unit length.

use nalgebra::Vector3;

use super::real::Real;

/// Why an impact location cannot be placed on the face.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum FaceError {
    /// The location is outside the torus (a negative square root in the face equations).
    #[error(
        "impact location (y = {y_mm} mm, z = {z_mm} mm) is outside the face torus \
         (bulge {bulge_mm} mm, roll {roll_mm} mm): |y| must be below the roll radius and \
         |z| below the heel-toe radius at that height"
    )]
    OffFace {
        /// Vertical location, mm.
        y_mm: f64,
        /// Heel–toe location, mm.
        z_mm: f64,
        /// Bulge radius, mm.
        bulge_mm: f64,
        /// Roll radius, mm.
        roll_mm: f64,
    },
    /// A face radius that is not a finite positive length ([`FaceGeometry::new`]).
    #[error("{radius} must be a finite positive radius, got {value_m} m")]
    Radius {
        /// Which radius (`bulge`, `roll`).
        radius: &'static str,
        /// Its value, m.
        value_m: f64,
    },
}

/// [`ContactFrame`] on any number type ([`FaceGeometry::contact_on`]), components as arrays.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactFrameOf<R> {
    /// Contact point relative to the centre of face, m.
    pub point_m: [R; 3],
    /// Unit outward face normal `x_I`.
    pub normal: [R; 3],
    /// Unit tangent up the face `y_I`.
    pub tangent_y: [R; 3],
    /// Unit horizontal heel–toe tangent `z_I`.
    pub tangent_z: [R; 3],
}

/// Face geometry: a torus with given bulge and roll radii at the face centre. Valid by construction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FaceGeometry {
    bulge_m: f64,
    roll_m: f64,
    /// Major radius `R = B − Rr`, m.
    major_m: f64,
}

/// Contact point and impact frame `I` at one location on the face, all in the face frame `F`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactFrame {
    /// Contact point relative to the centre of face, m.
    pub point_m: Vector3<f64>,
    /// Unit outward face normal `x_I`.
    pub normal: Vector3<f64>,
    /// Unit tangent up the face `y_I`.
    pub tangent_y: Vector3<f64>,
    /// Unit horizontal heel–toe tangent `z_I`.
    pub tangent_z: Vector3<f64>,
}

impl FaceGeometry {
    /// A face with bulge radius `bulge_m` and roll radius `roll_m` (both m, finite, > 0).
    pub fn new(bulge_m: f64, roll_m: f64) -> Result<Self, FaceError> {
        for (radius, value_m) in [("bulge", bulge_m), ("roll", roll_m)] {
            if !(value_m.is_finite() && value_m > 0.0) {
                return Err(FaceError::Radius { radius, value_m });
            }
        }
        Ok(Self {
            bulge_m,
            roll_m,
            major_m: bulge_m - roll_m,
        })
    }

    /// Bulge (heel–toe radius of curvature at CoF), m.
    pub fn bulge_m(&self) -> f64 {
        self.bulge_m
    }

    /// Roll (crown–sole radius of curvature at CoF), m.
    pub fn roll_m(&self) -> f64 {
        self.roll_m
    }

    /// Contact point and impact frame at `(y_m, z_m)` (m up the face and toward the toe).
    #[inline]
    pub fn contact(&self, y_m: f64, z_m: f64) -> Result<ContactFrame, FaceError> {
        let (on_face, f) = self.contact_on(y_m, z_m);
        if !on_face {
            return Err(FaceError::OffFace {
                y_mm: y_m * 1e3,
                z_mm: z_m * 1e3,
                bulge_mm: self.bulge_m * 1e3,
                roll_mm: self.roll_m * 1e3,
            });
        }
        let v = |a: [f64; 3]| Vector3::new(a[0], a[1], a[2]);
        Ok(ContactFrame {
            point_m: v(f.point_m),
            normal: v(f.normal),
            tangent_y: v(f.tangent_y),
            tangent_z: v(f.tangent_z),
        })
    }

    /// The face equations of the module docs on any number type ([`Real`]: one location, or
    /// one a lane): the contact frame at `(y_m, z_m)` and whether the location is on the face
    /// (false, with NaN or meaningless components, where [`FaceGeometry::contact`] reports
    /// [`FaceError::OffFace`]; also for NaN inputs). [`FaceGeometry::contact`] is this on
    /// `f64`, so the fits' lanes, which compute each site's frame here rather than reading a
    /// stored one, get the same bits.
    #[inline(always)]
    pub fn contact_on<R: Real>(&self, y_m: R, z_m: R) -> (R::Mask, ContactFrameOf<R>) {
        let r = self.roll_m;
        let zero = R::splat(0.0);
        let s2 = R::splat(r * r) - y_m * y_m;
        let s = s2.sqrt();
        let rho = s + self.major_m;
        let x2 = rho * rho - z_m * z_m;
        let x = x2.sqrt();
        let on_face = s2.gt(zero) & rho.gt(zero) & x2.gt(zero);
        // Two divisions, by ρ (per location) and by the roll radius (a constant), instead of
        // seven: the frame is a rounding or two away from dividing each component.
        let inv_rho = R::splat(1.0) / rho;
        let s_n = s * inv_rho * (1.0 / r);
        let normal = [x * s_n, y_m / r, z_m * s_n];
        // `z_I = (−z, 0, X)/ρ`; its `y` component is exactly 0.
        let tangent_z = [-z_m * inv_rho, zero, x * inv_rho];
        let (a, b) = (&tangent_z, &normal);
        let tangent_y = [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ];
        let frame = ContactFrameOf {
            point_m: [x - self.bulge_m, y_m, z_m],
            normal,
            tangent_y,
            tangent_z,
        };
        (on_face, frame)
    }
}
