//! Effects files and `[[define_effect]]` tables: read, compiled, checked and registered as
//! user-defined effects (`crate::effects::user`, `docs/user-effects.md`). Every error names the
//! file, line and column, the key, the effect, the expression and the character in it.

use std::path::Path;

use serde::{Deserialize, Serialize};
use toml::Spanned;

use super::toml_check::toml_key_error;
use super::{line_col, DataError, TomlDoc};
use crate::effects::user::{register, Offer, Quantity, UserEffect, UserTermDef};
use crate::effects::{EffectKind, ParamSpec, MAX_EFFECT_PARAMS};
use crate::physics::expr::{ExprError, Program};
use crate::physics::user_terms::{
    CONTACT_VARIABLES, DELIVERY_COLUMNS, VAR_DELIVERY, VAR_NOMINAL, VAR_PARAM0,
};

/// One `[[define_effect]]` table as written.
#[derive(Debug, Clone, Deserialize, Serialize)]
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

#[derive(Debug, Clone, Deserialize, Serialize)]
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

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct RawDefsFile {
    #[serde(default)]
    define_effect: Vec<Spanned<RawDefinition>>,
}

/// Read an effects file (only `[[define_effect]]` tables) and register its definitions.
pub fn read_effect_defs(path: &Path) -> Result<Vec<&'static UserEffect>, DataError> {
    let text = super::read_text(path)?;
    parse_effect_defs(path, &text)
}

/// Parse effects-file text (`path` for messages) and register its definitions.
pub fn parse_effect_defs(path: &Path, text: &str) -> Result<Vec<&'static UserEffect>, DataError> {
    let raw: RawDefsFile = TomlDoc::new(path, text).parse(
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
    register_definitions(path, text, &raw.define_effect, Offer::Candidate)
}

/// Compile, check and register `[[define_effect]]` tables read from `text` of `path`, offered
/// to model searches or world-only as `offer` says ([`Offer`]).
pub fn register_definitions(
    path: &Path,
    text: &str,
    defs: &[Spanned<RawDefinition>],
    offer: Offer,
) -> Result<Vec<&'static UserEffect>, DataError> {
    let mut out: Vec<&'static UserEffect> = Vec::with_capacity(defs.len());
    for (i, d) in defs.iter().enumerate() {
        let def = compile_definition(path, text, i, d)?;
        let name = def.name;
        if out.iter().any(|u| u.name == name) {
            return Err(toml_key_error(
                path,
                text,
                d.get_ref().name.span().start,
                &format!("define_effect[{i}].name"),
                format!("'{name}' is defined twice in this file; names must be distinct"),
            ));
        }
        let u = register(def, offer).map_err(|m| {
            toml_key_error(
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
        toml_key_error(path, text, offset, &format!("{table_key}.{key}"), m)
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
    let specs = compile_params(d, name, &err_at)?;
    let terms = compile_terms(path, text, &table_key, raw, name, &specs)?;
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
    let name: &'static str = leak(name.to_owned());
    let terms = terms
        .into_iter()
        .map(|t| &*Box::leak(Box::new(UserTermDef { effect: name, ..t })))
        .collect();
    Ok(UserEffect {
        name,
        doc: leak(doc),
        params: Box::leak(specs.into_boxed_slice()),
        terms,
        toml,
        source: path.display().to_string(),
    })
}

/// The parameters of a definition, checked: names, bounds, defaults, plausible ranges.
fn compile_params(
    d: &Spanned<RawDefinition>,
    name: &str,
    err_at: &dyn Fn(usize, &str, String) -> DataError,
) -> Result<Vec<ParamSpec>, DataError> {
    let raw = d.get_ref();
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
                "{key}: bounds lower = {}, upper = {} must be finite with lower < upper",
                crate::limits::fmt_value(lo),
                crate::limits::fmt_value(hi)
            )));
        }
        if !(def.is_finite() && lo <= def && def <= hi) {
            return Err(here(format!(
                "{key}: default = {} must lie within [lower, upper] = [{}, {}]",
                crate::limits::fmt_value(def),
                crate::limits::fmt_value(lo),
                crate::limits::fmt_value(hi)
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
    Ok(specs)
}

/// The quantities a definition sets, each expression compiled against its parameters.
fn compile_terms(
    path: &Path,
    text: &str,
    table_key: &str,
    raw: &RawDefinition,
    name: &str,
    specs: &[ParamSpec],
) -> Result<Vec<UserTermDef>, DataError> {
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
        let resolve = |n: &str| resolve(q, specs, n);
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
                        "effect '{name}': expression {}, at character {column}: {message}",
                        quote_expression(src)
                    ),
                )
            })?;
        terms.push(UserTermDef {
            effect: "",
            quantity: q,
            program,
            text: leak(src.to_owned()),
        });
    }
    Ok(terms)
}

/// An expression as an error message quotes it: whole and in double quotes when it is short
/// enough to read on one line, else cut as a long cell is ([`super::quote_cell`]): a 100 kB
/// expression once made a 100 kB message.
fn quote_expression(src: &str) -> String {
    if src.chars().count() <= 200 {
        format!("\"{}\"", super::escape(src))
    } else {
        super::quote_cell(src)
    }
}

/// A name an expression for a quantity may not read ([`resolve`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
enum NameError {
    /// A contact variable in a quantity set before the ball meets the face.
    #[error(
        "{} may not use '{name}': mass and geometry are set before the ball meets the face, so \
         they cannot depend on how fast it does; only cor, et and mu may read {}",
        quantity.key(),
        CONTACT_VARIABLES.map(|c| c.0).join(", ")
    )]
    ContactVariable {
        /// The quantity the expression is for.
        quantity: Quantity,
        /// The name read.
        name: String,
    },
    /// Another quantity's nominal value.
    #[error(
        "'{name}' is another quantity; the expression for {} may read its own nominal value \
         ('{}') only",
        quantity.key(),
        quantity.key()
    )]
    OtherQuantity {
        /// The quantity the expression is for.
        quantity: Quantity,
        /// The name read.
        name: String,
    },
    /// A name that is nothing the expression may read.
    #[error("unknown name '{name}'; {} may read: {}", quantity.key(), allowed.join(", "))]
    Unknown {
        /// The quantity the expression is for.
        quantity: Quantity,
        /// The name read.
        name: String,
        /// What it may read.
        allowed: Vec<&'static str>,
    },
}

/// The variable number of `name` in an expression for quantity `q` with parameters `specs`.
fn resolve(q: Quantity, specs: &[ParamSpec], name: &str) -> Result<u8, NameError> {
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
        return Err(NameError::ContactVariable {
            quantity: q,
            name: name.to_owned(),
        });
    }
    if Quantity::from_key(name).is_some() {
        return Err(NameError::OtherQuantity {
            quantity: q,
            name: name.to_owned(),
        });
    }
    let mut allowed = vec![q.key()];
    allowed.extend(specs.iter().map(|s| s.key));
    allowed.extend(DELIVERY_COLUMNS);
    if q.in_contact() {
        allowed.extend(CONTACT_VARIABLES.map(|c| c.0));
    }
    Err(NameError::Unknown {
        quantity: q,
        name: name.to_owned(),
        allowed,
    })
}

/// A definition as its raw `[[define_effect]]` table.
fn raw_definition<'t>(
    name: &str,
    doc: &str,
    specs: &[ParamSpec],
    terms: impl Iterator<Item = (Quantity, &'t str)>,
) -> RawDefinition {
    let sp = |x: &str| Spanned::new(0..0, x.to_owned());
    let params = specs
        .iter()
        .map(|p| RawParam {
            key: p.key.to_owned(),
            unit: p.unit.to_owned(),
            default: p.default,
            lower: p.lower,
            upper: p.upper,
            plausible: Some([p.plausible.0, p.plausible.1]),
            doc: Some(p.doc.to_owned()),
        })
        .collect();
    let mut raw = RawDefinition {
        name: sp(name),
        doc: Some(doc.to_owned()),
        params: Some(Spanned::new(0..0, params)),
        cor: None,
        et: None,
        mu: None,
        club_mass_g: None,
        ball_dy_mm: None,
        ball_dz_mm: None,
        com_dx_mm: None,
        com_dy_mm: None,
        com_dz_mm: None,
        inertia_scale: None,
        loft_deg: None,
        face_deg: None,
    };
    for (q, text) in terms {
        *raw.quantity_mut(q) = Some(sp(text));
    }
    raw
}

impl RawDefinition {
    fn quantity_mut(&mut self, q: Quantity) -> &mut Option<Spanned<String>> {
        match q {
            Quantity::Cor => &mut self.cor,
            Quantity::Et => &mut self.et,
            Quantity::Mu => &mut self.mu,
            Quantity::ClubMassG => &mut self.club_mass_g,
            Quantity::BallDyMm => &mut self.ball_dy_mm,
            Quantity::BallDzMm => &mut self.ball_dz_mm,
            Quantity::ComDxMm => &mut self.com_dx_mm,
            Quantity::ComDyMm => &mut self.com_dy_mm,
            Quantity::ComDzMm => &mut self.com_dz_mm,
            Quantity::InertiaScale => &mut self.inertia_scale,
            Quantity::LoftDeg => &mut self.loft_deg,
            Quantity::FaceDeg => &mut self.face_deg,
        }
    }
}

/// A registered user-defined effect as its `[[define_effect]]` table (for club files that use it).
pub fn raw_definition_of(u: &UserEffect) -> RawDefinition {
    raw_definition(
        u.name,
        u.doc,
        u.params,
        u.terms.iter().map(|t| (t.quantity, t.text)),
    )
}

/// The canonical `[[define_effect]]` table of a definition.
fn definition_toml(name: &str, doc: &str, specs: &[ParamSpec], terms: &[UserTermDef]) -> String {
    let raw = raw_definition(name, doc, specs, terms.iter().map(|t| (t.quantity, t.text)));
    let file = RawDefsFile {
        define_effect: vec![Spanned::new(0..0, raw)],
    };
    toml::to_string(&file).expect("a definition is plain TOML data")
}
