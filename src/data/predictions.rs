//! Predictions files: the shots file's columns, then `pred_<name>` for each launch column and
//! `pred_smash_factor`, then `err_<name>` = predicted − measured where measurements are present.

use crate::data::fmt_f64;
use crate::data::shots::ShotTable;
use crate::physics::{ImpactOutcome, LaunchComponent};

fn is_output_column(h: &str) -> bool {
    h == "pred_smash_factor"
        || LaunchComponent::ALL
            .iter()
            .any(|c| h.strip_prefix("pred_").or_else(|| h.strip_prefix("err_")) == Some(c.column()))
}

/// CSV bytes of the predictions for `table`. Input columns named like output columns (a file of
/// earlier predictions, say) are replaced, not repeated.
pub fn predictions_csv(table: &ShotTable, outcomes: &[ImpactOutcome]) -> Vec<u8> {
    assert_eq!(table.records.len(), outcomes.len(), "one outcome per shot");
    let keep: Vec<usize> = (0..table.headers.len())
        .filter(|&i| !is_output_column(&table.headers[i]))
        .collect();
    let with_err = table.has_measurements();
    let mut w = csv::Writer::from_writer(Vec::new());
    let mut header: Vec<String> = keep.iter().map(|&i| table.headers[i].clone()).collect();
    header.extend(
        LaunchComponent::ALL
            .iter()
            .map(|c| format!("pred_{}", c.column())),
    );
    header.push("pred_smash_factor".into());
    if with_err {
        header.extend(
            LaunchComponent::ALL
                .iter()
                .map(|c| format!("err_{}", c.column())),
        );
    }
    w.write_record(&header).expect("writing to memory");
    let mut row: Vec<String> = Vec::with_capacity(header.len());
    for ((rec, shot), out) in table.records.iter().zip(&table.shots).zip(outcomes) {
        row.clear();
        row.extend(keep.iter().map(|&i| rec[i].clone()));
        let pred = out.launch();
        row.extend(
            LaunchComponent::ALL
                .iter()
                .map(|&c| fmt_f64(pred.get_file(c))),
        );
        row.push(fmt_f64(out.smash_factor()));
        if let Some(m) = &shot.measured {
            row.extend(
                LaunchComponent::ALL
                    .iter()
                    .map(|&c| fmt_f64(pred.get_file(c) - m.get_file(c))),
            );
        }
        w.write_record(&row).expect("writing to memory");
    }
    w.into_inner().expect("flushing memory")
}
