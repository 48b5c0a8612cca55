//! The noise floor of a diagnosis as a view model: the instrument noise, per component the
//! spread observed against expected and its verdict, and the search for a shape in the errors
//! (face maps and club-speed bins).

use std::collections::BTreeMap;

use serde::Serialize;

use super::{components, ComponentMap};
use crate::diagnose::noise_floor::shape::{BinMap, ShapeSearch};
use crate::diagnose::noise_floor::{ComponentFloor, NoiseFloor, STRUCTURE_ALPHA};
use crate::model::DeliveryVar;

/// One bin of a shape's map.
#[derive(Debug, Clone, Serialize)]
pub struct BinView {
    /// Row.
    pub row: usize,
    /// Column.
    pub col: usize,
    /// Shots.
    pub count: usize,
    /// Mean error, file units (`None`: no shots).
    pub mean_error: Option<f64>,
    /// Mean error in standard errors.
    pub z_mean: Option<f64>,
}

/// Bins of the shots over one or two delivery variables, with their edges named by variable
/// and unit (`impact_y_edges_mm`, …).
#[derive(Debug, Clone, Serialize)]
pub struct BinMapView {
    /// The edges, keyed `{variable}_edges_{unit}`.
    #[serde(flatten)]
    pub edges: BTreeMap<String, Vec<f64>>,
    /// The bins, row-major.
    pub bins: Vec<BinView>,
}

fn finite(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}

impl BinMapView {
    /// The view of `m`, its rows named `row` and columns `col`, in `unit`.
    pub fn of(m: &BinMap, (row, col, unit): (&str, &str, &str)) -> Self {
        let nc = m.n_cols();
        let mut edges = BTreeMap::from([(format!("{row}_edges_{unit}"), m.row_edges.clone())]);
        if !m.col_edges.is_empty() {
            edges.insert(format!("{col}_edges_{unit}"), m.col_edges.clone());
        }
        Self {
            edges,
            bins: m
                .bins
                .iter()
                .enumerate()
                .map(|(k, b)| BinView {
                    row: k / nc,
                    col: k % nc,
                    count: b.count,
                    mean_error: finite(b.mean_error),
                    z_mean: finite(b.z_mean),
                })
                .collect(),
        }
    }
}

/// One shape term's test.
#[derive(Debug, Clone, Serialize)]
pub struct TermTestView {
    /// The term.
    pub term: &'static str,
    /// Its F statistic.
    pub f: f64,
    /// Its degrees of freedom.
    pub df: [usize; 2],
    /// Its p-value.
    pub p_value: f64,
}

/// The search for a shape in a component's errors.
#[derive(Debug, Clone, Serialize)]
pub struct ShapeView {
    /// The errors' unit.
    pub error_unit: &'static str,
    /// The face map of the errors.
    pub face_map: Option<BinMapView>,
    /// The errors by club speed.
    pub club_speed_bins: Option<BinMapView>,
    /// Every term tested.
    pub tests: Vec<TermTestView>,
    /// Level of each test.
    pub alpha_each: f64,
    /// The term found, if any.
    pub found: Option<&'static str>,
}

impl ShapeView {
    /// The view of `s` (`unit`: the component's file unit).
    pub fn of(s: &ShapeSearch, unit: &'static str) -> Self {
        Self {
            error_unit: unit,
            face_map: s
                .face_map
                .as_ref()
                .map(|m| BinMapView::of(m, ("impact_y", "impact_z", "mm"))),
            club_speed_bins: s
                .speed_bins
                .as_ref()
                .map(|m| BinMapView::of(m, ("club_speed", "", "mph"))),
            tests: s
                .tests
                .iter()
                .map(|t| TermTestView {
                    term: t.term.name(),
                    f: t.f,
                    df: [t.df.0, t.df.1],
                    p_value: t.p_value,
                })
                .collect(),
            alpha_each: crate::diagnose::noise_floor::shape::ALPHA_EACH,
            found: s.found.map(|t| t.term.name()),
        }
    }
}

/// The strongest trend of a component's errors with a delivery variable.
#[derive(Debug, Clone, Serialize)]
pub struct TrendView {
    /// The variable.
    pub variable: &'static str,
    /// Correlation.
    pub r: f64,
}

/// The noise-floor verdict for one launch component.
#[derive(Debug, Clone, Serialize)]
pub struct ComponentFloorView {
    /// The component.
    pub component: &'static str,
    /// Mean error, file units.
    pub mean: f64,
    /// Mean error in expected standard deviations.
    pub mean_in_expected_sd: f64,
    /// Expected standard deviation of the errors, file units.
    pub expected_sd: f64,
    /// Observed standard deviation, file units.
    pub observed_sd: f64,
    /// Observed over expected.
    pub ratio: f64,
    /// The spread test's p-value.
    pub p_value: f64,
    /// The mean's p-value.
    pub mean_p_value: f64,
    /// Structure remains.
    pub structure: bool,
    /// The strongest trend, when there is one.
    pub trend: Option<TrendView>,
    /// The shape search.
    pub shape: ShapeView,
    /// The verdict in words.
    pub verdict: String,
    /// Where the ratio lies: `well_below`, `near` or `well_above`.
    pub spread_band: &'static str,
}

/// The instrument noise assumed or given.
#[derive(Debug, Clone, Serialize)]
pub struct InstrumentView {
    /// Where the values come from.
    pub name: String,
    /// Launch monitor, per component.
    pub launch_sd: ComponentMap,
    /// Delivery measurement, per variable.
    pub delivery_sd: BTreeMap<&'static str, f64>,
}

/// The noise floor of a diagnosis.
#[derive(Debug, Clone, Serialize)]
pub struct NoiseFloorView {
    /// The instrument noise.
    pub instrument: InstrumentView,
    /// The noise was assumed (no noise file or class given).
    pub assumed: bool,
    /// Half-width of the band around 1 of a ratio near 1.
    pub band_half_width: f64,
    /// Level of the structure test.
    pub alpha: f64,
    /// Structure remains in a component.
    pub structure_remains: bool,
    /// Per component.
    pub components: Vec<ComponentFloorView>,
}

impl NoiseFloorView {
    /// The view of `f`.
    pub fn of(f: &NoiseFloor) -> Self {
        let component = |c: &ComponentFloor| ComponentFloorView {
            component: c.component.column(),
            mean: c.mean,
            mean_in_expected_sd: c.mean_in_sd,
            expected_sd: c.expected_sd,
            observed_sd: c.observed_sd,
            ratio: c.ratio,
            p_value: c.p_value,
            mean_p_value: c.mean_p_value,
            structure: c.structure,
            trend: c.trend.map(|(v, r)| TrendView {
                variable: v.column(),
                r,
            }),
            shape: ShapeView::of(&c.shape, c.component.unit()),
            verdict: c.verdict(),
            spread_band: f.spread_band(c).name(),
        };
        Self {
            instrument: InstrumentView {
                name: f.instrument.name.clone(),
                launch_sd: components(&f.instrument.launch_sd),
                delivery_sd: DeliveryVar::ALL
                    .iter()
                    .map(|v| (v.column(), f.instrument.delivery_sd[v.index()]))
                    .collect(),
            },
            assumed: f.assumed,
            band_half_width: f.band_half_width(),
            alpha: STRUCTURE_ALPHA,
            structure_remains: f.structure_remains(),
            components: f.components.iter().map(component).collect(),
        }
    }
}
