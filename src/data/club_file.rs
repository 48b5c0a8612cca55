//! Club files (TOML): clubhead, ball and optional `[[effect]]` tables.
//!
//! ```toml
//! [club]
//! name = "Paper driver (Table 1)"
//! mass_g = 204.0
//! com_mm = [-42.3, 2.9, 1.0]            # r_C/CoF in F
//! inertia_gcm2 = [[2843.0, -733.0, 530.2], [-733.0, 5679.0, 0.5], [530.2, 0.5, 4085.0]]
//! cor = 0.83
//! loft_deg = 9.8                         # static loft (informational)
//! bulge_mm = 305.0
//! roll_mm = 305.0
//! hosel_mm = [-20.0, 25.0, -55.0]       # optional: where the shaft joins the head, in F
//!
//! [ball]
//! mass_g = 45.9
//! radius_mm = 21.3
//! inertia_gcm2 = 83.63                   # isotropic
//!
//! [[effect]]
//! name = "added_mass"
//! dm_g = 2.54
//! group = "A"        # optional: applies to that group only
//! ```
//!
//! Unknown keys are errors; so are missing keys, non-finite or unphysical values. Every error
//! names the file, line and column of the offending key.

use std::fmt::Write as _;
use std::path::Path;

use nalgebra::{Matrix3, Vector3};
use serde::{Deserialize, Serialize};
use toml::Spanned;

use super::{read_text, DataError, TomlDoc};
use crate::club::ClubSpec;
use crate::effects::user::Offer;
#[cfg(test)]
use crate::effects::EffectKind;
use crate::effects::{Effect, EffectId};
use crate::limits::{self, LimitError};
use crate::physics::impact::DRIVER_HOSEL_MM;
use crate::physics::{validate_inertia, ModelParams};
use crate::units::{deg, g, gcm2, mm};

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    club: RawClub,
    ball: RawBall,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    define_effect: Vec<Spanned<super::effect_defs::RawDefinition>>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    effect: Vec<Spanned<toml::Table>>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct RawClub {
    name: Spanned<String>,
    mass_g: Spanned<f64>,
    #[serde(deserialize_with = "crate::data::toml_check::exact")]
    com_mm: Spanned<[f64; 3]>,
    #[serde(deserialize_with = "crate::data::toml_check::exact")]
    inertia_gcm2: Spanned<[[f64; 3]; 3]>,
    cor: Spanned<f64>,
    loft_deg: Option<Spanned<f64>>,
    bulge_mm: Spanned<f64>,
    roll_mm: Spanned<f64>,
    #[serde(default, deserialize_with = "crate::data::toml_check::exact_opt")]
    hosel_mm: Option<Spanned<[f64; 3]>>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct RawBall {
    mass_g: Spanned<f64>,
    radius_mm: Spanned<f64>,
    inertia_gcm2: Spanned<f64>,
}

/// Read and validate a club file (its user-defined effects offered to model searches).
pub fn read_club(path: &Path) -> Result<ClubSpec, DataError> {
    read_club_as(path, Offer::Candidate)
}

/// [`read_club`], its `[[define_effect]]` tables registered as `offer` says (a synth world's
/// base club: [`Offer::WorldOnly`]).
pub fn read_club_as(path: &Path, offer: Offer) -> Result<ClubSpec, DataError> {
    let text = read_text(path)?;
    parse_club_as(path, &text, offer)
}

/// Parse and validate club-file text (`path` is used in messages only; its user-defined
/// effects offered to model searches).
pub fn parse_club(path: &Path, text: &str) -> Result<ClubSpec, DataError> {
    parse_club_as(path, text, Offer::Candidate)
}

/// [`parse_club`], its `[[define_effect]]` tables registered as `offer` says (a club's own text
/// read back: [`Offer::Reread`]).
pub fn parse_club_as(path: &Path, text: &str, offer: Offer) -> Result<ClubSpec, DataError> {
    let ctx = TomlDoc::new(path, text);
    let raw: RawFile = ctx.parse("a club file has [club] name, mass_g, com_mm, inertia_gcm2, cor, bulge_mm, roll_mm and optional loft_deg, hosel_mm; [ball] mass_g, radius_mm, inertia_gcm2; optional [[effect]] and [[define_effect]] tables")?;
    // User-defined effects first, so that [[effect]] tables can name them.
    super::effect_defs::register_definitions(path, text, &raw.define_effect, offer)?;
    let c = &raw.club;
    let mass_g = ctx.ranged(&c.mass_g, "club.mass_g", limits::CLUB_MASS_G)?;
    let com = ctx.each_ranged(&c.com_mm, "club.com_mm", limits::CLUB_COM_MM)?;
    limits::check_club_com_x_mm(com[0]).map_err(|m| ctx.err(c.com_mm.span(), "club.com_mm", m))?;
    for x in c.inertia_gcm2.get_ref().iter().flatten() {
        limits::CLUB_INERTIA_GCM2
            .check(*x)
            .map_err(|m| ctx.err(c.inertia_gcm2.span(), "club.inertia_gcm2", m))?;
    }
    let inertia = Matrix3::from_fn(|i, j| gcm2(c.inertia_gcm2.get_ref()[i][j]));
    validate_inertia(&inertia, "club.inertia_gcm2")
        .map_err(|e| ctx.err(c.inertia_gcm2.span(), "club.inertia_gcm2", e.problem))?;
    check_least_moment(&inertia, mass_g)
        .map_err(|m| ctx.err(c.inertia_gcm2.span(), "club.inertia_gcm2", m))?;
    let cor = *c.cor.get_ref();
    if !(cor.is_finite() && cor > 0.0 && cor <= 1.0) {
        return Err(ctx.err(
            c.cor.span(),
            "club.cor",
            format!("must be in (0, 1], got {}", crate::limits::fmt_value(cor)),
        ));
    }
    let loft = match &c.loft_deg {
        Some(l) => Some(deg(ctx.ranged(
            l,
            "club.loft_deg",
            limits::STATIC_LOFT_DEG,
        )?)),
        None => None,
    };
    let hosel_mm = match &c.hosel_mm {
        Some(h) => ctx.each_ranged(h, "club.hosel_mm", limits::HOSEL_MM)?,
        None => DRIVER_HOSEL_MM,
    };
    let bulge_mm = ctx.ranged(&c.bulge_mm, "club.bulge_mm", limits::FACE_RADIUS_MM)?;
    let roll_mm = ctx.ranged(&c.roll_mm, "club.roll_mm", limits::FACE_RADIUS_MM)?;
    if bulge_mm < roll_mm {
        return Err(ctx.err(
            c.bulge_mm.span(),
            "club.bulge_mm",
            format!(
                "{bulge_mm} mm is below roll_mm = {roll_mm} mm; the face is a torus whose \
                 heel-toe radius (bulge) is at least its crown-sole radius (roll), as on every \
                 wood"
            ),
        ));
    }
    let (ball_mass_g, ball_radius_mm, ball_inertia) = read_ball(&ctx, &raw.ball)?;

    let nominal = ModelParams {
        club_mass_kg: g(mass_g),
        club_com_m: Vector3::new(mm(com[0]), mm(com[1]), mm(com[2])),
        club_inertia_kgm2: inertia,
        cor,
        bulge_m: mm(bulge_mm),
        roll_m: mm(roll_mm),
        ball_mass_kg: g(ball_mass_g),
        ball_radius_m: mm(ball_radius_mm),
        ball_inertia_kgm2: gcm2(ball_inertia),
        ball_offset_y_m: 0.0,
        ball_offset_z_m: 0.0,
        tangential_restitution: 0.0,
        friction_mu: None,
        cor_speed_k_s_per_m: 0.0,
        cor_power_q: 0.0,
        cor_radial_c_per_m2: 0.0,
        cor_radial_moment_per_m: [0.0; 2],
        cor_radial_offset: 0.0,
        loft_bias_rad: 0.0,
        face_bias_rad: 0.0,
        hosel_m: Vector3::new(mm(hosel_mm[0]), mm(hosel_mm[1]), mm(hosel_mm[2])),
        contact_time_s: 0.0,
        tangential_restitution_slope: 0.0,
        gear_restitution: 0.0,
        user: Default::default(),
    };

    let mut effects = Vec::with_capacity(raw.effect.len());
    for (i, table) in raw.effect.iter().enumerate() {
        effects.push(parse_effect(&ctx, "effect", i, table)?);
    }
    let name = c.name.get_ref();
    if name.chars().any(char::is_control) {
        return Err(ctx.err(
            c.name.span(),
            "club.name",
            format!(
                "'{}' holds a control character (an escape, a line break, a tab); the name is \
                 printed in tables and terminals: use printable text",
                super::escape(name)
            ),
        ));
    }
    let club = ClubSpec::new(name.clone(), loft, nominal, effects).map_err(|e| {
        DataError::file(
            path,
            format!("the club with its effects is not physical: {e}"),
        )
    })?;
    club.check_com_behind_face().map_err(|m| {
        DataError::file(
            path,
            format!("the club with its effects is not physical: {m}"),
        )
    })?;
    Ok(club)
}

/// Parse one effect table shaped like a club file's `[[effect]]` (`name`, optional `group`, the
/// effect's parameter keys), from `text` of the file at `path`. `array` names the table array in
/// messages (`effect`, `hidden`, …) and `index` the table's position in it.
pub fn parse_effect_table(
    path: &Path,
    text: &str,
    array: &str,
    index: usize,
    table: &Spanned<toml::Table>,
) -> Result<Effect, DataError> {
    parse_effect(&TomlDoc::new(path, text), array, index, table)
}

fn parse_effect(
    ctx: &TomlDoc<'_>,
    array: &str,
    index: usize,
    table: &Spanned<toml::Table>,
) -> Result<Effect, DataError> {
    let span = table.span();
    let t = table.get_ref();
    let here = |msg: String| ctx.err(span.clone(), &format!("{array}[{index}]"), msg);
    let name = match t.get("name") {
        Some(toml::Value::String(s)) => s.as_str(),
        Some(_) => return Err(here("`name` must be a string".into())),
        None => {
            return Err(here(format!(
                "missing `name`; one of: {}",
                EffectId::all_names()
            )))
        }
    };
    let kind = EffectId::from_name(name).ok_or_else(|| {
        let names = EffectId::all_names();
        let hint = super::toml_check::did_you_mean(name, names.split(", "))
            .map_or_else(String::new, |m| format!(" (did you mean '{m}'?)"));
        here(format!(
            "unknown effect '{name}'{hint}; the library has: {names} (a user-defined effect \
             needs its [[define_effect]] table in this file or an --effect-defs file)",
        ))
    })?;
    let group = match t.get("group") {
        Some(toml::Value::String(s)) if !s.is_empty() => Some(s.clone()),
        Some(_) => return Err(here(format!("{name}: `group` must be a non-empty string"))),
        None => None,
    };
    let specs = kind.params();
    let allowed = || {
        let mut s = String::from("name, group");
        for p in specs {
            let _ = write!(s, ", {}", p.key);
        }
        s
    };
    for key in t.keys() {
        if key != "name" && key != "group" && !specs.iter().any(|p| p.key == key) {
            let keys = allowed();
            let hint = super::toml_check::did_you_mean(key, keys.split(", "))
                .map_or_else(String::new, |m| format!(" (did you mean `{m}`?)"));
            return Err(here(format!(
                "{name}: unknown key `{key}`{hint}; allowed: {keys}"
            )));
        }
    }
    let mut values = Vec::with_capacity(specs.len());
    for p in specs {
        let v = match t.get(p.key) {
            Some(toml::Value::Float(f)) => *f,
            Some(toml::Value::Integer(i)) => *i as f64,
            Some(_) => {
                return Err(here(format!(
                    "{name}.{} must be a number ({})",
                    p.key, p.unit
                )))
            }
            None => {
                return Err(here(format!(
                    "{name}: missing `{}` ({}, {})",
                    p.key, p.unit, p.doc
                )))
            }
        };
        values.push(v);
    }
    Effect::new(kind, &values, group).map_err(|e| here(e.to_string()))
}

/// A head a club file would refuse ([`check_head`]): the club-file key and what is wrong.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{key}: {problem}")]
pub struct HeadError {
    /// The club-file key (`club.mass_g`, …).
    pub key: &'static str,
    /// What is wrong with its value.
    pub problem: HeadProblem,
}

/// The `[ball]` table's mass (g), radius (mm) and inertia (g·cm²), each in its physical range,
/// and an inertia no more than a thin shell of that mass and radius has.
fn read_ball(ctx: &TomlDoc, b: &RawBall) -> Result<(f64, f64, f64), DataError> {
    let mass_g = ctx.ranged(&b.mass_g, "ball.mass_g", limits::BALL_MASS_G)?;
    let radius_mm = ctx.ranged(&b.radius_mm, "ball.radius_mm", limits::BALL_RADIUS_MM)?;
    let inertia = ctx.ranged(
        &b.inertia_gcm2,
        "ball.inertia_gcm2",
        limits::BALL_INERTIA_GCM2,
    )?;
    // No ball has more inertia about its centre than a thin shell of its mass and radius,
    // (2/3)·m·r² (a solid ball has 2/5; a golf ball about 0.37-0.40).
    let shell_gcm2 = 2.0 / 3.0 * mass_g * (radius_mm / 10.0).powi(2);
    if inertia > shell_gcm2 {
        return Err(ctx.err(
            b.inertia_gcm2.span(),
            "ball.inertia_gcm2",
            format!(
                "{} g·cm² is more than a ball of {} g and radius {} mm can have: at most {} \
                 g·cm², its whole mass at its surface ((2/3)·m·r²; a golf ball has about 80)",
                crate::limits::fmt_value(inertia),
                crate::limits::fmt_value(mass_g),
                crate::limits::fmt_value(radius_mm),
                crate::limits::fmt_value(floor_to_digits(shell_gcm2, 4))
            ),
        ));
    }
    Ok((mass_g, radius_mm, inertia))
}

/// `Err` stating the least principal moment of `inertia` (kg·m², a valid tensor) when it is
/// below the least a head of `mass_g` grams can have ([`limits::min_head_moment_gcm2`]).
fn check_least_moment(inertia: &Matrix3<f64>, mass_g: f64) -> Result<(), String> {
    let least = inertia.symmetric_eigenvalues().min() * 1e7;
    let floor = limits::min_head_moment_gcm2(mass_g);
    if least >= floor {
        return Ok(());
    }
    // The bound rounded up, so that a moment at the printed bound is one a head may have.
    let scale = 10f64.powi(3 - floor.log10().floor() as i32);
    Err(format!(
        "principal moment {} g·cm² is below the least a {} g head can have, {} g·cm² (its \
         whole mass packed at the density of osmium, {} g/cm³, into a rod as long as the \
         largest head, {} mm, about the rod's axis)",
        limits::fmt_value(format!("{least:.3e}").parse().unwrap_or(least)),
        limits::fmt_value(mass_g),
        limits::fmt_value((floor * scale).ceil() / scale),
        limits::fmt_value(limits::DENSEST_G_CM3),
        limits::fmt_value(limits::HEAD_REACH_MM),
    ))
}

/// `v` (> 0) rounded down to `digits` significant digits: a bound printed that way is one a
/// value may take (138.829 prints as 138.8, not 138.83, which is refused).
fn floor_to_digits(v: f64, digits: i32) -> f64 {
    let scale = 10f64.powi(digits - 1 - v.log10().floor() as i32);
    (v * scale).floor() / scale
}

/// What is wrong with a head's value ([`HeadError`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum HeadProblem {
    /// Outside its physical range.
    #[error(transparent)]
    Limit(#[from] LimitError),
    /// An inertia tensor no body has (the problem as the inertia check states it).
    #[error("{0}")]
    Inertia(String),
}

/// Check a head made in code (a what-if's or a design variant's, from a club file's nominal
/// head) against the limits a club file is read with ([`parse_club`]): mass, CoM (behind the
/// face), every inertia entry and the tensor's physical validity, the face radii. `Err` names
/// the club-file key, the value and the allowed range, so that a scaling or a move cannot make
/// a head the club file itself would refuse.
pub fn check_head(p: &ModelParams) -> Result<(), HeadError> {
    let at = |key: &'static str, m: LimitError| HeadError {
        key,
        problem: HeadProblem::Limit(m),
    };
    // In the file's units, the shortest decimal of each value (as a club file is written).
    let (in_g, in_mm) = (|v| file_value(v, g, 1e3), |v| file_value(v, mm, 1e3));
    limits::CLUB_MASS_G
        .check(in_g(p.club_mass_kg))
        .map_err(|m| at("club.mass_g", m))?;
    let com_mm = p.club_com_m.map(in_mm);
    for x in com_mm.iter() {
        limits::CLUB_COM_MM
            .check(*x)
            .map_err(|m| at("club.com_mm", m))?;
    }
    limits::check_club_com_x_mm(com_mm.x).map_err(|m| at("club.com_mm", m))?;
    for x in p.club_inertia_kgm2.iter() {
        let r = limits::CLUB_INERTIA_GCM2;
        // A computed entry (a scaled tensor) is stated to 6 digits, not as 2.8429999999999995e9.
        r.check(file_value(*x, gcm2, 1e7)).map_err(|_| {
            at(
                "club.inertia_gcm2",
                r.check(limits::shown_outside(*x * 1e7, &r)).unwrap_err(),
            )
        })?;
    }
    let inertia_problem = |problem| HeadError {
        key: "club.inertia_gcm2",
        problem: HeadProblem::Inertia(problem),
    };
    validate_inertia(&p.club_inertia_kgm2, "club.inertia_gcm2")
        .map_err(|e| inertia_problem(e.problem))?;
    check_least_moment(&p.club_inertia_kgm2, in_g(p.club_mass_kg)).map_err(inertia_problem)?;
    for (key, r) in [("club.bulge_mm", p.bulge_m), ("club.roll_mm", p.roll_m)] {
        limits::FACE_RADIUS_MM
            .check(in_mm(r))
            .map_err(|m| at(key, m))?;
    }
    Ok(())
}

/// [`club_toml`], checked to read back as a valid club before it is written to `path`: no
/// infinite, undefined or unphysical value reaches a club file.
pub fn club_toml_checked(spec: &ClubSpec, comment: &str, path: &Path) -> Result<String, DataError> {
    let text = club_toml(spec, comment);
    parse_club_as(path, &text, Offer::Reread).map_err(|e| {
        DataError::file(
            path,
            format!("not written: the club would not read back ({})", e.message),
        )
    })?;
    Ok(text)
}

/// An effect as a club file's `[[effect]]` table: `name`, its parameters, optional `group`.
pub fn effect_table(e: &Effect) -> toml::Table {
    let mut t = toml::Table::new();
    t.insert(
        "name".into(),
        toml::Value::String(e.kind().name().to_owned()),
    );
    for (spec, v) in e.kind().params().iter().zip(e.values()) {
        t.insert(spec.key.to_owned(), toml::Value::Float(*v));
    }
    if let Some(g) = e.group() {
        t.insert("group".into(), toml::Value::String(g.to_owned()));
    }
    t
}

/// The shortest decimal (fewest significant digits) of a value `si` in SI units that the
/// reader's conversion `from_file` turns back into exactly `si`: a club read from a file with
/// `mass_g = 204` is written back as 204, not as `0.204 kg × 1000 = 204.00000000000003`.
fn file_value(si: f64, from_file: fn(f64) -> f64, per_si: f64) -> f64 {
    let plain = si * per_si;
    (1..=17)
        .filter_map(|digits| format!("{:.*e}", digits - 1, plain).parse::<f64>().ok())
        .find(|&d| from_file(d) == si)
        .unwrap_or(plain)
}

/// Club-file text for `spec`, with `comment` lines at the top. Reads back to the same club
/// (bit for bit: every value is the shortest decimal the reader converts back to it).
/// Written by serde from the reader's own raw structs.
pub fn club_toml(spec: &ClubSpec, comment: &str) -> String {
    let p = &spec.nominal;
    let sp = |x| Spanned::new(0..0, x);
    let in_mm = |v: f64| file_value(v, mm, 1e3);
    let in_g = |v: f64| file_value(v, g, 1e3);
    let in_gcm2 = |v: f64| file_value(v, gcm2, 1e7);
    let c = p.club_com_m.map(in_mm);
    let i = p.club_inertia_kgm2.map(in_gcm2);
    let h = p.hosel_m.map(in_mm);
    let hosel = [h.x, h.y, h.z];
    // The definitions of the user-defined effects it uses, so the file stays usable alone.
    let mut define_effect = Vec::new();
    let mut defined: Vec<&str> = Vec::new();
    for u in spec.effects.iter().filter_map(|e| e.kind().user()) {
        if !defined.contains(&u.name) {
            defined.push(u.name);
            define_effect.push(Spanned::new(0..0, super::effect_defs::raw_definition_of(u)));
        }
    }
    let raw = RawFile {
        club: RawClub {
            name: Spanned::new(0..0, spec.name.clone()),
            mass_g: sp(in_g(p.club_mass_kg)),
            com_mm: Spanned::new(0..0, [c.x, c.y, c.z]),
            inertia_gcm2: Spanned::new(
                0..0,
                std::array::from_fn(|r| std::array::from_fn(|k| i[(r, k)])),
            ),
            cor: sp(p.cor),
            loft_deg: spec
                .static_loft_rad
                .map(|l| sp(file_value(l, deg, 180.0 / std::f64::consts::PI))),
            bulge_mm: sp(in_mm(p.bulge_m)),
            roll_mm: sp(in_mm(p.roll_m)),
            hosel_mm: (hosel != DRIVER_HOSEL_MM).then(|| Spanned::new(0..0, hosel)),
        },
        ball: RawBall {
            mass_g: sp(in_g(p.ball_mass_kg)),
            radius_mm: sp(in_mm(p.ball_radius_m)),
            inertia_gcm2: sp(in_gcm2(p.ball_inertia_kgm2)),
        },
        define_effect,
        effect: spec
            .effects
            .iter()
            .map(|e| Spanned::new(0..0, effect_table(e)))
            .collect(),
    };
    let mut s = String::new();
    for line in comment.lines() {
        let _ = writeln!(s, "# {line}");
    }
    s.push_str(&toml::to_string(&raw).expect("a club is plain TOML data"));
    s
}

#[cfg(test)]
#[path = "club_file_tests.rs"]
mod tests;

#[cfg(test)]
mod paper_driver_tests {
    use super::*;

    #[test]
    fn shipped_paper_driver_matches_the_code_constant() {
        let path = Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/configs/clubs/paper_driver.toml"
        ));
        let file = read_club(path).unwrap().nominal;
        let code = ModelParams::paper_driver();
        assert!((file.club_inertia_kgm2 - code.club_inertia_kgm2).amax() < 1e-15);
        assert!((file.club_com_m - code.club_com_m).amax() < 1e-15);
        for (a, b) in [
            (file.club_mass_kg, code.club_mass_kg),
            (file.cor, code.cor),
            (file.bulge_m, code.bulge_m),
            (file.roll_m, code.roll_m),
            (file.ball_mass_kg, code.ball_mass_kg),
            (file.ball_radius_m, code.ball_radius_m),
            (file.ball_inertia_kgm2, code.ball_inertia_kgm2),
        ] {
            assert!((a - b).abs() <= 1e-12 * b.abs(), "{a} vs {b}");
        }
    }
}
