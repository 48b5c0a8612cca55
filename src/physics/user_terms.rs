//! The run-time side of user-defined effects (`crate::effects::user`): the model quantities they
//! may set, the variables their expressions read, and the compiled terms a model carries
//! ([`UserTerms`], in [`ModelParams::user`]), evaluated per shot:
//!
//! * mass and geometry quantities (`club_mass_g`, `ball_dy_mm`, `ball_dz_mm`, `com_d*_mm`,
//!   `inertia_scale`, `loft_deg`, `face_deg`) before the solve, from the delivery
//!   ([`UserTerms::pre_solve`]);
//! * `cor`, `et`, `mu` inside the restitution and tangential laws, where the normal and
//!   tangential approach speeds are known ([`UserTerms::contact`], generic over [`Real`], the
//!   same code on one shot and on the kernel's lanes).
//!
//! Every variable an expression reads is the quantity's own nominal value (its value before
//! this term: the library's law and any earlier term included), the effect's parameters and the
//! shot columns of a shots file in file units (the delivery, the impact location `impact_y_mm`,
//! `impact_z_mm`, and `shaft_mass_g`, [`DEFAULT_SHAFT_MASS_G`] when a shot has none); `cor`,
//! `et` and `mu` may also read the approach speeds `u1n_m_s` and `ut_m_s`. Mass and geometry
//! are fixed before the ball meets the face, so they may not depend on how fast it does; they
//! may depend on where (a face map then evaluates them at every point,
//! [`UserTerms::pre_solve_reads_location`]).

use std::convert::Infallible;

use nalgebra::Vector3;

use super::delivery::Delivery;
use super::delivery_vars::{delivery_to_file_units, DeliveryVar, N_DELIVERY};
use super::expr::Program;
use super::real::Real;

/// A model quantity a user-defined effect may set.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Quantity {
    /// Normal coefficient of restitution `e` of the impact.
    Cor,
    /// Tangential restitution `e_t`.
    Et,
    /// Coulomb friction coefficient (nominal: infinite when no friction effect is on).
    Mu,
    /// Clubhead mass, g.
    ClubMassG,
    /// Ball contact offset along `y_I`, mm.
    BallDyMm,
    /// Ball contact offset along `z_I`, mm.
    BallDzMm,
    /// Clubhead CoM shift along x_F, mm (nominal 0).
    ComDxMm,
    /// Clubhead CoM shift along y_F, mm (nominal 0).
    ComDyMm,
    /// Clubhead CoM shift along z_F, mm (nominal 0).
    ComDzMm,
    /// Factor on the clubhead inertia tensor (nominal 1).
    InertiaScale,
    /// Delivered dynamic loft, deg.
    LoftDeg,
    /// Delivered face angle, deg.
    FaceDeg,
}

impl Quantity {
    /// Every settable quantity, in file order.
    pub const ALL: [Quantity; 12] = [
        Quantity::Cor,
        Quantity::Et,
        Quantity::Mu,
        Quantity::ClubMassG,
        Quantity::BallDyMm,
        Quantity::BallDzMm,
        Quantity::ComDxMm,
        Quantity::ComDyMm,
        Quantity::ComDzMm,
        Quantity::InertiaScale,
        Quantity::LoftDeg,
        Quantity::FaceDeg,
    ];

    /// Its key in a `[[define_effect]]` table, and its nominal value's name in expressions.
    pub const fn key(self) -> &'static str {
        match self {
            Quantity::Cor => "cor",
            Quantity::Et => "et",
            Quantity::Mu => "mu",
            Quantity::ClubMassG => "club_mass_g",
            Quantity::BallDyMm => "ball_dy_mm",
            Quantity::BallDzMm => "ball_dz_mm",
            Quantity::ComDxMm => "com_dx_mm",
            Quantity::ComDyMm => "com_dy_mm",
            Quantity::ComDzMm => "com_dz_mm",
            Quantity::InertiaScale => "inertia_scale",
            Quantity::LoftDeg => "loft_deg",
            Quantity::FaceDeg => "face_deg",
        }
    }

    /// Is it evaluated inside the contact laws (may read `u1n_m_s` and `ut_m_s`)?
    pub const fn in_contact(self) -> bool {
        matches!(self, Quantity::Cor | Quantity::Et | Quantity::Mu)
    }

    /// What a value must be: the library's own limits on the quantity (the club file's `cor`
    /// in (0, 1] and `tangential_restitution` in [−1, 1], `ModelParams::validate`; the club
    /// mass range [`crate::limits::CLUB_MASS_G`]; a loft or face angle of ±90° or more turns
    /// the face away from the ball, [`crate::limits::DYNAMIC_LOFT_DEG`]).
    const fn allowed(self) -> &'static str {
        match self {
            Quantity::Cor => "in (0, 1]",
            Quantity::Et => "in [-1, 1]",
            Quantity::ClubMassG => "in [1, 10000] g",
            Quantity::InertiaScale | Quantity::Mu => "finite and > 0",
            Quantity::LoftDeg | Quantity::FaceDeg => "in (-90, 90) deg",
            _ => "finite",
        }
    }

    /// Whether `v` is allowed ([`Quantity::allowed`]); NaN never is. The face-map kernel's
    /// lanes make the same decision for `cor`, `et` and `mu` (`sweep::kernel`), to the bit.
    pub fn ok(self, v: f64) -> bool {
        match self {
            Quantity::Cor => v > 0.0 && v <= 1.0,
            Quantity::Et => v.abs() <= 1.0,
            Quantity::ClubMassG => crate::limits::CLUB_MASS_G.contains(v),
            Quantity::InertiaScale | Quantity::Mu => v.is_finite() && v > 0.0,
            Quantity::LoftDeg | Quantity::FaceDeg => v.abs() < 90.0,
            _ => v.is_finite(),
        }
    }

    /// The quantity with this key.
    pub fn from_key(key: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|q| q.key() == key)
    }
}

/// Number of expression variables.
pub const NV: usize = 18;
/// Variable: the quantity's nominal value.
pub const VAR_NOMINAL: u8 = 0;
/// Variable: the effect's first parameter (the others follow).
pub const VAR_PARAM0: u8 = 1;
/// Variable: first shot column (`VAR_DELIVERY + i` is `DELIVERY_COLUMNS[i]`).
pub const VAR_DELIVERY: u8 = 4;
/// Shots-file columns every quantity may read, file units: the delivery variables in their
/// column order ([`DeliveryVar::ALL`], which holds the impact location) and the shaft mass.
pub const DELIVERY_COLUMNS: [&str; N_DELIVERY + 1] = {
    let mut c = [""; N_DELIVERY + 1];
    let mut i = 0;
    while i < N_DELIVERY {
        c[i] = DeliveryVar::ALL[i].column();
        i += 1;
    }
    c[N_DELIVERY] = "shaft_mass_g";
    c
};
/// Variable: impact height, mm.
pub const VAR_IMPACT_Y: u8 = VAR_DELIVERY + DeliveryVar::ImpactY.index() as u8;
/// Variable: impact heel–toe location, mm.
pub const VAR_IMPACT_Z: u8 = VAR_DELIVERY + DeliveryVar::ImpactZ.index() as u8;
/// Variable: shaft mass, g.
pub const VAR_SHAFT_MASS: u8 = VAR_DELIVERY + N_DELIVERY as u8;
/// Variable: normal approach speed, m/s.
pub const VAR_U1N: u8 = 16;
/// Variable: tangential approach speed, m/s.
pub const VAR_UT: u8 = 17;
/// Variables only the contact quantities (`cor`, `et`, `mu`) may read: the approach speeds,
/// known only once the ball meets the face.
pub const CONTACT_VARIABLES: [(&str, u8); 2] = [("u1n_m_s", VAR_U1N), ("ut_m_s", VAR_UT)];

const _: () = assert!(VAR_U1N as usize == VAR_DELIVERY as usize + DELIVERY_COLUMNS.len());
const _: () = assert!(VAR_UT as usize + 1 == NV);

/// Shaft mass an expression reads when a shot does not give one (no `shaft_mass_g` column, or a
/// face map of a study), g: the mean of the three driver shafts of the paper (Danaei et al.,
/// Section 2.1: 74.5, 60.3 and 70.9 g; see [`crate::physics`]), a typical graphite driver shaft.
pub const DEFAULT_SHAFT_MASS_G: f64 = (74.5 + 60.3 + 70.9) / 3.0;

/// Variables that change with the impact location at one delivery: a face map must evaluate an
/// expression that reads one of them at every point.
pub const LOCATION_VARIABLES: [u8; 2] = [VAR_IMPACT_Y, VAR_IMPACT_Z];

/// The per-shot variables of `d` that do not depend on the solve (the shot columns in file
/// units, the shaft mass defaulting to [`DEFAULT_SHAFT_MASS_G`]); the nominal, parameter and
/// speed slots are 0.
pub fn delivery_vars(d: &Delivery) -> [f64; NV] {
    let mut v = [0.0; NV];
    let at = VAR_DELIVERY as usize;
    v[at..at + N_DELIVERY].copy_from_slice(&delivery_to_file_units(d));
    v[VAR_SHAFT_MASS as usize] = d.shaft_mass_g.unwrap_or(DEFAULT_SHAFT_MASS_G);
    v
}

/// Variable `k` of [`delivery_vars`] alone (a shot column in file units, or the shaft mass),
/// the same value; 0 for the other slots.
#[inline]
pub fn delivery_var(d: &Delivery, k: usize) -> f64 {
    let at = VAR_DELIVERY as usize;
    if k == VAR_SHAFT_MASS as usize {
        d.shaft_mass_g.unwrap_or(DEFAULT_SHAFT_MASS_G)
    } else if (at..at + N_DELIVERY).contains(&k) {
        DeliveryVar::ALL[k - at].file_value(d)
    } else {
        0.0
    }
}

/// One quantity a user-defined effect sets: its compiled expression, the text it came from and
/// the effect's name (for messages). Created once when a definition is read, and kept for the
/// life of the process.
#[derive(Debug)]
pub struct UserTermDef {
    /// Name of the effect that defines it.
    pub effect: &'static str,
    /// The quantity.
    pub quantity: Quantity,
    /// The compiled expression.
    pub program: Program,
    /// The expression as written.
    pub text: &'static str,
}

/// Most parameters of a user-defined effect (the effect library's limit).
pub const MAX_USER_PARAMS: usize = 3;

/// One term of a user-defined effect with its parameter values, as a model carries it.
#[derive(Debug, Clone, Copy)]
pub struct AppliedTerm {
    /// The term.
    pub def: &'static UserTermDef,
    /// Parameter values (file units).
    pub params: [f64; MAX_USER_PARAMS],
}

impl PartialEq for AppliedTerm {
    fn eq(&self, o: &Self) -> bool {
        std::ptr::eq(self.def, o.def) && self.params == o.params
    }
}

impl AppliedTerm {
    fn def(&self) -> &'static UserTermDef {
        self.def
    }
}

/// Most user-defined terms one model carries.
pub const MAX_TERMS: usize = 16;

/// The user-defined terms applied to a model, in application order. `Copy`, no heap.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct UserTerms {
    items: [Option<AppliedTerm>; MAX_TERMS],
    len: u8,
    /// More than [`MAX_TERMS`] were pushed (the model refuses to build).
    pub overflow: bool,
}

/// The mass and geometry a shot's user terms set (file units), before the solve: on one shot
/// (`R = f64`) or on lanes of shots.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PreSolve<R = f64> {
    /// Clubhead mass, g.
    pub club_mass_g: R,
    /// Ball offsets along `y_I`, `z_I`, mm.
    pub ball_d_mm: [R; 2],
    /// Clubhead CoM shift, mm.
    pub com_d_mm: [R; 3],
    /// Factor on the clubhead inertia.
    pub inertia_scale: R,
    /// Delivered dynamic loft with the loft bias, deg.
    pub loft_deg: R,
    /// Delivered face angle with the face bias, deg.
    pub face_deg: R,
}

/// A user-defined term gave a value outside what its quantity allows ([`Quantity::allowed`]:
/// non-finite, or outside the library's own limits on the quantity).
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error(
    "user-defined effect '{effect}': {quantity} = \"{expr}\" gave {}; it must be {allowed}",
    value_in_words(*value)
)]
pub struct UserEvalError {
    /// Effect name.
    pub effect: &'static str,
    /// Quantity key.
    pub quantity: &'static str,
    /// Expression text.
    pub expr: &'static str,
    /// The value it gave.
    pub value: f64,
    /// What is allowed.
    pub allowed: &'static str,
}

/// A value an expression gave, as a message says it: a finite number as itself, a non-finite one
/// in words and with its likely cause (no `inf` or `NaN` leaves the program, even in a message).
fn value_in_words(value: f64) -> String {
    if value.is_nan() {
        "no number (an undefined operation: ln or sqrt of a negative number, or 0/0)".to_owned()
    } else if value.is_infinite() {
        format!(
            "a {} value too large for a double (an overflow, or a division by zero)",
            if value > 0.0 { "positive" } else { "negative" }
        )
    } else {
        crate::limits::fmt_value(value)
    }
}

impl UserTerms {
    /// Add a term (past [`MAX_TERMS`], set `overflow`).
    pub fn push(&mut self, t: AppliedTerm) {
        if (self.len as usize) < MAX_TERMS {
            self.items[self.len as usize] = Some(t);
            self.len += 1;
        } else {
            self.overflow = true;
        }
    }

    /// No user-defined term at all?
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    fn iter(&self) -> impl Iterator<Item = &AppliedTerm> {
        self.items[..self.len as usize].iter().flatten()
    }

    /// The variables any term reads: bit `i` for variable `i` ([`NV`] of them).
    pub fn read_mask(&self) -> u64 {
        self.iter().fold(0, |m, t| m | t.def().program.read_mask())
    }

    /// Does any term set a mass or geometry quantity (evaluated before the solve)?
    pub fn has_pre_solve(&self) -> bool {
        self.iter().any(|t| !t.def().quantity.in_contact())
    }

    /// Does a mass or geometry term read the impact location (so that it differs between the
    /// points of a face map at one delivery)?
    pub fn pre_solve_reads_location(&self) -> bool {
        self.iter().any(|t| {
            let def = t.def();
            !def.quantity.in_contact() && LOCATION_VARIABLES.iter().any(|&v| def.program.reads(v))
        })
    }

    /// Does any term set `cor`, `et` or `mu` (evaluated in the contact laws)?
    pub fn has_contact(&self) -> bool {
        self.iter().any(|t| t.def().quantity.in_contact())
    }

    /// Does any term set `mu` (so the friction branch must run)?
    pub fn sets_mu(&self) -> bool {
        self.iter().any(|t| t.def().quantity == Quantity::Mu)
    }

    /// Does a term set the delivered loft or face angle (so that the face orientation differs
    /// shot by shot from the delivery frame a fit caches)?
    pub fn sets_orientation(&self) -> bool {
        self.iter()
            .any(|t| matches!(t.def().quantity, Quantity::LoftDeg | Quantity::FaceDeg))
    }

    /// Evaluate the mass and geometry terms for one shot whose delivery variables are `vars`
    /// ([`delivery_vars`]), starting from the model's values `base`.
    pub fn pre_solve(&self, vars: &[f64; NV], base: PreSolve) -> Result<PreSolve, UserEvalError> {
        let mut v = *vars;
        self.pre_solve_with(&mut v, base, &mut Refuse)
    }

    /// [`UserTerms::pre_solve`] on lanes of shots (or one): `vars` holds each lane's delivery
    /// variables. Lanes where any term's value is not allowed ([`Quantity::ok`], the decision
    /// [`UserTerms::pre_solve`] makes on one shot) are cleared from `valid`. The same
    /// operations as [`UserTerms::pre_solve`], so a lane gets the bits of its shot.
    #[inline(always)]
    pub fn pre_solve_lanes<R: Real>(
        &self,
        vars: &mut [R; NV],
        base: PreSolve<R>,
        valid: &mut R::Mask,
    ) -> PreSolve<R> {
        match self.pre_solve_with(vars, base, &mut Clear(valid)) {
            Ok(q) => q,
            Err(never) => match never {},
        }
    }

    /// The one loop of [`UserTerms::pre_solve`] and [`UserTerms::pre_solve_lanes`]: each mass
    /// or geometry term in turn, its nominal the value so far, `check` asked about every value
    /// it makes.
    #[inline(always)]
    fn pre_solve_with<R: Real, E>(
        &self,
        v: &mut [R; NV],
        base: PreSolve<R>,
        verdict: &mut impl Verdict<R, Error = E>,
    ) -> Result<PreSolve<R>, E> {
        let mut out = base;
        for t in self.iter() {
            let def = t.def();
            let slot = match def.quantity {
                Quantity::ClubMassG => &mut out.club_mass_g,
                Quantity::BallDyMm => &mut out.ball_d_mm[0],
                Quantity::BallDzMm => &mut out.ball_d_mm[1],
                Quantity::ComDxMm => &mut out.com_d_mm[0],
                Quantity::ComDyMm => &mut out.com_d_mm[1],
                Quantity::ComDzMm => &mut out.com_d_mm[2],
                Quantity::InertiaScale => &mut out.inertia_scale,
                Quantity::LoftDeg => &mut out.loft_deg,
                Quantity::FaceDeg => &mut out.face_deg,
                Quantity::Cor | Quantity::Et | Quantity::Mu => continue,
            };
            v[VAR_NOMINAL as usize] = *slot;
            for (k, p) in t.params.iter().enumerate() {
                v[VAR_PARAM0 as usize + k] = R::splat(*p);
            }
            let value = def.program.eval(&v[..]);
            verdict.check(t, value)?;
            *slot = value;
        }
        Ok(out)
    }

    /// Evaluate the `cor`, `et` and `mu` terms on lanes (or one shot): `vars` holds the
    /// delivery variables, the impact location and the approach speeds; `e`, `et`, `mu` the
    /// values of the library laws. Lanes where any term's value is not allowed
    /// ([`Quantity::ok`], the decision [`UserTerms::contact_checked`] makes on one shot) are
    /// cleared from `valid`. No allocation.
    #[inline(always)]
    pub fn contact<R: Real>(
        &self,
        vars: &mut [R; NV],
        [e, et, mu]: [R; 3],
        valid: &mut R::Mask,
    ) -> (R, R, R) {
        match self.contact_with(vars, [e, et, mu], &mut Clear(valid)) {
            Ok(q) => q,
            Err(never) => match never {},
        }
    }

    /// [`UserTerms::contact`] on one shot, with the first term whose value is not allowed
    /// named.
    pub fn contact_checked(
        &self,
        vars: &mut [f64; NV],
        e: f64,
        et: f64,
        mu: f64,
    ) -> Result<(f64, f64, f64), UserEvalError> {
        self.contact_with(vars, [e, et, mu], &mut Refuse)
    }

    /// The one loop of [`UserTerms::contact`] and [`UserTerms::contact_checked`]: each contact
    /// term in turn, its nominal the value so far, `verdict` asked about every value it makes.
    #[inline(always)]
    fn contact_with<R: Real, E>(
        &self,
        vars: &mut [R; NV],
        mut q: [R; 3],
        verdict: &mut impl Verdict<R, Error = E>,
    ) -> Result<(R, R, R), E> {
        for t in self.iter() {
            let def = t.def();
            let i = match def.quantity {
                Quantity::Cor => 0,
                Quantity::Et => 1,
                Quantity::Mu => 2,
                _ => continue,
            };
            vars[VAR_NOMINAL as usize] = q[i];
            for (k, p) in t.params.iter().enumerate() {
                vars[VAR_PARAM0 as usize + k] = R::splat(*p);
            }
            let value = def.program.eval(&vars[..]);
            verdict.check(t, value)?;
            q[i] = value;
        }
        Ok((q[0], q[1], q[2]))
    }
}

/// What the term loops do with each value a term makes: on one shot, refuse it naming the term
/// ([`Refuse`]); on lanes, clear the lanes where it is not allowed ([`Clear`]). A trait rather
/// than a closure so that it is always inlined: a closure does not inherit the lane code's
/// `#[target_feature]`, and the lane operations in it would become out-of-line calls.
trait Verdict<R: Real> {
    type Error;
    fn check(&mut self, t: &AppliedTerm, value: R) -> Result<(), Self::Error>;
}

/// Refuse a value its quantity does not allow, naming the term.
struct Refuse;

impl Verdict<f64> for Refuse {
    type Error = UserEvalError;
    #[inline(always)]
    fn check(&mut self, t: &AppliedTerm, value: f64) -> Result<(), UserEvalError> {
        if t.def().quantity.ok(value) {
            Ok(())
        } else {
            Err(t.error(value))
        }
    }
}

/// Clear the lanes whose value its quantity does not allow, by [`Quantity::ok`] lane by lane.
struct Clear<'a, M>(&'a mut M);

impl<R: Real> Verdict<R> for Clear<'_, R::Mask> {
    type Error = Infallible;
    #[inline(always)]
    fn check(&mut self, t: &AppliedTerm, value: R) -> Result<(), Infallible> {
        let q = t.def().quantity;
        let ok = value
            .map(|x| f64::from(u8::from(q.ok(x))))
            .gt(R::splat(0.5));
        *self.0 = *self.0 & ok;
        Ok(())
    }
}

impl AppliedTerm {
    fn error(&self, value: f64) -> UserEvalError {
        let def = self.def();
        UserEvalError {
            effect: def.effect,
            quantity: def.quantity.key(),
            expr: def.text,
            value,
            allowed: def.quantity.allowed(),
        }
    }
}

impl PreSolve<f64> {
    /// The clubhead CoM shift, m.
    pub fn com_shift_m(&self) -> Vector3<f64> {
        Vector3::new(self.com_d_mm[0], self.com_d_mm[1], self.com_d_mm[2]) * 1e-3
    }
}
