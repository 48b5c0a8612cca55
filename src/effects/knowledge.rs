//! What the library knows about an effect beyond its law: the launch patterns it produces
//! (compare's signature table), what a fitted value outside its plausible range stands in for,
//! the measurement that pins it down, and which delivery variables must vary for the shots to
//! identify it.
//!
//! Each effect file declares all four next to its law (`SIGNATURE`, `STAND_IN`, `SEPARATE_BY`,
//! `NEEDS`); the `library!` registration dispatches to them, and every list elsewhere (compare's
//! hints, diagnose's honest reading, the variation check) is derived from the files. A test in
//! this module fails when an effect leaves any of them empty.

use serde::Serialize;

use crate::physics::delivery_vars::DeliveryVar;
use crate::physics::LaunchComponent;

/// The shape of an error pattern a model leaves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Pattern {
    /// A uniform bias: the mean error is not zero.
    Bias,
    /// The mean error differs between groups (shafts): the effect fitted per group.
    GroupBias,
    /// The error changes with a delivery variable (its shots-file column).
    Trend(&'static str),
}

/// One launch pattern an effect produces when it is present and the model lacks it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SignatureRow {
    /// Error component.
    pub component: LaunchComponent,
    /// Pattern of its error.
    pub pattern: Pattern,
    /// Why the effect moves that component that way, in a few words.
    pub why: &'static str,
}

/// Build a signature row (for the effect files).
pub(crate) const fn row(
    component: LaunchComponent,
    pattern: Pattern,
    why: &'static str,
) -> SignatureRow {
    SignatureRow {
        component,
        pattern,
        why,
    }
}

/// What a fitted value outside the plausible range behaves like: the physics that moves the
/// same launch components the same way, below the range and above it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StandIn {
    /// For a value below the plausible range.
    pub below: &'static str,
    /// For a value above it.
    pub above: &'static str,
}

impl StandIn {
    /// The same reading on either side of the range.
    pub const fn either(text: &'static str) -> Self {
        Self {
            below: text,
            above: text,
        }
    }
}

/// Which delivery variables the shots must vary in for an effect to be more than a constant
/// offset of the launch (`crate::fit::check_variation`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Needs {
    /// Shots that differ in any way identify it; the reason says why nothing in particular
    /// must vary.
    Nothing(&'static str),
    /// At least one of these variables must vary; the reason says why.
    AnyOf(&'static [DeliveryVar], &'static str),
}

impl Needs {
    /// The reason, whichever the case.
    pub const fn reason(&self) -> &'static str {
        match self {
            Needs::Nothing(why) | Needs::AnyOf(_, why) => why,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::EffectKind;
    use super::*;

    /// Every effect declares a signature, a stand-in reading on both sides, a separating
    /// measurement and its variation needs, none of them empty.
    #[test]
    fn every_effect_owns_all_its_knowledge() {
        for k in EffectKind::ALL {
            assert!(!k.signature().is_empty(), "{k}: no signature row");
            for r in k.signature() {
                assert!(
                    !r.why.trim().is_empty(),
                    "{k}: a signature row without a reason"
                );
            }
            let s = k.stand_in();
            assert!(!s.below.trim().is_empty(), "{k}: no stand-in text below");
            assert!(!s.above.trim().is_empty(), "{k}: no stand-in text above");
            assert!(
                !k.separate_by().trim().is_empty(),
                "{k}: no separating measurement"
            );
            assert!(
                !k.needs().reason().trim().is_empty(),
                "{k}: no variation reason"
            );
            if let Needs::AnyOf(vars, _) = k.needs() {
                assert!(!vars.is_empty(), "{k}: AnyOf with no variable");
            }
        }
    }

    /// A trend row names a delivery variable compare can correlate with.
    #[test]
    fn trend_rows_name_delivery_columns() {
        let known: Vec<&str> = DeliveryVar::ALL
            .iter()
            .map(|v| v.column())
            .chain(["impact_r_mm"])
            .collect();
        for k in EffectKind::ALL {
            for r in k.signature() {
                if let Pattern::Trend(v) = r.pattern {
                    assert!(known.contains(&v), "{k}: trend against unknown column {v}");
                }
            }
        }
    }
}
