//! The strata check as a view model: per family its strata and per parameter its test.

use std::collections::BTreeMap;

use serde::Serialize;

use crate::diagnose::strata::StrataCheck;

/// A value and its standard error.
#[derive(Debug, Clone, Serialize)]
pub struct ValueSe {
    /// Value.
    pub value: f64,
    /// Standard error.
    pub stderr: f64,
}

/// One stratum of a family: its label, shots and per parameter value.
#[derive(Debug, Clone, Serialize)]
pub struct StratumView {
    /// Label.
    pub label: String,
    /// Shots.
    pub n: usize,
    /// Per parameter, its value in this stratum (`None`: not estimable there).
    pub values: BTreeMap<String, Option<ValueSe>>,
}

/// A parameter's consistency test across a family's strata.
#[derive(Debug, Clone, Serialize)]
pub struct ConsistencyView {
    /// χ² of the differences.
    pub chi2: f64,
    /// Degrees of freedom.
    pub dof: usize,
    /// Its p-value.
    pub p_value: f64,
    /// The values agree.
    pub stable: bool,
}

/// A family of strata and its tests.
#[derive(Debug, Clone, Serialize)]
pub struct StrataFamilyView {
    /// Name.
    pub name: String,
    /// Its strata.
    pub strata: Vec<StratumView>,
    /// Per parameter, its test (`None`: not tested).
    pub checks: BTreeMap<String, Option<ConsistencyView>>,
}

/// The strata check: per family its strata and per parameter its test.
#[derive(Debug, Clone, Serialize)]
pub struct StrataView {
    /// Level of the whole check.
    pub alpha: f64,
    /// Level of each test.
    pub alpha_each: f64,
    /// The parameters checked.
    pub params: Vec<String>,
    /// The families.
    pub families: Vec<StrataFamilyView>,
}

impl StrataView {
    /// The view of `c`.
    pub fn of(c: &StrataCheck) -> Self {
        let per_param = |f: &dyn Fn(usize) -> Option<ValueSe>| {
            c.params
                .iter()
                .enumerate()
                .map(|(j, l)| (l.clone(), f(j)))
                .collect::<BTreeMap<_, _>>()
        };
        let families = c
            .families
            .iter()
            .map(|f| StrataFamilyView {
                name: f.name.clone(),
                strata: f
                    .strata
                    .iter()
                    .map(|s| StratumView {
                        label: s.label.clone(),
                        n: s.n,
                        values: per_param(&|j| {
                            s.values[j].map(|(value, stderr)| ValueSe { value, stderr })
                        }),
                    })
                    .collect(),
                checks: c
                    .params
                    .iter()
                    .enumerate()
                    .map(|(j, l)| {
                        let check = f.checks[j].as_ref().map(|k| ConsistencyView {
                            chi2: k.chi2,
                            dof: k.dof,
                            p_value: k.p_value,
                            stable: k.stable,
                        });
                        (l.clone(), check)
                    })
                    .collect(),
            })
            .collect();
        Self {
            alpha: crate::diagnose::strata::STRATA_ALPHA,
            alpha_each: c.alpha_each,
            params: c.params.clone(),
            families,
        }
    }
}
