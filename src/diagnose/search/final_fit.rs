//! The final fit and the gate of the swap rounds (`docs/diagnose-selection.md`, "The final fit
//! and the gate").
//!
//! The rounds question stand-ins in the selection's own fit, warm-started step after step. The
//! report prints a calibration of the selected effects started afresh from their neutral
//! values, which on a rough χ² surface can land at another optimum, with a value outside its
//! plausible range that the rounds never saw. So before the selection stands, its final fit is
//! made and checked: when it shows a stand-in the rounds' fit did not, the rounds' fit takes
//! its values and the rounds run on it. Each selection is checked once, so this ends.

use nalgebra::DVector;

use super::Search;
use crate::fit::calibrate::{calibrate_data, CalibrateOptions, Calibration};
use crate::fit::{EffectRequest, FitError, ParamLayout};

impl Search<'_> {
    /// The calibration of the selected effects the report prints (`None`: nothing selected).
    pub(super) fn final_calibration(&self) -> Result<Option<Calibration>, FitError> {
        if self.base.is_empty() {
            return Ok(None);
        }
        calibrate_data(
            self.club,
            &self.data,
            self.base.clone(),
            &CalibrateOptions {
                max_iters: self.opts.max_iters,
                ..CalibrateOptions::default()
            },
            None,
        )
        .map(Some)
    }

    /// Check the final fit of the current selection (once per selection: `checked` lists the
    /// selections already checked). When it shows a stand-in the rounds' fit does not, the
    /// rounds' fit takes its values and `true` is returned: the rounds are to run again.
    pub(in crate::diagnose) fn adopt_final_stand_ins(
        &mut self,
        checked: &mut Vec<Vec<String>>,
    ) -> Result<bool, FitError> {
        let labels: Vec<String> = self.selected.iter().map(EffectRequest::label).collect();
        if checked.contains(&labels) {
            return Ok(false);
        }
        checked.push(labels.clone());
        let Some(cal) = self.final_calibration()? else {
            return Ok(false);
        };
        let theta = DVector::from_iterator(cal.params.len(), cal.params.iter().map(|p| p.value));
        let unseen = Self::unseen_stand_in(&self.base, &self.theta_base, &theta);
        if unseen {
            self.theta_base = theta;
        } else {
            self.checked_fit = Some((labels, cal));
        }
        Ok(unseen)
    }

    /// The final calibration for the report: the one the check made when the selection and the
    /// data are still those it fitted (the same calibration from the same start), else made now.
    pub(super) fn take_final_calibration(&mut self) -> Result<Option<Calibration>, FitError> {
        let labels: Vec<String> = self.selected.iter().map(EffectRequest::label).collect();
        match self.checked_fit.take() {
            Some((checked, cal)) if checked == labels => Ok(Some(cal)),
            _ => self.final_calibration(),
        }
    }

    /// Does the final fit (`final_theta`) hold a stand-in effect the rounds' fit
    /// (`rounds_theta`, same layout) does not?
    pub(super) fn unseen_stand_in(
        layout: &ParamLayout,
        rounds_theta: &DVector<f64>,
        final_theta: &DVector<f64>,
    ) -> bool {
        let seen = Self::implausible_kinds(layout, rounds_theta);
        Self::implausible_kinds(layout, final_theta)
            .into_iter()
            .any(|k| !seen.contains(&k))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::effects::EffectKind;

    /// The 3000-shot `compliant_driver` case: `com_offset.dx` plausible in the rounds' fit,
    /// a stand-in (−13.8 mm) in the final one; the rounds must run again on the final fit.
    #[test]
    fn a_stand_in_only_the_final_fit_shows_sends_the_selection_back_to_the_rounds() {
        let layout = ParamLayout::from_requests(
            &[
                EffectRequest::Global(EffectKind::ComOffset.into()),
                EffectRequest::Global(EffectKind::InertiaScale.into()),
            ],
            &[],
        )
        .unwrap();
        // dx, dy, dz (mm), s.
        let rounds = DVector::from_vec(vec![0.9, 0.07, -0.4, 0.81]);
        let fin = DVector::from_vec(vec![-13.8, 0.07, -0.4, 0.81]);
        assert!(Search::unseen_stand_in(&layout, &rounds, &fin));
        // The same stand-in in both fits (the rounds saw it), or none in the final fit.
        assert!(!Search::unseen_stand_in(&layout, &fin, &fin));
        assert!(!Search::unseen_stand_in(&layout, &fin, &rounds));
        let plausible = DVector::from_vec(vec![0.9, 0.07, -0.4, 1.0]);
        assert!(!Search::unseen_stand_in(&layout, &plausible, &plausible));
    }
}
