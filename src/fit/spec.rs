//! Which effects a fit frees, and how their parameters are laid out in one vector.
//!
//! On the command line an effect list reads `added_mass@group,ball_offset,cor_speed@A`:
//! `name` is one global effect, `name@group` one effect per group present in the shots, and
//! `name@A` one effect applying to group `A` only.

use nalgebra::DVector;

use super::FitError;
#[cfg(test)]
use crate::effects::EffectKind;
use crate::effects::{Effect, EffectError, EffectId, ParamSpec};

/// The keyword that asks for one effect per group.
pub const PER_GROUP: &str = "group";

/// One requested effect, before it is expanded over the groups of the shots.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum EffectRequest {
    /// `name`: one effect for all shots.
    Global(EffectId),
    /// `name@group`: one effect per group present in the shots.
    PerGroup(EffectId),
    /// `name@A`: one effect for the shots of group `A` only.
    OneGroup(EffectId, String),
}

impl EffectRequest {
    /// The effect kind.
    pub fn kind(&self) -> EffectId {
        match self {
            Self::Global(k) | Self::PerGroup(k) | Self::OneGroup(k, _) => *k,
        }
    }

    /// As written on the command line.
    pub fn label(&self) -> String {
        match self {
            Self::Global(k) => k.name().to_owned(),
            Self::PerGroup(k) => format!("{}@{PER_GROUP}", k.name()),
            Self::OneGroup(k, g) => format!("{}@{g}", k.name()),
        }
    }

    /// Expand over the `groups` present in the shots (sorted, distinct).
    pub fn expand(&self, groups: &[String]) -> Result<Vec<FreeEffect>, FitError> {
        match self {
            Self::Global(kind) => Ok(vec![FreeEffect {
                kind: *kind,
                group: None,
            }]),
            Self::PerGroup(kind) => {
                if groups.len() < 2 {
                    return Err(FitError::PerGroupNeedsGroups {
                        effect: kind.name(),
                        groups: groups.to_vec(),
                    });
                }
                Ok(groups
                    .iter()
                    .map(|g| FreeEffect {
                        kind: *kind,
                        group: Some(g.clone()),
                    })
                    .collect())
            }
            Self::OneGroup(kind, g) => {
                if !groups.contains(g) {
                    return Err(FitError::UnknownGroup {
                        effect: kind.name(),
                        group: g.clone(),
                        groups: groups.to_vec(),
                    });
                }
                Ok(vec![FreeEffect {
                    kind: *kind,
                    group: Some(g.clone()),
                }])
            }
        }
    }
}

/// Parse one `name`, `name@group` or `name@A`.
pub fn parse_request(text: &str) -> Result<EffectRequest, FitError> {
    let text = text.trim();
    let (name, group) = match text.split_once('@') {
        Some((n, g)) => (n.trim(), Some(g.trim())),
        None => (text, None),
    };
    let kind = EffectId::from_name(name).ok_or_else(|| {
        FitError::Effect(EffectError::UnknownName {
            name: name.to_owned(),
        })
    })?;
    Ok(match group {
        None => EffectRequest::Global(kind),
        Some("") => {
            return Err(FitError::BadEffectList(format!(
                "'{text}': empty group after '@'"
            )))
        }
        Some(PER_GROUP) => EffectRequest::PerGroup(kind),
        Some(g) => EffectRequest::OneGroup(kind, g.to_owned()),
    })
}

/// Parse a comma-separated effect list.
pub fn parse_effect_list(text: &str) -> Result<Vec<EffectRequest>, FitError> {
    let list: Vec<EffectRequest> = text
        .split(',')
        .filter(|s| !s.trim().is_empty())
        .map(parse_request)
        .collect::<Result<_, _>>()?;
    if list.is_empty() {
        return Err(FitError::BadEffectList(format!(
            "no effect named; the library has: {}",
            EffectId::all_names()
        )));
    }
    Ok(list)
}

/// One effect whose parameters a fit is free to change.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FreeEffect {
    /// Effect kind.
    pub kind: EffectId,
    /// Group it applies to, or `None` for all shots.
    pub group: Option<String>,
}

impl FreeEffect {
    /// `name` or `name@group`.
    pub fn label(&self) -> String {
        match &self.group {
            Some(g) => format!("{}@{g}", self.kind.name()),
            None => self.kind.name().to_owned(),
        }
    }

    /// Does it apply to shots of `group`?
    pub fn applies_to(&self, group: &str) -> bool {
        self.group.as_deref().is_none_or(|g| g == group)
    }

    /// Does χ² have corners in its parameters? The friction coefficient's has one where shots
    /// change between sticking and slipping (and is flat where none slips): the fits scan it
    /// before they start ([`crate::fit::run::scan_nonsmooth_starts`]) and difference it
    /// centrally ([`crate::fit::problem::difference_points`]).
    pub fn is_nonsmooth(&self) -> bool {
        self.kind == crate::effects::EffectKind::Friction
    }
}

/// The free effects and where each one's parameters sit in the fit vector `θ`
/// (physical file units: g, mm, deg, …, in the order of `kind.params()`).
#[derive(Debug, Clone, PartialEq)]
pub struct ParamLayout {
    effects: Vec<FreeEffect>,
    starts: Vec<usize>,
    len: usize,
}

impl ParamLayout {
    /// Lay out `effects`; the same effect (kind and group) twice is an error.
    pub fn new(effects: Vec<FreeEffect>) -> Result<Self, FitError> {
        for (i, a) in effects.iter().enumerate() {
            if effects[..i].iter().any(|b| b == a) {
                return Err(FitError::BadEffectList(format!(
                    "effect '{}' is listed twice",
                    a.label()
                )));
            }
        }
        let mut starts = Vec::with_capacity(effects.len());
        let mut len = 0;
        for e in &effects {
            starts.push(len);
            len += e.kind.params().len();
        }
        Ok(Self {
            effects,
            starts,
            len,
        })
    }

    /// Expand requests over the groups present in the shots.
    pub fn from_requests(requests: &[EffectRequest], groups: &[String]) -> Result<Self, FitError> {
        let mut effects = Vec::new();
        for r in requests {
            effects.extend(r.expand(groups)?);
        }
        Self::new(effects)
    }

    /// Number of parameters.
    pub fn len(&self) -> usize {
        self.len
    }

    /// No parameters at all?
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The free effects, in order.
    pub fn effects(&self) -> &[FreeEffect] {
        &self.effects
    }

    /// Range of `θ` holding effect `i`'s parameters.
    pub fn range(&self, i: usize) -> std::ops::Range<usize> {
        self.starts[i]..self.starts[i] + self.effects[i].kind.params().len()
    }

    /// For each parameter: its effect index and spec.
    pub fn params(&self) -> impl Iterator<Item = (usize, &'static ParamSpec)> + '_ {
        self.effects
            .iter()
            .enumerate()
            .flat_map(|(i, e)| e.kind.params().iter().map(move |s| (i, s)))
    }

    /// `effect@group.key` for each parameter.
    pub fn labels(&self) -> Vec<String> {
        self.params()
            .map(|(i, s)| format!("{}.{}", self.effects[i].label(), s.key))
            .collect()
    }

    /// Default (neutral) values: the start of a fit.
    pub fn defaults(&self) -> DVector<f64> {
        DVector::from_iterator(self.len, self.params().map(|(_, s)| s.default))
    }

    /// Lower physical bounds.
    pub fn lower(&self) -> DVector<f64> {
        DVector::from_iterator(self.len, self.params().map(|(_, s)| s.lower))
    }

    /// Upper physical bounds.
    pub fn upper(&self) -> DVector<f64> {
        DVector::from_iterator(self.len, self.params().map(|(_, s)| s.upper))
    }

    /// The effects with values `theta`, validated against the library's bounds.
    pub fn to_effects(&self, theta: &[f64]) -> Result<Vec<Effect>, EffectError> {
        self.effects
            .iter()
            .enumerate()
            .map(|(i, e)| Effect::new(e.kind, &theta[self.range(i)], e.group.clone()))
            .collect()
    }

    /// A layout with `more` effects appended (used by forward selection).
    pub fn extended(&self, more: &[FreeEffect]) -> Result<Self, FitError> {
        let mut effects = self.effects.clone();
        effects.extend_from_slice(more);
        Self::new(effects)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn groups() -> Vec<String> {
        vec!["A".into(), "B".into(), "C".into()]
    }

    #[test]
    fn parses_and_expands() {
        let r = parse_effect_list("added_mass@group, ball_offset,cor_speed@B").unwrap();
        assert_eq!(r[0], EffectRequest::PerGroup(EffectKind::AddedMass.into()));
        assert_eq!(r[1], EffectRequest::Global(EffectKind::BallOffset.into()));
        assert_eq!(
            r[2],
            EffectRequest::OneGroup(EffectKind::CorSpeed.into(), "B".into())
        );
        let l = ParamLayout::from_requests(&r, &groups()).unwrap();
        assert_eq!(l.len(), 3 + 2 + 1);
        assert_eq!(
            l.labels(),
            [
                "added_mass@A.dm_g",
                "added_mass@B.dm_g",
                "added_mass@C.dm_g",
                "ball_offset.dy_mm",
                "ball_offset.dz_mm",
                "cor_speed@B.k_per_m_s"
            ]
        );
        assert_eq!(l.range(3), 3..5);
    }

    #[test]
    fn rejects_bad_lists() {
        let e = parse_effect_list("added_mas").unwrap_err().to_string();
        assert!(e.contains("unknown effect 'added_mas'") && e.contains("ball_offset"));
        let r = parse_effect_list("added_mass@group").unwrap();
        let e = ParamLayout::from_requests(&r, &["all".into()])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("only one group") && e.contains("'added_mass'"),
            "{e}"
        );
        let r = parse_effect_list("added_mass@D").unwrap();
        assert!(ParamLayout::from_requests(&r, &groups()).is_err());
        let r = parse_effect_list("ball_offset,ball_offset").unwrap();
        assert!(ParamLayout::from_requests(&r, &groups()).is_err());
        assert!(parse_effect_list(" , ").is_err());
    }
}
