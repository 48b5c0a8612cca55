//! A what-if: one design change stated directly, answered in yards against the base head for
//! a stated golfer and mishit pattern (`smash whatif`).
//!
//! The change ([`HeadChange`]) is applied to the club's nominal head in this order:
//!
//! 1. **Mass move**: a mass `m` that is part of the head moves from `A` to `B` (F frame, from
//!    the CoF). The head's mass is unchanged; its CoM and its inertia about the new CoM follow
//!    from the parallel-axis theorem, exactly as a `[design]` discretionary-mass move does
//!    ([`super::design`]: `I' = I − m·J(A − C) + m·J(B − C) − M·J(c)`, `c = m·(B − A)/M`).
//! 2. **CoM shift**: the CoM moves, the inertia about it is unchanged.
//! 3. **MOI scale**: the inertia tensor about the CoM scales by `s`.
//! 4. **Bulge and roll radii**: replaced.
//! 5. **Loft change**: the head has `δ` more loft; delivered by the same swing (the same shaft
//!    lean and attack), the face meets the ball with `δ` more dynamic loft.
//!
//! The answer is [`super::yards_variants`]'s comparison of the two heads over the same
//! distribution of swings and impacts. Pure: no I/O.

use std::fmt::Write as _;

use nalgebra::Vector3;

use super::design::{Design, DesignVar, DiscretionaryMass};
use super::distribution::SwingSpec;
use super::landing::Landing;
use super::yards::YardsError;
use super::yards_variants::{head_landing, HeadYards, YardSetting};
use crate::physics::{ImpactModel, ModelParams};
use crate::units::{g, mm};

/// A point mass of the head moved from one place to another.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassMove {
    /// The mass moved, g.
    pub mass_g: f64,
    /// Where it sits in the base head, mm (F frame, from the CoF).
    pub from_mm: [f64; 3],
    /// Where it is moved to, mm.
    pub to_mm: [f64; 3],
}

/// One design change (every part optional; the default changes nothing).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct HeadChange {
    /// A mass moved within the head.
    pub mass_move: Option<MassMove>,
    /// CoM shift, mm (F frame).
    pub com_shift_mm: Option<[f64; 3]>,
    /// Scale of the inertia tensor about the CoM.
    pub moi_scale: Option<f64>,
    /// New bulge radius, mm.
    pub bulge_mm: Option<f64>,
    /// New roll radius, mm.
    pub roll_mm: Option<f64>,
    /// Loft change of the head, degrees (+ more loft).
    pub loft_change_deg: Option<f64>,
}

fn fmt3(v: [f64; 3]) -> String {
    format!(
        "({}, {}, {})",
        crate::limits::fmt_value(v[0]),
        crate::limits::fmt_value(v[1]),
        crate::limits::fmt_value(v[2])
    )
}

impl HeadChange {
    /// Whether it changes anything.
    pub fn is_empty(&self) -> bool {
        *self == Self::default()
    }

    /// The change in words, one part per item.
    pub fn describe(&self) -> Vec<String> {
        let f = crate::limits::fmt_value;
        let mut out = Vec::new();
        if let Some(m) = &self.mass_move {
            out.push(format!(
                "move {} g from {} mm to {} mm",
                f(m.mass_g),
                fmt3(m.from_mm),
                fmt3(m.to_mm)
            ));
        }
        if let Some(c) = self.com_shift_mm {
            out.push(format!("shift the CoM by {} mm", fmt3(c)));
        }
        if let Some(s) = self.moi_scale {
            out.push(format!("scale the inertia tensor by {}", f(s)));
        }
        if let Some(b) = self.bulge_mm {
            out.push(format!("bulge radius {} mm", f(b)));
        }
        if let Some(r) = self.roll_mm {
            out.push(format!("roll radius {} mm", f(r)));
        }
        if let Some(d) = self.loft_change_deg {
            out.push(format!("loft {:+} deg", d));
        }
        out
    }

    /// The changed head (errors name what is not physical, and the part of the change that
    /// made it so: [`WhatIfError::Part`]). Each part is checked as it is applied, so that a
    /// refusal is about the part that was given, not about a club-file key.
    pub fn apply(&self, nominal: &ModelParams) -> Result<ModelParams, WhatIfError> {
        let part = |part: ChangePart| move |problem: String| WhatIfError::Part { part, problem };
        let head = |part: ChangePart| {
            move |e: crate::data::club_file::HeadError| WhatIfError::Part {
                part,
                problem: format!("the changed head's {}", e.problem),
            }
        };
        for (r, which) in [
            (self.bulge_mm, ChangePart::Bulge),
            (self.roll_mm, ChangePart::Roll),
        ] {
            if let Some(r) = r {
                crate::limits::FACE_RADIUS_MM
                    .check(r)
                    .map_err(|e| part(which)(e.to_string()))?;
            }
        }
        let mut d = Design::default();
        let mut mass = None;
        if let Some(m) = &self.mass_move {
            check_mass_move(m, nominal).map_err(part(ChangePart::MassMove))?;
            mass = Some(DiscretionaryMass {
                mass_kg: g(m.mass_g),
                at_m: Vector3::new(mm(m.from_mm[0]), mm(m.from_mm[1]), mm(m.from_mm[2])),
            });
            for (k, v) in [DesignVar::MassDx, DesignVar::MassDy, DesignVar::MassDz]
                .into_iter()
                .enumerate()
            {
                d.set(v, m.to_mm[k] - m.from_mm[k]);
            }
        }
        if let Some(c) = self.com_shift_mm {
            d.set(DesignVar::ComDx, c[0]);
            d.set(DesignVar::ComDy, c[1]);
            d.set(DesignVar::ComDz, c[2]);
        }
        // The CoM's place is the CoM shift's doing when one is given, else the mass move's.
        let moved = if self.com_shift_mm.is_some() {
            ChangePart::ComShift
        } else {
            ChangePart::MassMove
        };
        // The design's own check of the head states the club-file key first (`club.com_mm:
        // …`): the key is replaced by the part of the change that moved it.
        let mut p = d.apply(nominal, mass.as_ref()).map_err(|e| {
            let by = if e.problem.starts_with("club.com_mm") {
                moved
            } else {
                ChangePart::MassMove
            };
            let problem = match e.problem.split_once(": ") {
                Some((key, rest)) if key.starts_with("club.") => rest,
                _ => e.problem.as_str(),
            };
            part(by)(format!("the changed head's {problem}"))
        })?;
        crate::data::club_file::check_head(&p).map_err(|e| {
            let by = if e.key == "club.com_mm" {
                moved
            } else {
                ChangePart::MassMove
            };
            head(by)(e)
        })?;
        if let Some(s) = self.moi_scale {
            let allowed = moi_scale_range(&p);
            if !(s.is_finite() && s > 0.0) {
                return Err(part(ChangePart::MoiScale)(format!(
                    "must be a positive number; for this head within [{}, {}]",
                    crate::limits::fmt_value(allowed[0]),
                    crate::limits::fmt_value(allowed[1])
                )));
            }
            p.club_inertia_kgm2 *= s;
            crate::data::club_file::check_head(&p).map_err(|e| WhatIfError::Part {
                part: ChangePart::MoiScale,
                problem: format!(
                    "the changed head's {}; for this head the scale must be within [{}, {}]",
                    e.problem,
                    crate::limits::fmt_value(allowed[0]),
                    crate::limits::fmt_value(allowed[1])
                ),
            })?;
        }
        if let Some(b) = self.bulge_mm {
            p.bulge_m = mm(b);
        }
        if let Some(r) = self.roll_mm {
            p.roll_m = mm(r);
        }
        // The limits a club file is read with hold for the changed head too: a scaling or a
        // move may not make a head the club file itself would refuse (`--moi-scale 1e6`).
        crate::data::club_file::check_head(&p).map_err(WhatIfError::ChangedHead)?;
        ImpactModel::new(p.clone())?;
        Ok(p)
    }

    /// The swing the changed head is delivered with (the loft change).
    pub fn swing(&self, base: &SwingSpec) -> SwingSpec {
        SwingSpec {
            dynamic_loft_deg: base.dynamic_loft_deg + self.loft_change_deg.unwrap_or(0.0),
            ..*base
        }
    }
}

/// The part of a [`HeadChange`] a refusal is about (the command line names its flag).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ChangePart {
    /// [`HeadChange::mass_move`].
    MassMove,
    /// [`HeadChange::com_shift_mm`].
    ComShift,
    /// [`HeadChange::moi_scale`].
    MoiScale,
    /// [`HeadChange::bulge_mm`].
    Bulge,
    /// [`HeadChange::roll_mm`].
    Roll,
    /// [`HeadChange::loft_change_deg`].
    LoftChange,
}

/// `Err` when a mass move is not one within the head `nominal`: a mass that is not part of it,
/// a FROM or TO point in front of the face or farther from the centre of face than any head
/// reaches ([`crate::limits::HEAD_REACH_MM`]), or a FROM point too far from the centre of mass
/// for the mass it moves. That last: the head is the moved mass `m` at `A` and the rest, `M − m`,
/// whose own inertia about its CoM is `I − k·J(A − C)` with `k = m·M/(M − m)` (the two-body
/// parallel-axis sum, `J(r) = |r|²·1 − r·rᵀ`); a body's inertia is positive definite, so when
/// that is not, `m` cannot sit at `A`: it alone would give the head more inertia than it has.
/// (Where the mass goes cannot break this: the changed head is the same rest plus `m` at `B`.)
fn check_mass_move(m: &MassMove, nominal: &ModelParams) -> Result<(), String> {
    use crate::limits::{fmt_value as f, HEAD_REACH_MM};
    crate::limits::check_head_part_mass_g("the moved mass", m.mass_g, nominal.club_mass_kg)
        .map_err(|e| e.to_string())?;
    for (which, at) in [("FROM", m.from_mm), ("TO", m.to_mm)] {
        let reach = Vector3::from(at).norm();
        if at[0] >= 0.0 {
            return Err(format!(
                "the {which} point {} mm is at or in front of the face (x = {} mm; the face is \
                 at x = 0, the head behind it at x < 0)",
                fmt3(at),
                f(at[0])
            ));
        }
        if !(reach <= HEAD_REACH_MM) {
            return Err(format!(
                "the {which} point {} mm lies outside any clubhead: {} mm from the centre of \
                 face, where no head reaches farther than {} mm",
                fmt3(at),
                f(round_to(reach, 1)),
                f(HEAD_REACH_MM)
            ));
        }
    }
    let big_m = nominal.club_mass_kg;
    let k = g(m.mass_g) * big_m / (big_m - g(m.mass_g));
    let com = nominal.club_com_m;
    let d = Vector3::new(mm(m.from_mm[0]), mm(m.from_mm[1]), mm(m.from_mm[2])) - com;
    let rest_valid = |t: f64| {
        let r = d * t;
        let j = nalgebra::Matrix3::identity() * r.norm_squared() - r * r.transpose();
        (nominal.club_inertia_kgm2 - j * k)
            .symmetric_eigenvalues()
            .min()
            > 0.0
    };
    if rest_valid(1.0) {
        return Ok(());
    }
    // The farthest along that direction the mass may sit: bisection on the share of `d`.
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if rest_valid(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let c_mm = com.map(|x| x * 1e3);
    Err(format!(
        "the FROM point {} mm is {} mm from the head's centre of mass {} mm, too far for {} g \
         of this {} g head: a part that heavy lies at most {} mm from it in that direction \
         (farther, it alone would give the head more inertia than it has), so the point is \
         outside the head",
        fmt3(m.from_mm),
        f(round_to(d.norm() * 1e3, 1)),
        fmt3([
            round_to(c_mm.x, 2),
            round_to(c_mm.y, 2),
            round_to(c_mm.z, 2)
        ]),
        f(m.mass_g),
        f(round_to(big_m * 1e3, 3)),
        f(round_to(lo * d.norm() * 1e3, 1))
    ))
}

/// `x` rounded to `digits` decimals.
fn round_to(x: f64, digits: i32) -> f64 {
    let s = 10f64.powi(digits);
    (x * s).round() / s
}

/// The `--moi-scale` range that keeps head `p` one a club file takes: from the least principal
/// moment a head of its mass can have ([`crate::limits::min_head_moment_gcm2`]) to the largest
/// inertia entry ([`crate::limits::CLUB_INERTIA_GCM2`]), each to 3 significant digits inward.
fn moi_scale_range(p: &ModelParams) -> [f64; 2] {
    let i = p.club_inertia_kgm2 * 1e7;
    let least = i.symmetric_eigenvalues().min();
    let low = crate::limits::min_head_moment_gcm2(p.club_mass_kg * 1e3) / least;
    let high = crate::limits::CLUB_INERTIA_GCM2.max / i.amax();
    let digits = |x: f64, up: bool| {
        let s = 10f64.powi(2 - x.log10().floor() as i32);
        if up {
            (x * s).ceil() / s
        } else {
            (x * s).floor() / s
        }
    };
    [digits(low, true), digits(high, false)]
}

/// The answer: both heads and their yard metrics.
#[derive(Debug, Clone)]
pub struct WhatIf {
    /// The base head.
    pub base_params: ModelParams,
    /// The changed head.
    pub changed_params: ModelParams,
    /// The base head's yards.
    pub base: HeadYards,
    /// The changed head's yards.
    pub changed: HeadYards,
    /// Where the base head's balls land (the distribution as given).
    pub base_landing: Landing,
    /// Where the changed head's balls land.
    pub changed_landing: Landing,
}

/// Why a what-if cannot be answered ([`what_if`], [`HeadChange::apply`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum WhatIfError {
    /// A moved mass that is not part of the head, or a value out of its range.
    #[error(transparent)]
    Limit(#[from] crate::limits::LimitError),
    /// One part of the change is not physical (or makes a head that is not).
    #[error("{problem}")]
    Part {
        /// Which part.
        part: ChangePart,
        /// What is wrong, and what is allowed.
        problem: String,
    },
    /// The changed head is one a club file would refuse.
    #[error("the changed head: {0}")]
    ChangedHead(crate::data::club_file::HeadError),
    /// The model refuses the changed head.
    #[error(transparent)]
    Model(#[from] crate::physics::ParamError),
    /// The base head's yards.
    #[error("the base head: {0}")]
    BaseYards(YardsError),
    /// The changed head's yards.
    #[error("the changed head: {0}")]
    ChangedYards(YardsError),
}

/// Answer `change` against the base head `nominal` in the setting `s` (its swing is the base
/// head's; the changed head's follows from [`HeadChange::swing`]).
pub fn what_if(
    nominal: &ModelParams,
    change: &HeadChange,
    s: &YardSetting<'_>,
) -> Result<WhatIf, WhatIfError> {
    let changed_params = change.apply(nominal)?;
    let swing = change.swing(s.swing);
    if let Err(e) = crate::limits::DYNAMIC_LOFT_DEG.check(swing.dynamic_loft_deg) {
        let r = crate::limits::DYNAMIC_LOFT_DEG;
        let base = s.swing.dynamic_loft_deg;
        return Err(WhatIfError::Part {
            part: ChangePart::LoftChange,
            problem: format!(
                "the changed head's {e}: with a base dynamic loft of {} deg the loft change \
                 must be within [{}, {}] deg",
                crate::limits::fmt_value(base),
                crate::limits::fmt_value(r.min - base),
                crate::limits::fmt_value(r.max - base)
            ),
        });
    }
    let (base, base_landing) = head_landing(nominal, s).map_err(WhatIfError::BaseYards)?;
    let (changed, changed_landing) = head_landing(
        &changed_params,
        &YardSetting {
            swing: &swing,
            ..*s
        },
    )
    .map_err(WhatIfError::ChangedYards)?;
    Ok(WhatIf {
        base_params: nominal.clone(),
        changed_params,
        base,
        changed,
        base_landing,
        changed_landing,
    })
}

/// The carry change over the face at the golfer's central swing: each head's carry at each
/// impact location of a grid, and the change (changed − base), yd.
#[derive(Debug, Clone, PartialEq)]
pub struct CarryChangeMap {
    /// Heights up the face, mm (ascending).
    pub ys_mm: Vec<f64>,
    /// Heel–toe locations, mm (ascending, + toward the toe).
    pub zs_mm: Vec<f64>,
    /// Changed carry − base carry, yd, row-major (`ys × zs`); `None` where either head's impact
    /// is off the face or misses the ball.
    pub d_carry_yd: Vec<Option<f64>>,
}

/// The impact locations of the carry-change map: the mishit pattern's centre ± 2.5 σ (at
/// least ± 10 mm up and ± 20 mm across), `n` points a side.
pub fn carry_change_grid(centre_mm: [f64; 2], sigma_mm: [f64; 2], n: usize) -> [Vec<f64>; 2] {
    let n = n.max(2);
    let side = |c: f64, s: f64, least: f64| -> Vec<f64> {
        let h = (2.5 * s).max(least);
        (0..n)
            .map(|i| c - h + 2.0 * h * i as f64 / (n - 1) as f64)
            .collect()
    };
    [
        side(centre_mm[0], sigma_mm[0], 10.0),
        side(centre_mm[1], sigma_mm[1], 20.0),
    ]
}

/// The carry change from the head `base_params` to `changed_params` over the grid `ys_mm ×
/// zs_mm` for the swing `swing` (the base head's; the changed head is delivered with
/// [`HeadChange::swing`]).
pub fn carry_change_map(
    base_params: &ModelParams,
    changed_params: &ModelParams,
    change: &HeadChange,
    swing: &SwingSpec,
    flight: &crate::flight::FlightConfig,
    [ys_mm, zs_mm]: &[Vec<f64>; 2],
) -> Result<CarryChangeMap, YardsError> {
    let map = |p: &ModelParams, s: &SwingSpec| {
        let model = ImpactModel::new(p.clone())?;
        super::yards::carry_map(&model, s, ys_mm, zs_mm, flight)
    };
    let base = map(base_params, swing)?;
    let changed = map(changed_params, &change.swing(swing))?;
    let d_carry_yd = base
        .carry_yd
        .iter()
        .zip(&changed.carry_yd)
        .map(|(b, c)| Some(c.as_ref()? - b.as_ref()?))
        .collect();
    Ok(CarryChangeMap {
        ys_mm: ys_mm.clone(),
        zs_mm: zs_mm.clone(),
        d_carry_yd,
    })
}

/// The heads side by side: mass, CoM and the inertia tensor's diagonal.
pub fn head_text(w: &WhatIf) -> String {
    let mut t = String::new();
    let com = |p: &ModelParams| {
        let c = p.club_com_m / crate::units::M_PER_MM;
        format!("({:.2}, {:.2}, {:.2})", c.x, c.y, c.z)
    };
    let moi = |p: &ModelParams| {
        let i = p.club_inertia_kgm2 / crate::units::KGM2_PER_GCM2;
        format!("({:.1}, {:.1}, {:.1})", i[(0, 0)], i[(1, 1)], i[(2, 2)])
    };
    let (b, c) = (&w.base_params, &w.changed_params);
    let _ = writeln!(
        t,
        "head mass: {:.1} g -> {:.1} g",
        b.club_mass_kg * 1e3,
        c.club_mass_kg * 1e3
    );
    let _ = writeln!(t, "CoM (x, y, z) mm: {} -> {}", com(b), com(c));
    let _ = writeln!(
        t,
        "I_xx, I_yy, I_zz about the CoM g·cm²: {} -> {}",
        moi(b),
        moi(c)
    );
    let _ = writeln!(
        t,
        "bulge, roll mm: {:.1}, {:.1} -> {:.1}, {:.1}",
        b.bulge_m * 1e3,
        b.roll_m * 1e3,
        c.bulge_m * 1e3,
        c.roll_m * 1e3
    );
    t
}

#[cfg(test)]
#[path = "whatif_tests.rs"]
mod tests;
