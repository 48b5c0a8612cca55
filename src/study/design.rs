//! Design variables: how a design variant changes the clubhead.
//!
//! A design is a value for each [`DesignVar`] (unlisted variables stay at their neutral value,
//! which is the base club). [`Design::apply`] changes the club's *nominal* (physical) clubhead
//! in this order, then the club's calibration effects are applied on top as usual:
//!
//! 1. **Discretionary mass move** (`mass_dx_mm`, `mass_dy_mm`, `mass_dz_mm`): a point mass `m_d`
//!    that is part of the head, at `r_0` (in F, from the CoF), moves by `Δ` to `r_1 = r_0 + Δ`.
//!    The total mass `M` is unchanged (the mass constraint holds by construction); the CoM moves
//!    by `c = m_d·Δ/M`; the inertia about the new CoM follows from the parallel-axis theorem,
//!    with `J(r) = |r|²·1 − r rᵀ` and `r_0`, `r_1` taken from the old CoM:
//!    `I' = I − m_d·J(r_0 − C) + m_d·J(r_1 − C) − M·J(c)`.
//! 2. **CoM offset** (`com_dx_mm`, `com_dy_mm`, `com_dz_mm`): the CoM moves, the inertia about it
//!    is unchanged (the idealised "what if the CoM were here" question).
//! 3. **Inertia scale** (`inertia_scale`): `I → s·I`.
//! 4. **Axis scales** (`ixx_scale`, `iyy_scale`, `izz_scale`): `I → D·I·D` with
//!    `D = diag(√s_xx, √s_yy, √s_zz)` (F axes): the moment about that axis scales by `s`, its
//!    products of inertia by `√s`. Positive-definiteness is kept; the triangle inequality may
//!    break, and is checked.
//! 5. **Principal-moment changes** (`d_i1_gcm2`, `d_i2_gcm2`, `d_i3_gcm2`): the principal moments
//!    of the tensor, smallest first, change by the given amounts; the principal axes stay.
//!
//! A variant whose result is not physical (not positive definite, triangle inequality broken) is
//! an error that names the variant's values.

use std::fmt::Write as _;

use nalgebra::{Matrix3, Vector3};

use crate::physics::{validate_inertia, ModelParams};
use crate::units::{gcm2, mm};

/// One design variable. The key names the unit, as in files.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum DesignVar {
    /// Discretionary mass moved along x_F (toward the face), mm.
    MassDx,
    /// Discretionary mass moved along y_F (up), mm.
    MassDy,
    /// Discretionary mass moved along z_F (toward the toe), mm.
    MassDz,
    /// CoM offset along x_F, mm.
    ComDx,
    /// CoM offset along y_F, mm.
    ComDy,
    /// CoM offset along z_F, mm.
    ComDz,
    /// Whole-tensor inertia scale.
    InertiaScale,
    /// Scale of I_xx (with its products by √s).
    IxxScale,
    /// Scale of I_yy.
    IyyScale,
    /// Scale of I_zz.
    IzzScale,
    /// Change of the smallest principal moment, g·cm².
    DI1,
    /// Change of the middle principal moment, g·cm².
    DI2,
    /// Change of the largest principal moment, g·cm².
    DI3,
}

/// Number of design variables.
pub const N_VARS: usize = 13;

impl DesignVar {
    /// All variables in canonical (file, column and loop) order.
    pub const ALL: [DesignVar; N_VARS] = [
        Self::MassDx,
        Self::MassDy,
        Self::MassDz,
        Self::ComDx,
        Self::ComDy,
        Self::ComDz,
        Self::InertiaScale,
        Self::IxxScale,
        Self::IyyScale,
        Self::IzzScale,
        Self::DI1,
        Self::DI2,
        Self::DI3,
    ];

    /// Key in study files and column in outputs.
    pub const fn key(self) -> &'static str {
        match self {
            Self::MassDx => "mass_dx_mm",
            Self::MassDy => "mass_dy_mm",
            Self::MassDz => "mass_dz_mm",
            Self::ComDx => "com_dx_mm",
            Self::ComDy => "com_dy_mm",
            Self::ComDz => "com_dz_mm",
            Self::InertiaScale => "inertia_scale",
            Self::IxxScale => "ixx_scale",
            Self::IyyScale => "iyy_scale",
            Self::IzzScale => "izz_scale",
            Self::DI1 => "d_i1_gcm2",
            Self::DI2 => "d_i2_gcm2",
            Self::DI3 => "d_i3_gcm2",
        }
    }

    /// Unit (`mm`, `1`, `gcm2`).
    pub const fn unit(self) -> &'static str {
        match self {
            Self::MassDx
            | Self::MassDy
            | Self::MassDz
            | Self::ComDx
            | Self::ComDy
            | Self::ComDz => "mm",
            Self::InertiaScale | Self::IxxScale | Self::IyyScale | Self::IzzScale => "1",
            Self::DI1 | Self::DI2 | Self::DI3 => "gcm2",
        }
    }

    /// The physically meaningful values of the variable (see [`crate::limits`]).
    pub const fn range(self) -> crate::limits::PhysicalRange {
        match self.unit().as_bytes()[0] {
            b'm' => crate::limits::DESIGN_OFFSET_MM,
            b'1' => crate::limits::DESIGN_INERTIA_SCALE,
            _ => crate::limits::DESIGN_MOMENT_CHANGE_GCM2,
        }
    }

    /// The value that leaves the club unchanged.
    pub const fn neutral(self) -> f64 {
        match self {
            Self::InertiaScale | Self::IxxScale | Self::IyyScale | Self::IzzScale => 1.0,
            _ => 0.0,
        }
    }

    /// Default central-difference step for sensitivities: 0.5 mm, 0.01, 10 g·cm².
    pub const fn default_step(self) -> f64 {
        match self.unit().as_bytes()[0] {
            b'm' => 0.5,
            b'1' => 0.01,
            _ => 10.0,
        }
    }

    /// Reference change used to rank sensitivities of different units against each other:
    /// 1 mm, 0.1 (10 %), 100 g·cm².
    pub const fn reference_change(self) -> f64 {
        match self.unit().as_bytes()[0] {
            b'm' => 1.0,
            b'1' => 0.1,
            _ => 100.0,
        }
    }

    /// Whether the variable moves the discretionary mass.
    pub const fn needs_discretionary_mass(self) -> bool {
        matches!(self, Self::MassDx | Self::MassDy | Self::MassDz)
    }

    /// Index in [`DesignVar::ALL`].
    pub const fn index(self) -> usize {
        self as usize
    }

    /// Variable from its key.
    pub fn from_key(key: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|v| v.key() == key)
    }

    /// All keys, comma-separated (for messages).
    pub fn all_keys() -> String {
        Self::ALL.map(|v| v.key()).join(", ")
    }
}

/// A point mass that is part of the head and may be moved (the physical CoM/inertia lever).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiscretionaryMass {
    /// Mass `m_d`, kg (> 0, below the head mass).
    pub mass_kg: f64,
    /// Base position `r_0` relative to the CoF, in F, m.
    pub at_m: Vector3<f64>,
}

/// Values of every design variable.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Design {
    /// Indexed by [`DesignVar::index`].
    pub values: [f64; N_VARS],
}

impl Default for Design {
    fn default() -> Self {
        Self {
            values: DesignVar::ALL.map(DesignVar::neutral),
        }
    }
}

/// Why a design cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("design ({values}) is not physical: {problem}")]
pub struct DesignError {
    /// The design's non-neutral values, `key = value, …`.
    pub values: String,
    /// What is wrong.
    pub problem: String,
}

/// `J(r) = |r|²·1 − r rᵀ`: the inertia of a unit point mass at `r`.
fn point_inertia(r: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::identity() * r.norm_squared() - r * r.transpose()
}

impl Design {
    /// Value of one variable.
    pub fn get(&self, v: DesignVar) -> f64 {
        self.values[v.index()]
    }

    /// Set one variable.
    pub fn set(&mut self, v: DesignVar, x: f64) {
        self.values[v.index()] = x;
    }

    /// The same design with one variable changed.
    pub fn with(mut self, v: DesignVar, x: f64) -> Self {
        self.set(v, x);
        self
    }

    /// `key = value` for every variable away from neutral (`base` when none).
    pub fn describe(&self) -> String {
        let mut s = String::new();
        for v in DesignVar::ALL {
            let x = self.get(v);
            if x != v.neutral() {
                if !s.is_empty() {
                    s.push_str(", ");
                }
                let _ = write!(s, "{} = {}", v.key(), crate::limits::fmt_value(x));
            }
        }
        if s.is_empty() {
            s.push_str("base");
        }
        s
    }

    /// The nominal clubhead changed by this design (see the module docs for the order).
    pub fn apply(
        &self,
        nominal: &ModelParams,
        mass: Option<&DiscretionaryMass>,
    ) -> Result<ModelParams, DesignError> {
        let err = |problem: String| DesignError {
            values: self.describe(),
            problem,
        };
        if let Some(bad) = DesignVar::ALL
            .into_iter()
            .find(|v| !self.get(*v).is_finite())
        {
            return Err(err(format!("{} must be finite", bad.key())));
        }
        let mut p = nominal.clone();
        let delta = Vector3::new(
            mm(self.get(DesignVar::MassDx)),
            mm(self.get(DesignVar::MassDy)),
            mm(self.get(DesignVar::MassDz)),
        );
        if delta != Vector3::zeros() {
            let md = mass.ok_or_else(|| {
                err("moving the discretionary mass needs [design.discretionary_mass]".into())
            })?;
            let m = p.club_mass_kg;
            let old_com = p.club_com_m;
            crate::limits::check_behind_face_mm(
                "the moved discretionary mass",
                (md.at_m.x + delta.x) * 1e3,
            )
            .map_err(|e| err(e.to_string()))?;
            let r0 = md.at_m - old_com;
            let r1 = r0 + delta;
            let shift = delta * (md.mass_kg / m);
            p.club_inertia_kgm2 +=
                md.mass_kg * (point_inertia(&r1) - point_inertia(&r0)) - m * point_inertia(&shift);
            p.club_com_m = old_com + shift;
        }
        p.club_com_m += Vector3::new(
            mm(self.get(DesignVar::ComDx)),
            mm(self.get(DesignVar::ComDy)),
            mm(self.get(DesignVar::ComDz)),
        );
        crate::limits::check_club_com_x_mm(p.club_com_m.x * 1e3).map_err(|e| err(e.to_string()))?;
        let s = self.get(DesignVar::InertiaScale);
        if !(s > 0.0) {
            return Err(err(format!(
                "inertia_scale must be > 0, got {}",
                crate::limits::fmt_value(s)
            )));
        }
        p.club_inertia_kgm2 *= s;
        let axis = [
            self.get(DesignVar::IxxScale),
            self.get(DesignVar::IyyScale),
            self.get(DesignVar::IzzScale),
        ];
        if let Some(i) = axis.iter().position(|s| !(*s > 0.0)) {
            return Err(err(format!(
                "{} must be > 0, got {}",
                [
                    DesignVar::IxxScale,
                    DesignVar::IyyScale,
                    DesignVar::IzzScale
                ][i]
                    .key(),
                crate::limits::fmt_value(axis[i])
            )));
        }
        if axis != [1.0; 3] {
            let d = Matrix3::from_diagonal(&Vector3::new(
                axis[0].sqrt(),
                axis[1].sqrt(),
                axis[2].sqrt(),
            ));
            p.club_inertia_kgm2 = d * p.club_inertia_kgm2 * d;
        }
        let dp = [
            self.get(DesignVar::DI1),
            self.get(DesignVar::DI2),
            self.get(DesignVar::DI3),
        ];
        if dp != [0.0; 3] {
            let eig = p.club_inertia_kgm2.symmetric_eigen();
            let mut order = [0usize, 1, 2];
            order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
            let mut lambda = eig.eigenvalues;
            for (rank, &i) in order.iter().enumerate() {
                lambda[i] += gcm2(dp[rank]);
            }
            let q = eig.eigenvectors;
            let t = q * Matrix3::from_diagonal(&lambda) * q.transpose();
            p.club_inertia_kgm2 = (t + t.transpose()) * 0.5;
        }
        validate_inertia(&p.club_inertia_kgm2, "club inertia tensor")
            .map_err(|e| err(e.to_string()))?;
        // Within the limits a club file is read with, as the base head is.
        crate::data::club_file::check_head(&p).map_err(|e| err(e.to_string()))?;
        Ok(p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn nominal() -> ModelParams {
        crate::data::club_file::parse_club(
            std::path::Path::new("club.toml"),
            include_str!("../../configs/clubs/paper_driver.toml"),
        )
        .unwrap()
        .nominal
    }

    /// Inertia of a set of point masses about their CoM, and the CoM.
    fn points_inertia(points: &[(f64, Vector3<f64>)]) -> (Vector3<f64>, Matrix3<f64>) {
        let m: f64 = points.iter().map(|p| p.0).sum();
        let c = points.iter().map(|p| p.1 * p.0).sum::<Vector3<f64>>() / m;
        let i = points
            .iter()
            .map(|(mi, r)| point_inertia(&(r - c)) * *mi)
            .sum::<Matrix3<f64>>();
        (c, i)
    }

    #[test]
    fn discretionary_mass_move_matches_a_rigid_body_of_point_masses() {
        // A head made of point masses; one of them (the discretionary mass) moves.
        let body = [
            (0.05, Vector3::new(-0.01, 0.01, 0.03)),
            (0.06, Vector3::new(-0.08, -0.01, -0.02)),
            (0.07, Vector3::new(-0.05, 0.02, -0.04)),
            (0.011, Vector3::new(-0.03, -0.015, 0.045)),
        ];
        let md = (0.012, Vector3::new(-0.09, -0.01, 0.01));
        let mut all = body.to_vec();
        all.push(md);
        let (c0, i0) = points_inertia(&all);
        let mut p = nominal();
        p.club_mass_kg = all.iter().map(|x| x.0).sum();
        p.club_com_m = c0;
        p.club_inertia_kgm2 = i0;
        let d = Design::default()
            .with(DesignVar::MassDx, 25.0)
            .with(DesignVar::MassDz, -12.0);
        let mass = DiscretionaryMass {
            mass_kg: md.0,
            at_m: md.1,
        };
        let q = d.apply(&p, Some(&mass)).unwrap();
        let mut moved = body.to_vec();
        moved.push((md.0, md.1 + Vector3::new(0.025, 0.0, -0.012)));
        let (c1, i1) = points_inertia(&moved);
        assert_relative_eq!(q.club_com_m, c1, epsilon = 1e-15);
        assert_relative_eq!(q.club_inertia_kgm2, i1, epsilon = 1e-15);
        assert_eq!(q.club_mass_kg, p.club_mass_kg);
    }

    #[test]
    fn axis_and_principal_changes_do_what_they_say() {
        let p = nominal();
        let q = Design::default()
            .with(DesignVar::IyyScale, 1.05)
            .apply(&p, None)
            .unwrap();
        assert_relative_eq!(
            q.club_inertia_kgm2[(1, 1)],
            1.05 * p.club_inertia_kgm2[(1, 1)],
            max_relative = 1e-14
        );
        assert_relative_eq!(q.club_inertia_kgm2[(0, 0)], p.club_inertia_kgm2[(0, 0)]);
        let q = Design::default()
            .with(DesignVar::DI3, 200.0)
            .apply(&p, None)
            .unwrap();
        let mut e0: Vec<f64> = p
            .club_inertia_kgm2
            .symmetric_eigenvalues()
            .iter()
            .copied()
            .collect();
        let mut e1: Vec<f64> = q
            .club_inertia_kgm2
            .symmetric_eigenvalues()
            .iter()
            .copied()
            .collect();
        e0.sort_by(f64::total_cmp);
        e1.sort_by(f64::total_cmp);
        assert_relative_eq!(e1[2] - e0[2], gcm2(200.0), max_relative = 1e-9);
        assert_relative_eq!(e1[0], e0[0], max_relative = 1e-12);
    }

    #[test]
    fn unphysical_designs_name_their_values() {
        let p = nominal();
        let e = Design::default()
            .with(DesignVar::IyyScale, 3.0)
            .apply(&p, None)
            .unwrap_err();
        assert!(e.to_string().contains("iyy_scale = 3"), "{e}");
        assert!(e.to_string().contains("triangle"), "{e}");
        let e = Design::default()
            .with(DesignVar::DI1, -5000.0)
            .apply(&p, None)
            .unwrap_err();
        assert!(e.to_string().contains("positive definite"), "{e}");
        let e = Design::default()
            .with(DesignVar::MassDx, 1.0)
            .apply(&p, None)
            .unwrap_err();
        assert!(e.to_string().contains("discretionary_mass"), "{e}");
    }
}
