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
use crate::fit::{EffectRequest, FitError};

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
        checked.push(labels);
        let Some(cal) = self.final_calibration()? else {
            return Ok(false);
        };
        let theta = DVector::from_iterator(cal.params.len(), cal.params.iter().map(|p| p.value));
        let seen = Self::implausible_kinds(&self.base, &self.theta_base);
        let unseen = Self::implausible_kinds(&self.base, &theta)
            .into_iter()
            .any(|k| !seen.contains(&k));
        if unseen {
            self.theta_base = theta;
        }
        Ok(unseen)
    }
}
