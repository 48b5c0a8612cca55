//! Shots → model → predictions: run a club over every shot of a table.
//!
//! Pure: no files, no threads. Each shot uses the model of its group (the club's nominal
//! parameters plus the effects that apply to that group).

use std::collections::BTreeMap;

use crate::club::ClubSpec;
use crate::data::shots::ShotTable;
use crate::measurement::{expected_outcome, ImpactNoise, MeasurementError};
use crate::model::Shot;
use crate::physics::{ImpactError, ImpactModel, ImpactOutcome, Launch, ParamError};

/// Why a set of shots cannot be predicted.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PredictError {
    /// The impact-location noise model cannot be applied to these shots.
    #[error(transparent)]
    Measurement(#[from] MeasurementError),
    /// The club's parameters for some group are not physical.
    #[error("group '{group}': {source}")]
    Model {
        /// Group.
        group: String,
        /// Problem.
        source: ParamError,
    },
    /// One shot cannot be computed.
    #[error("shot '{shot_id}' (row {row}): {source}")]
    Shot {
        /// Shot id.
        shot_id: String,
        /// 1-based data row (the header is row 0).
        row: usize,
        /// Problem.
        source: ImpactError,
    },
}

/// Models for every group of `shots`.
pub fn group_models(
    club: &ClubSpec,
    shots: &[Shot],
) -> Result<BTreeMap<String, ImpactModel>, PredictError> {
    let mut out = BTreeMap::new();
    for s in shots {
        if !out.contains_key(&s.group) {
            let m = club
                .model_for_group(&s.group)
                .map_err(|source| PredictError::Model {
                    group: s.group.clone(),
                    source,
                })?;
            out.insert(s.group.clone(), m);
        }
    }
    Ok(out)
}

/// Predict every shot, in order. Fails on the first shot that cannot be computed.
pub fn predict_shots(club: &ClubSpec, shots: &[Shot]) -> Result<Vec<ImpactOutcome>, PredictError> {
    solve_each(club, shots)?
        .into_iter()
        .zip(shots)
        .enumerate()
        .map(|(i, (o, s))| {
            o.map_err(|source| PredictError::Shot {
                shot_id: s.id.clone(),
                row: i + 1,
                source,
            })
        })
        .collect()
}

/// Every shot solved with its group's model, in order, each with its own result (a shot that
/// cannot be solved does not stop the others); an error only when a group's model cannot be
/// built.
pub fn solve_each(
    club: &ClubSpec,
    shots: &[Shot],
) -> Result<Vec<Result<ImpactOutcome, ImpactError>>, PredictError> {
    let models = group_models(club, shots)?;
    Ok(shots
        .iter()
        .map(|s| models[&s.group].solve(&s.delivery))
        .collect())
}

/// Predict every shot of a table.
pub fn predict_table(
    club: &ClubSpec,
    table: &ShotTable,
) -> Result<Vec<ImpactOutcome>, PredictError> {
    predict_shots(club, &table.shots)
}

/// Expected launch of every shot, in order: the model at the measured delivery, or, with
/// `impact_noise`, averaged over where each ball was most likely struck
/// (see [`crate::measurement`]).
pub fn expected_launches(
    club: &ClubSpec,
    shots: &[Shot],
    impact_noise: Option<ImpactNoise>,
) -> Result<Vec<Launch>, PredictError> {
    let models = group_models(club, shots)?;
    let nodes = impact_noise
        .map(|n| n.nodes_for(shots.iter().map(|s| &s.delivery)))
        .transpose()?;
    shots
        .iter()
        .enumerate()
        .map(|(i, s)| {
            expected_outcome(
                &models[&s.group],
                &s.delivery,
                nodes.as_ref().map(|n| &n[i]),
            )
            .map(|(launch, _, _)| launch)
            .map_err(|source| PredictError::Shot {
                shot_id: s.id.clone(),
                row: i + 1,
                source,
            })
        })
        .collect()
}
