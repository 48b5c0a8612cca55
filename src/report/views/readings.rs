//! The readings of a diagnosis as view models: aliases, rivals, ambiguities, the unresolved
//! candidate, the rival-family checks and explained aliases.

use serde::Serialize;

use super::{briefs, Brief};
use crate::diagnose::honest::{self, Alias, Ambiguity, Rival, Unresolved};
use crate::diagnose::rival_family::FamilyCheck;

/// Two parameters the data cannot tell apart.
#[derive(Debug, Clone, Serialize)]
pub struct AliasView {
    /// First parameter.
    pub a: String,
    /// Second parameter.
    pub b: String,
    /// Correlation of their estimates.
    pub r: f64,
    /// What would separate them.
    pub separate_by: String,
}

impl AliasView {
    /// The view of `a`.
    pub fn of(a: &Alias) -> Self {
        Self {
            a: a.a.clone(),
            b: a.b.clone(),
            r: a.r,
            separate_by: a.separate_by.clone(),
        }
    }
}

/// A candidate that explained nearly the same signal as a selected effect.
#[derive(Debug, Clone, Serialize)]
pub struct RivalView {
    /// The candidate.
    pub effect: String,
    /// Its values.
    pub params: Vec<Brief>,
    /// How much worse it fits (negative: better).
    pub margin_gap: f64,
    /// Correlation of the changes the two make to the predictions.
    pub r: f64,
    /// Its values are plausible.
    pub plausible: bool,
}

impl RivalView {
    /// The view of `r`.
    pub fn of(r: &Rival) -> Self {
        Self {
            effect: r.label.clone(),
            params: briefs(&r.params),
            margin_gap: r.margin_gap,
            r: r.r,
            plausible: r.plausible,
        }
    }
}

/// A selected effect with its rivals, and whether the reading is ambiguous.
#[derive(Debug, Clone, Serialize)]
pub struct AmbiguityView {
    /// The selected effect.
    pub selected: String,
    /// Its final values.
    pub values: Vec<Brief>,
    /// Two plausible readings the data cannot tell apart.
    pub ambiguous: bool,
    /// The rivals, best first.
    pub rivals: Vec<RivalView>,
    /// One line of text.
    pub text: String,
}

impl AmbiguityView {
    /// The view of `a`.
    pub fn of(a: &Ambiguity) -> Self {
        Self {
            selected: a.selected.clone(),
            values: briefs(&a.estimates),
            ambiguous: a.is_ambiguous(),
            rivals: a.rivals.iter().map(RivalView::of).collect(),
            text: a.text(),
        }
    }
}

/// A candidate with a plausible value the shots do not yet decide.
#[derive(Debug, Clone, Serialize)]
pub struct UnresolvedView {
    /// The candidate.
    pub effect: String,
    /// Its values.
    pub params: Vec<Brief>,
    /// Its cross-validated gain.
    pub gain: f64,
    /// The penalty it had to beat.
    pub penalty: f64,
    /// The selected effects it resembles, with the correlation.
    pub alike: Vec<Alike>,
    /// How many times the shots would decide it.
    pub shots_factor: f64,
    /// One line of text.
    pub text: String,
}

/// A candidate and its correlation with another.
#[derive(Debug, Clone, Serialize)]
pub struct Alike {
    /// The candidate.
    pub candidate: String,
    /// Correlation.
    pub r: f64,
}

/// `(label, r)` pairs as [`Alike`]s.
pub fn alike(pairs: &[(String, f64)]) -> Vec<Alike> {
    pairs
        .iter()
        .map(|(l, r)| Alike {
            candidate: l.clone(),
            r: *r,
        })
        .collect()
}

impl UnresolvedView {
    /// The view of `u`.
    pub fn of(u: &Unresolved) -> Self {
        Self {
            effect: u.label.clone(),
            params: briefs(&u.params),
            gain: u.gain,
            penalty: u.penalty,
            alike: alike(&u.alike),
            shots_factor: u.growth,
            text: u.text(),
        }
    }
}

/// A selected effect against its family's general form.
#[derive(Debug, Clone, Serialize)]
pub struct FamilyCheckView {
    /// The effect.
    pub effect: String,
    /// Its own gain.
    pub own_gain: f64,
    /// Its gain over the family's general form.
    pub gain_over_family: f64,
    /// The penalty it had to beat.
    pub penalty: f64,
    /// It stands in for a location in the family.
    pub location_in_family: bool,
    /// The form's gain, when checked.
    pub form_gain: Option<f64>,
    /// The form's penalty, when checked.
    pub form_penalty: Option<f64>,
    /// For a location form: its own gain over the other selected effects and a constant per
    /// launch component it moves (penalty `penalty`).
    pub gain_over_level: Option<f64>,
    /// It is a stand-in for the family.
    pub stand_in: bool,
}

impl FamilyCheckView {
    /// The view of `f`.
    pub fn of(f: &FamilyCheck) -> Self {
        Self {
            effect: f.label.clone(),
            own_gain: f.own_gain,
            gain_over_family: f.gain_over_family,
            penalty: f.penalty,
            location_in_family: f.location_in_family,
            form_gain: f.form.map(|f| f.0),
            form_penalty: f.form.map(|f| f.1),
            gain_over_level: f.over_level,
            stand_in: f.is_stand_in(),
        }
    }
}

/// A plausible candidate selected in place of one with more evidence and an implausible value.
#[derive(Debug, Clone, Serialize)]
pub struct ExplainedAliasView {
    /// The plausible candidate selected.
    pub selected: String,
    /// The candidate with more evidence and an implausible value.
    pub instead_of: String,
    /// Correlation of the changes they make to the predictions.
    pub r: f64,
}

impl ExplainedAliasView {
    /// The view of `a`.
    pub fn of(a: &honest::ExplainedAlias) -> Self {
        Self {
            selected: a.selected.clone(),
            instead_of: a.instead_of.clone(),
            r: a.r,
        }
    }
}
