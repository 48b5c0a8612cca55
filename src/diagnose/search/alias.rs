//! A stand-in against its plausible alias (`docs/diagnose-selection.md`, "A stand-in and its
//! plausible alias"): the one option of a swap round that is not scored by the CV χ² alone.
//!
//! A selected stand-in (a value outside its plausible range) is not a physical reading of the
//! data: it is a library effect's parameter standing for physics the library lacks. Its model
//! therefore claims one ingredient more than the numbers in its layout: the unknown physics
//! the stand-in's value is a proxy for. When an unselected candidate that changed the
//! predictions alike at the stand-in's step (its *kin*, correlation above
//! [`STRONG_CORRELATION`]) replaces it with the same number of parameters and a plausible
//! value, the replacement reads the same signal as known physics. By the penalty's own rule
//! (`ln n` for every parameter a model adds), the stand-in's model is charged that unknown
//! ingredient's one parameter: the replacement is made when its cross-validated χ² is worse by
//! less than `ln n`. The rule cannot add an effect, change the number of parameters or leave a
//! new stand-in (every value the refitted model has must be plausible where the current one's
//! was), so selections without stand-ins (the null worlds, the paper world) never meet it.

use nalgebra::DVector;

use super::super::evaluate::EffectFit;
use super::super::honest;
use super::Search;
use crate::effects::EffectId;
use crate::fit::calibrate::STRONG_CORRELATION;
use crate::fit::{EffectRequest, ParamEstimate, ParamLayout};

impl Search<'_> {
    /// The kinds of the effects in `layout` with a value at `theta` outside its plausible range.
    pub(in crate::diagnose) fn implausible_kinds(
        layout: &ParamLayout,
        theta: &DVector<f64>,
    ) -> Vec<EffectId> {
        let mut out = Vec::new();
        for (i, e) in layout.effects().iter().enumerate() {
            let implausible = e
                .kind
                .params()
                .iter()
                .zip(&theta.as_slice()[layout.range(i)])
                .any(|(s, &value)| {
                    let p = ParamEstimate {
                        effect: e.kind.name(),
                        group: e.group.clone(),
                        param: s.key,
                        unit: s.unit,
                        value,
                        stderr: None,
                        at_bound: false,
                    };
                    honest::is_plausible(&p) == Some(false)
                });
            if implausible && !out.contains(&e.kind) {
                out.push(e.kind);
            }
        }
        out
    }

    /// Does the current model have a stand-in (the gate of the swap rounds)?
    pub(in crate::diagnose) fn has_stand_in(&self) -> bool {
        !Self::implausible_kinds(&self.base, &self.theta_base).is_empty()
    }

    /// When replacing the selected stand-in `o` by `c` (fitted as `f`, `k_net` parameters
    /// added net) is the plausible-alias case of the module docs: the correlation with which
    /// `c` is the stand-in's kin.
    pub(in crate::diagnose) fn plausible_alias(
        &self,
        o: usize,
        c: &EffectRequest,
        f: &EffectFit,
        k_net: f64,
    ) -> Option<f64> {
        if k_net != 0.0 || !f.result.eligible() || !f.result.plausible() {
            return None;
        }
        let kind = self.selected[o].kind();
        let (_, _, kin) = self.kin_of.iter().find(|(_, r, _)| r.kind() == kind)?;
        let r = kin.iter().find(|(k, _)| k == c)?.1;
        let before = Self::implausible_kinds(&self.base, &self.theta_base);
        if !before.contains(&kind) || r.abs() <= STRONG_CORRELATION {
            return None;
        }
        let (layout, run) = f.fit.as_ref()?;
        let after = Self::implausible_kinds(layout, &run.theta);
        after
            .iter()
            .all(|k| *k != kind && before.contains(k))
            .then_some(r)
    }
}
