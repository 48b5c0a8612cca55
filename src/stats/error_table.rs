//! Launch errors per group and component: the paper's Table 2 layout (mean and STD of
//! model − measured, per launch component, per group of shots).

use std::collections::BTreeMap;

use serde::Serialize;

/// Mean and sample standard deviation of errors, in the component's file unit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MeanStd {
    /// Mean error (model − measured).
    pub mean: f64,
    /// Sample standard deviation of the error (NaN, shown as "–" and written as `null`, for a
    /// group of one shot).
    pub std: f64,
}

/// Error statistics of one group, one entry per [`LaunchComponent::ALL`].
#[derive(Debug, Clone, PartialEq)]
pub struct GroupErrors {
    /// Group name.
    pub group: String,
    /// Number of shots.
    pub n: usize,
    /// Per component, in file order.
    pub components: [MeanStd; 5],
}

/// Errors of every group, sorted by group name.
#[derive(Debug, Clone, PartialEq)]
pub struct ErrorTable {
    /// One row block per group.
    pub groups: Vec<GroupErrors>,
}

/// Table-2 statistics from per-shot errors (model − measured, file units) and each shot's group.
pub fn launch_error_table<S: AsRef<str>>(groups: &[S], errors: &[[f64; 5]]) -> ErrorTable {
    assert_eq!(groups.len(), errors.len(), "one group per shot");
    let mut by_group: BTreeMap<&str, Vec<usize>> = BTreeMap::new();
    for (i, g) in groups.iter().enumerate() {
        by_group.entry(g.as_ref()).or_default().push(i);
    }
    let groups = by_group
        .into_iter()
        .map(|(g, idx)| {
            let components = std::array::from_fn(|c| {
                let col: Vec<f64> = idx.iter().map(|&i| errors[i][c]).collect();
                MeanStd {
                    mean: super::mean(&col),
                    std: super::std_dev(&col),
                }
            });
            GroupErrors {
                group: g.to_owned(),
                n: idx.len(),
                components,
            }
        })
        .collect();
    ErrorTable { groups }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_groups_and_stats() {
        let groups = ["B", "A", "B"];
        let e = [[1.0; 5], [2.0; 5], [3.0; 5]];
        let t = launch_error_table(&groups, &e);
        assert_eq!(t.groups.len(), 2);
        assert_eq!(t.groups[0].group, "A");
        assert_eq!(t.groups[1].n, 2);
        assert_eq!(t.groups[1].components[0].mean, 2.0);
        assert!((t.groups[1].components[0].std - 2f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn a_single_shot_group_has_no_spread() {
        let t = launch_error_table(&["A", "A", "B"], &[[1.0; 5], [3.0; 5], [2.0; 5]]);
        assert!(t.groups[1].components[0].std.is_nan());
    }
}
