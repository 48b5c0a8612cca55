//! User-defined effects: `[[define_effect]]` tables read at run time, no recompiling.
//!
//! ```toml
//! [[define_effect]]
//! name = "cor_power2"
//! doc = "COR falls as a power of the normal approach speed"
//! params = [{ key = "q", unit = "1", default = 0.0, lower = 0.0, upper = 1.0 }]
//! cor = "cor * (u1n_m_s / 48.77) ^ (-q)"
//! ```
//!
//! A definition names parameters (key, unit, default, physical bounds, optional plausible range)
//! and sets one or more model quantities ([`Quantity`]), each to an expression
//! ([`super::expr`]) compiled once. Applying the effect with parameter values
//! ([`UserEffect::apply`]) adds its compiled terms to [`ModelParams::user`]; the model then
//! evaluates them per shot:
//!
//! * mass and geometry quantities (`club_mass_g`, `ball_dy_mm`, `ball_dz_mm`, `com_d*_mm`,
//!   `inertia_scale`, `loft_deg`, `face_deg`) before the solve, from the delivery
//!   ([`UserTerms::pre_solve`]);
//! * `cor`, `et`, `mu` inside the restitution and tangential laws, where the normal and
//!   tangential approach speeds are known ([`UserTerms::contact`], generic over
//!   [`Real`], the same code on one shot and on the kernel's lanes).
//!
//! Every variable an expression reads is the quantity's own nominal value (its value before
//! this effect: the library's law and any earlier effect included), the effect's parameters and
//! the delivery columns of a shots file in file units; `cor`, `et` and `mu` may also read the
//! impact location (`impact_y_mm`, `impact_z_mm`), `u1n_m_s` and `ut_m_s`. Mass and geometry
//! are fixed before the ball meets the face, so they may not depend on where or how fast it
//! does (a face map varies the location at one delivery).
//!
//! Definitions live in a process-wide registry ([`register`]), so that an effect list or a club
//! file can name them like library effects. A name may not clash with the library; defining
//! the same name twice is allowed only with the same definition (a calibrated club file that
//! carries the definition read beside the definitions file it came from).

use std::path::Path;
use std::sync::RwLock;

use nalgebra::Vector3;
use serde::Deserialize;
use toml::Spanned;

use super::expr::{ExprError, Program};
use super::{EffectKind, ParamSpec, MAX_EFFECT_PARAMS};
use crate::data::{line_col, DataError};
use crate::physics::laws::Real;
use crate::physics::{Delivery, ModelParams};

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

    /// Is it evaluated inside the contact laws (may read `u1n_m_s`, `ut_m_s`, the location)?
    pub const fn in_contact(self) -> bool {
        matches!(self, Quantity::Cor | Quantity::Et | Quantity::Mu)
    }

    /// What a value must be.
    const fn allowed(self) -> &'static str {
        match self {
            Quantity::ClubMassG | Quantity::InertiaScale | Quantity::Mu => "finite and > 0",
            _ => "finite",
        }
    }

    fn ok(self, v: f64) -> bool {
        match self {
            Quantity::ClubMassG | Quantity::InertiaScale | Quantity::Mu => v.is_finite() && v > 0.0,
            _ => v.is_finite(),
        }
    }

    fn from_key(key: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|q| q.key() == key)
    }
}

/// Number of expression variables.
pub const NV: usize = 17;
/// Variable: the quantity's nominal value.
pub const VAR_NOMINAL: u8 = 0;
/// Variable: the effect's first parameter (the others follow).
pub const VAR_PARAM0: u8 = 1;
/// Variable: first delivery column (`VAR_DELIVERY + i` is `DELIVERY_COLUMNS[i]`).
pub const VAR_DELIVERY: u8 = 4;
/// Delivery columns every quantity may read, file units.
pub const DELIVERY_COLUMNS: [&str; 9] = [
    "club_speed_mph",
    "attack_angle_deg",
    "club_path_deg",
    "dynamic_loft_deg",
    "face_angle_deg",
    "lie_tilt_deg",
    "club_omega_x_rad_s",
    "club_omega_y_rad_s",
    "club_omega_z_rad_s",
];
/// Variable: impact height, mm.
pub const VAR_IMPACT_Y: u8 = 13;
/// Variable: impact heel–toe location, mm.
pub const VAR_IMPACT_Z: u8 = 14;
/// Variable: normal approach speed, m/s.
pub const VAR_U1N: u8 = 15;
/// Variable: tangential approach speed, m/s.
pub const VAR_UT: u8 = 16;
/// Variables only the contact quantities (`cor`, `et`, `mu`) may read.
pub const CONTACT_VARIABLES: [(&str, u8); 4] = [
    ("impact_y_mm", VAR_IMPACT_Y),
    ("impact_z_mm", VAR_IMPACT_Z),
    ("u1n_m_s", VAR_U1N),
    ("ut_m_s", VAR_UT),
];

/// The per-shot variables of `d` that do not depend on the solve (delivery columns in file
/// units and the impact location); the nominal, parameter and speed slots are 0.
pub fn delivery_vars(d: &Delivery) -> [f64; NV] {
    let mut v = [0.0; NV];
    let cols = [
        d.club_speed_m_s / crate::units::M_S_PER_MPH,
        d.attack_angle_rad.to_degrees(),
        d.club_path_rad.to_degrees(),
        d.dynamic_loft_rad.to_degrees(),
        d.face_angle_rad.to_degrees(),
        d.lie_tilt_rad.to_degrees(),
        d.club_omega_rad_s.x,
        d.club_omega_rad_s.y,
        d.club_omega_rad_s.z,
    ];
    v[VAR_DELIVERY as usize..VAR_DELIVERY as usize + cols.len()].copy_from_slice(&cols);
    v[VAR_IMPACT_Y as usize] = d.impact_y_m * 1e3;
    v[VAR_IMPACT_Z as usize] = d.impact_z_m * 1e3;
    v
}

/// One quantity a definition sets: its compiled expression and the text it came from.
#[derive(Debug)]
pub struct UserTerm {
    /// The quantity.
    pub quantity: Quantity,
    /// The compiled expression.
    pub program: Program,
    /// The expression as written.
    pub text: &'static str,
}

/// A user-defined effect (leaked once when registered: definitions live for the process).
#[derive(Debug)]
pub struct UserEffect {
    /// Name in files and on the command line.
    pub name: &'static str,
    /// One-line description.
    pub doc: &'static str,
    /// Parameters, in file order.
    pub params: &'static [ParamSpec],
    /// The quantities it sets, in file order.
    pub terms: Vec<UserTerm>,
    /// The definition as a `[[define_effect]]` table (written back to calibrated club files).
    pub toml: String,
    /// Where it was defined (file), for messages.
    pub source: String,
}

impl PartialEq for UserEffect {
    fn eq(&self, o: &Self) -> bool {
        self.name == o.name && self.toml == o.toml
    }
}

impl UserEffect {
    /// Apply with parameter values `v` (units of [`UserEffect::params`]): add its terms to the
    /// model's user terms.
    pub fn apply(&'static self, v: &[f64], p: &mut ModelParams) {
        let mut params = [0.0; MAX_EFFECT_PARAMS];
        params[..v.len()].copy_from_slice(v);
        for (i, _) in self.terms.iter().enumerate() {
            p.user.push(AppliedTerm {
                effect: self,
                term: i as u8,
                params,
            });
        }
    }
}

/// One term of a user-defined effect with its parameter values, as a model carries it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AppliedTerm {
    /// The effect.
    pub effect: &'static UserEffect,
    /// Which of its terms.
    pub term: u8,
    /// Parameter values (file units).
    pub params: [f64; MAX_EFFECT_PARAMS],
}

impl AppliedTerm {
    fn def(&self) -> &'static UserTerm {
        &self.effect.terms[self.term as usize]
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

/// The mass and geometry a shot's user terms set (file units), before the solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PreSolve {
    /// Clubhead mass, g.
    pub club_mass_g: f64,
    /// Ball offsets along `y_I`, `z_I`, mm.
    pub ball_d_mm: [f64; 2],
    /// Clubhead CoM shift, mm.
    pub com_d_mm: [f64; 3],
    /// Factor on the clubhead inertia.
    pub inertia_scale: f64,
    /// Delivered dynamic loft with the loft bias, deg.
    pub loft_deg: f64,
    /// Delivered face angle with the face bias, deg.
    pub face_deg: f64,
}

/// A user-defined term gave a value outside what its quantity allows (non-finite, or not
/// positive for a mass, an inertia factor or a friction coefficient).
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error(
    "user-defined effect '{effect}': {quantity} = \"{expr}\" gave {value}; it must be {allowed}"
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

    /// Does any term set a mass or geometry quantity (evaluated before the solve)?
    pub fn has_pre_solve(&self) -> bool {
        self.iter().any(|t| !t.def().quantity.in_contact())
    }

    /// Does any term set `cor`, `et` or `mu` (evaluated in the contact laws)?
    pub fn has_contact(&self) -> bool {
        self.iter().any(|t| t.def().quantity.in_contact())
    }

    /// Does any term set `mu` (so the friction branch must run)?
    pub fn sets_mu(&self) -> bool {
        self.iter().any(|t| t.def().quantity == Quantity::Mu)
    }

    /// Evaluate the mass and geometry terms for one shot whose delivery variables are `vars`
    /// ([`delivery_vars`]), starting from the model's values `base`.
    pub fn pre_solve(&self, vars: &[f64; NV], base: PreSolve) -> Result<PreSolve, UserEvalError> {
        let mut out = base;
        let mut v = *vars;
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
            v[VAR_PARAM0 as usize..VAR_PARAM0 as usize + MAX_EFFECT_PARAMS]
                .copy_from_slice(&t.params);
            let value = def.program.eval(&v);
            if !def.quantity.ok(value) {
                return Err(t.error(value));
            }
            *slot = value;
        }
        Ok(out)
    }

    /// Evaluate the `cor`, `et` and `mu` terms on lanes (or one shot): `vars` holds the
    /// delivery variables, the impact location and the approach speeds; `e`, `et`, `mu` the
    /// values of the library laws. No allocation.
    #[inline]
    pub fn contact<R: Real>(&self, vars: &mut [R; NV], e: R, et: R, mu: R) -> (R, R, R) {
        let mut q = [e, et, mu];
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
            q[i] = def.program.eval(&vars[..]);
        }
        (q[0], q[1], q[2])
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
        let mut q = [e, et, mu];
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
                vars[VAR_PARAM0 as usize + k] = *p;
            }
            let value = def.program.eval(&vars[..]);
            if !def.quantity.ok(value) {
                return Err(t.error(value));
            }
            q[i] = value;
        }
        Ok((q[0], q[1], q[2]))
    }
}

impl AppliedTerm {
    fn error(&self, value: f64) -> UserEvalError {
        let def = self.def();
        UserEvalError {
            effect: self.effect.name,
            quantity: def.quantity.key(),
            expr: def.text,
            value,
            allowed: def.quantity.allowed(),
        }
    }
}

/// The base values of the pre-solve quantities for a model with parameters `p` and delivery
/// `d` (file units).
pub fn pre_solve_base(p: &ModelParams, d: &Delivery) -> PreSolve {
    PreSolve {
        club_mass_g: p.club_mass_kg * 1e3,
        ball_d_mm: [p.ball_offset_y_m * 1e3, p.ball_offset_z_m * 1e3],
        com_d_mm: [0.0; 3],
        inertia_scale: 1.0,
        loft_deg: (d.dynamic_loft_rad + p.loft_bias_rad).to_degrees(),
        face_deg: (d.face_angle_rad + p.face_bias_rad).to_degrees(),
    }
}

impl PreSolve {
    /// The clubhead CoM shift, m.
    pub fn com_shift_m(&self) -> Vector3<f64> {
        Vector3::new(self.com_d_mm[0], self.com_d_mm[1], self.com_d_mm[2]) * 1e-3
    }
}

// ---------------------------------------------------------------------------------------------
// Registry

static REGISTRY: RwLock<Vec<&'static UserEffect>> = RwLock::new(Vec::new());

/// The registered user-defined effect called `name`.
pub fn lookup(name: &str) -> Option<&'static UserEffect> {
    REGISTRY
        .read()
        .unwrap_or_else(|e| e.into_inner())
        .iter()
        .copied()
        .find(|u| u.name == name)
}

/// Every registered user-defined effect, in registration order.
pub fn registered() -> Vec<&'static UserEffect> {
    REGISTRY.read().unwrap_or_else(|e| e.into_inner()).clone()
}

/// Register `def`: a new name is added; a name already registered with the same definition
/// returns that one; a name of the library or registered with another definition is an error.
pub fn register(def: UserEffect) -> Result<&'static UserEffect, String> {
    if EffectKind::from_name(def.name).is_some() {
        return Err(format!(
            "'{}' is the name of a library effect; a user-defined effect needs its own name \
             (the library has: {})",
            def.name,
            EffectKind::all_names()
        ));
    }
    let mut reg = REGISTRY.write().unwrap_or_else(|e| e.into_inner());
    if let Some(old) = reg.iter().find(|u| u.name == def.name) {
        if **old == def {
            return Ok(old);
        }
        return Err(format!(
            "'{}' is already defined differently (in {}); user-defined effects need distinct \
             names",
            def.name, old.source
        ));
    }
    let leaked: &'static UserEffect = Box::leak(Box::new(def));
    reg.push(leaked);
    Ok(leaked)
}

// ---------------------------------------------------------------------------------------------
// Files

/// One `[[define_effect]]` table as written.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawDefinition {
    name: Spanned<String>,
    #[serde(default)]
    doc: Option<String>,
    #[serde(default)]
    params: Option<Spanned<Vec<RawParam>>>,
    cor: Option<Spanned<String>>,
    et: Option<Spanned<String>>,
    mu: Option<Spanned<String>>,
    club_mass_g: Option<Spanned<String>>,
    ball_dy_mm: Option<Spanned<String>>,
    ball_dz_mm: Option<Spanned<String>>,
    com_dx_mm: Option<Spanned<String>>,
    com_dy_mm: Option<Spanned<String>>,
    com_dz_mm: Option<Spanned<String>>,
    inertia_scale: Option<Spanned<String>>,
    loft_deg: Option<Spanned<String>>,
    face_deg: Option<Spanned<String>>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawParam {
    key: String,
    unit: String,
    default: f64,
    lower: f64,
    upper: f64,
    #[serde(default)]
    plausible: Option<[f64; 2]>,
    #[serde(default)]
    doc: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDefsFile {
    #[serde(default)]
    define_effect: Vec<Spanned<RawDefinition>>,
}

/// Read an effects file (only `[[define_effect]]` tables) and register its definitions.
pub fn read_effect_defs(path: &Path) -> Result<Vec<&'static UserEffect>, DataError> {
    let text = crate::data::read_text(path)?;
    parse_effect_defs(path, &text)
}

/// Parse effects-file text (`path` for messages) and register its definitions.
pub fn parse_effect_defs(path: &Path, text: &str) -> Result<Vec<&'static UserEffect>, DataError> {
    let raw: RawDefsFile = crate::data::parse_toml(
        path,
        text,
        "an effects file holds [[define_effect]] tables: name, doc, params = [{ key, unit, \
         default, lower, upper, plausible? }], and one or more of cor, et, mu, club_mass_g, \
         ball_dy_mm, ball_dz_mm, com_dx_mm, com_dy_mm, com_dz_mm, inertia_scale, loft_deg, \
         face_deg = \"expression\"",
    )?;
    if raw.define_effect.is_empty() {
        return Err(DataError::file(
            path,
            "no [[define_effect]] table; an effects file defines at least one effect",
        ));
    }
    register_definitions(path, text, &raw.define_effect)
}

/// Compile, check and register `[[define_effect]]` tables read from `text` of `path`.
pub fn register_definitions(
    path: &Path,
    text: &str,
    defs: &[Spanned<RawDefinition>],
) -> Result<Vec<&'static UserEffect>, DataError> {
    let mut out: Vec<&'static UserEffect> = Vec::with_capacity(defs.len());
    for (i, d) in defs.iter().enumerate() {
        let def = compile_definition(path, text, i, d)?;
        let name = def.name;
        if out.iter().any(|u| u.name == name) {
            return Err(at(
                path,
                text,
                d.get_ref().name.span().start,
                &format!("define_effect[{i}].name"),
                format!("'{name}' is defined twice in this file; names must be distinct"),
            ));
        }
        let u = register(def).map_err(|m| {
            at(
                path,
                text,
                d.get_ref().name.span().start,
                &format!("define_effect[{i}].name"),
                m,
            )
        })?;
        out.push(u);
    }
    Ok(out)
}

fn at(path: &Path, text: &str, offset: usize, key: &str, message: String) -> DataError {
    crate::data::toml_key_error(path, text, offset, key, message)
}

fn is_identifier(s: &str) -> bool {
    let mut c = s.chars();
    c.next().is_some_and(|f| f.is_ascii_lowercase() || f == '_')
        && c.all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
}

/// Names an expression could read apart from parameters: a parameter key may not be one.
fn reserved(name: &str) -> bool {
    Quantity::from_key(name).is_some()
        || DELIVERY_COLUMNS.contains(&name)
        || CONTACT_VARIABLES.iter().any(|(n, _)| *n == name)
        || ["exp", "ln", "sqrt", "abs", "min", "max", "name", "group"].contains(&name)
}

fn leak(s: String) -> &'static str {
    Box::leak(s.into_boxed_str())
}

fn compile_definition(
    path: &Path,
    text: &str,
    index: usize,
    d: &Spanned<RawDefinition>,
) -> Result<UserEffect, DataError> {
    let table_key = format!("define_effect[{index}]");
    let raw = d.get_ref();
    let name = raw.name.get_ref().as_str();
    let err_at = |offset: usize, key: &str, m: String| {
        at(path, text, offset, &format!("{table_key}.{key}"), m)
    };
    if !is_identifier(name) {
        return Err(err_at(
            raw.name.span().start,
            "name",
            format!("'{name}' is not a name: lower-case letters, digits and '_', not starting with a digit"),
        ));
    }
    if EffectKind::from_name(name).is_some() {
        return Err(err_at(
            raw.name.span().start,
            "name",
            format!(
                "'{name}' is the name of a library effect; a user-defined effect needs its own \
                 name (the library has: {})",
                EffectKind::all_names()
            ),
        ));
    }
    // Parameters.
    let pspan = raw
        .params
        .as_ref()
        .map_or(d.span().start, |p| p.span().start);
    let params: &[RawParam] = raw.params.as_ref().map_or(&[], |p| p.get_ref());
    if params.len() > MAX_EFFECT_PARAMS {
        return Err(err_at(
            pspan,
            "params",
            format!(
                "effect '{name}': {} parameters; at most {MAX_EFFECT_PARAMS}",
                params.len()
            ),
        ));
    }
    let mut specs = Vec::with_capacity(params.len());
    for (k, p) in params.iter().enumerate() {
        let key = p.key.as_str();
        let here = |m: String| {
            err_at(
                pspan,
                &format!("params[{k}]"),
                format!("effect '{name}': {m}"),
            )
        };
        if !is_identifier(key) {
            return Err(here(format!("parameter key '{key}' is not a name")));
        }
        if reserved(key) {
            return Err(here(format!(
                "parameter key '{key}' clashes with a quantity, variable or function of the \
                 expression language; choose another key"
            )));
        }
        if params[..k].iter().any(|o| o.key == key) {
            return Err(here(format!("parameter key '{key}' is given twice")));
        }
        let (lo, hi, def) = (p.lower, p.upper, p.default);
        if !(lo.is_finite() && hi.is_finite() && lo < hi) {
            return Err(here(format!(
                "{key}: bounds lower = {lo}, upper = {hi} must be finite with lower < upper"
            )));
        }
        if !(def.is_finite() && lo <= def && def <= hi) {
            return Err(here(format!(
                "{key}: default = {def} must lie within [lower, upper] = [{lo}, {hi}]"
            )));
        }
        let plausible = match p.plausible {
            Some([a, b]) if a.is_finite() && b.is_finite() && lo <= a && a <= b && b <= hi => {
                (a, b)
            }
            Some([a, b]) => {
                return Err(here(format!(
                    "{key}: plausible = [{a}, {b}] must be finite, ordered and within [lower, \
                     upper] = [{lo}, {hi}]"
                )))
            }
            None => (lo, hi),
        };
        specs.push(ParamSpec {
            key: leak(key.to_owned()),
            unit: leak(p.unit.clone()),
            default: def,
            lower: lo,
            upper: hi,
            plausible,
            doc: leak(
                p.doc
                    .clone()
                    .unwrap_or_else(|| format!("parameter of {name}")),
            ),
        });
    }
    // Quantities.
    let given: [(Quantity, &Option<Spanned<String>>); 12] = [
        (Quantity::Cor, &raw.cor),
        (Quantity::Et, &raw.et),
        (Quantity::Mu, &raw.mu),
        (Quantity::ClubMassG, &raw.club_mass_g),
        (Quantity::BallDyMm, &raw.ball_dy_mm),
        (Quantity::BallDzMm, &raw.ball_dz_mm),
        (Quantity::ComDxMm, &raw.com_dx_mm),
        (Quantity::ComDyMm, &raw.com_dy_mm),
        (Quantity::ComDzMm, &raw.com_dz_mm),
        (Quantity::InertiaScale, &raw.inertia_scale),
        (Quantity::LoftDeg, &raw.loft_deg),
        (Quantity::FaceDeg, &raw.face_deg),
    ];
    let mut terms = Vec::new();
    for (q, expr) in given {
        let Some(expr) = expr else { continue };
        let src = expr.get_ref().as_str();
        let resolve = |n: &str| resolve(q, &specs, n);
        let program =
            Program::compile(src, &resolve).map_err(|ExprError { column, message }| {
                // Point at the character in the file when the string has no escapes.
                let start = expr.span().start;
                let raw_text = text.get(start..expr.span().end).unwrap_or("");
                let offset = if raw_text.len() == src.len() + 2 {
                    start
                        + 1
                        + src
                            .char_indices()
                            .nth(column - 1)
                            .map_or(src.len(), |(b, _)| b)
                } else {
                    start
                };
                let (line, col) = line_col(text, offset);
                DataError::at(
                    path,
                    Some(line),
                    Some(format!("column {col}: key {table_key}.{}", q.key())),
                    format!(
                        "effect '{name}': expression \"{src}\", at character {column}: {message}"
                    ),
                )
            })?;
        terms.push(UserTerm {
            quantity: q,
            program,
            text: leak(src.to_owned()),
        });
    }
    if terms.is_empty() {
        return Err(err_at(
            d.span().start,
            "name",
            format!(
                "effect '{name}' sets no quantity; give one or more of {} as an expression",
                Quantity::ALL.map(|q| q.key()).join(", ")
            ),
        ));
    }
    let doc = raw.doc.clone().unwrap_or_default();
    let toml = definition_toml(name, &doc, &specs, &terms);
    Ok(UserEffect {
        name: leak(name.to_owned()),
        doc: leak(doc),
        params: Box::leak(specs.into_boxed_slice()),
        terms,
        toml,
        source: path.display().to_string(),
    })
}

/// The variable number of `name` in an expression for quantity `q` with parameters `specs`.
fn resolve(q: Quantity, specs: &[ParamSpec], name: &str) -> Result<u8, String> {
    if name == q.key() {
        return Ok(VAR_NOMINAL);
    }
    if let Some(k) = specs.iter().position(|s| s.key == name) {
        return Ok(VAR_PARAM0 + k as u8);
    }
    if let Some(k) = DELIVERY_COLUMNS.iter().position(|c| *c == name) {
        return Ok(VAR_DELIVERY + k as u8);
    }
    if let Some((_, v)) = CONTACT_VARIABLES.iter().find(|(n, _)| *n == name) {
        if q.in_contact() {
            return Ok(*v);
        }
        return Err(format!(
            "{} may not use '{name}': mass and geometry are set before the ball meets the face, \
             so they cannot depend on where or how fast it does; only cor, et and mu may read \
             {}",
            q.key(),
            CONTACT_VARIABLES.map(|c| c.0).join(", ")
        ));
    }
    if Quantity::from_key(name).is_some() {
        return Err(format!(
            "'{name}' is another quantity; the expression for {} may read its own nominal value \
             ('{}') only",
            q.key(),
            q.key()
        ));
    }
    let mut allowed = vec![q.key()];
    allowed.extend(specs.iter().map(|s| s.key));
    allowed.extend(DELIVERY_COLUMNS);
    if q.in_contact() {
        allowed.extend(CONTACT_VARIABLES.map(|c| c.0));
    }
    Err(format!(
        "unknown name '{name}'; {} may read: {}",
        q.key(),
        allowed.join(", ")
    ))
}

/// The canonical `[[define_effect]]` table of a definition.
fn definition_toml(name: &str, doc: &str, specs: &[ParamSpec], terms: &[UserTerm]) -> String {
    use std::fmt::Write as _;
    let s = |v: &str| toml::Value::String(v.to_owned()).to_string();
    let mut t = String::new();
    let _ = writeln!(t, "[[define_effect]]");
    let _ = writeln!(t, "name = {}", s(name));
    let _ = writeln!(t, "doc = {}", s(doc));
    let _ = write!(t, "params = [");
    for (i, p) in specs.iter().enumerate() {
        if i > 0 {
            let _ = write!(t, ", ");
        }
        let _ = write!(
            t,
            "{{ key = {}, unit = {}, default = {:?}, lower = {:?}, upper = {:?}, plausible = [{:?}, {:?}], doc = {} }}",
            s(p.key),
            s(p.unit),
            p.default,
            p.lower,
            p.upper,
            p.plausible.0,
            p.plausible.1,
            s(p.doc)
        );
    }
    let _ = writeln!(t, "]");
    for term in terms {
        let _ = writeln!(t, "{} = {}", term.quantity.key(), s(term.text));
    }
    t
}
