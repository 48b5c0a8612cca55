//! `predict`: the launch of every shot of a table, as the predictions file.

use std::path::Path;

use anyhow::bail;
use serde::{Deserialize, Serialize};

use super::inputs::{self, NamedClub, ShotsFormat, ShotsInput};
use super::Notes;
use crate::data::shots::ShotTable;
use crate::physics::ImpactOutcome;
use crate::predict::{predict_table, PredictError};

/// Settings of `predict` for a shots table (the flight columns are `smash predict --flight`'s).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct PredictSettings {
    /// How the shots are read.
    #[serde(flatten)]
    pub shots: ShotsFormat,
}

/// The predictions of a shots table.
pub struct Predictions {
    /// The shots, in the model's convention.
    pub table: ShotTable,
    /// Every shot's impact, in the table's order.
    pub outcomes: Vec<ImpactOutcome>,
    /// The predictions file: the input columns, the predicted launch and, where the shots have
    /// measured launch, the errors.
    pub csv: Vec<u8>,
}

/// Predict every shot of `input` with `club` (the conversion lines and warnings to `notes`).
pub fn run(
    settings: &PredictSettings,
    club: NamedClub,
    input: &ShotsInput,
    notes: &mut dyn Notes,
) -> anyhow::Result<Predictions> {
    let prepared = inputs::prepare(club, input, &settings.shots, (true, false), notes)?;
    predict_prepared(club, input.label(), prepared.table)
}

/// Predict every shot of `table` (already in the model's convention; named `shots_path` in
/// messages) with `club`.
pub fn predict_prepared(
    club: NamedClub,
    shots_path: &Path,
    table: ShotTable,
) -> anyhow::Result<Predictions> {
    let outcomes = predict_checked(club, shots_path, &table)?;
    let csv = crate::data::predictions::predictions_csv(&table, &outcomes);
    Ok(Predictions {
        table,
        outcomes,
        csv,
    })
}

/// Every shot of `table` predicted with `club` (`shots_path` names the shots in messages);
/// refuses a shot whose impact has no finite launch.
pub fn predict_checked(
    club: NamedClub,
    shots_path: &Path,
    table: &ShotTable,
) -> anyhow::Result<Vec<ImpactOutcome>> {
    let outcomes = predict_table(club.spec, table).map_err(|e| locate_shot_error(table, e))?;
    for (shot, o) in table.shots.iter().zip(&outcomes) {
        if !(o.launch().is_finite() && o.smash_factor().is_finite()) {
            bail!(
                "{}: shot '{}': the impact has no finite launch; check its delivery and the \
                 club {}",
                shots_path.display(),
                shot.id,
                club.path.display()
            );
        }
    }
    Ok(outcomes)
}

/// A shot that cannot be predicted, located in its file: `FILE:LINE: columns …: shot 'ID': …`,
/// the same form as the shots reader's own errors.
pub fn locate_shot_error(table: &ShotTable, e: PredictError) -> anyhow::Error {
    let PredictError::Shot {
        shot_id,
        row,
        source,
    } = e
    else {
        return anyhow::Error::new(e).context(table.path.display().to_string());
    };
    table.shot_error(row, &shot_id, source).into()
}
