//! The face map of what remains in a launch component: the mean error of the shots binned by
//! impact location ([`crate::diagnose::noise_floor::shape`]), as a text grid and a heatmap.

use crate::diagnose::noise_floor::shape::{error_value, BinMap, ShapeTerm};
use crate::diagnose::noise_floor::ComponentFloor;
use crate::physics::LaunchComponent;
use crate::report::heatmap::{binned_heatmap_svg, Heatmap, Scale};
use crate::report::TextTable;

/// Is the component's face map worth showing: structure remains in it, or its shape is found
/// though its spread is as the noise explains?
pub fn shown(c: &ComponentFloor) -> bool {
    c.shape.face_map.is_some() && (c.structure || c.quiet_shape().is_some())
}

/// The face-map tests' F and p, in words (empty when none was made).
fn test_words(c: &ComponentFloor) -> String {
    let words: Vec<String> = [
        (ShapeTerm::FaceBins, "bins"),
        (ShapeTerm::FaceQuadratic, "quadratic"),
    ]
    .into_iter()
    .filter_map(|(term, name)| {
        let t = c.shape.tests.iter().find(|t| t.term == term)?;
        Some(format!(
            "{name} F({}, {}) = {:.2}, p = {:.1e}",
            t.df.0, t.df.1, t.f, t.p_value
        ))
    })
    .collect();
    if words.is_empty() {
        String::new()
    } else {
        format!("; {}", words.join("; "))
    }
}

/// An edge range `a to b`, 1 decimal.
fn range(e: &[f64], k: usize) -> String {
    format!("{:.1} to {:.1}", e[k], e[k + 1])
}

/// The grid: a row per band of impact height (top first), a column per band from heel to toe,
/// each cell the mean error and its shots.
fn grid(map: &BinMap, c: LaunchComponent) -> String {
    let nc = map.n_cols();
    let nr = map.row_edges.len() - 1;
    let mut header = vec!["impact_y_mm \\ impact_z_mm".to_owned()];
    header.extend((0..nc).map(|j| range(&map.col_edges, j)));
    let mut t = TextTable::new(header);
    for i in (0..nr).rev() {
        let mut row = vec![range(&map.row_edges, i)];
        row.extend((0..nc).map(|j| {
            let b = map.bins[i * nc + j];
            if b.count == 0 {
                "– (0)".to_owned()
            } else {
                format!("{} ({})", error_value(b.mean_error, c), b.count)
            }
        }));
        t.row(row);
    }
    t.render()
}

/// The face map of `c` as text: a heading and the grid, when [`shown`].
pub fn face_map_text(c: &ComponentFloor) -> Option<String> {
    let map = c.shape.face_map.as_ref().filter(|_| shown(c))?;
    let heading = format!(
        "Face map of {} error (model − measured, {}; shots in brackets; rows up the face, \
         columns heel to toe{}):",
        c.component.column(),
        c.component.unit(),
        test_words(c)
    );
    Some(format!(
        "{}{}",
        crate::report::wrap::wrap(&heading, crate::report::text::WIDTH, 2),
        grid(map, c.component)
    ))
}

/// The face map of `c` as an SVG heatmap (diverging about zero), when [`shown`].
pub fn face_map_svg(c: &ComponentFloor) -> Option<String> {
    let map = c.shape.face_map.as_ref().filter(|_| shown(c))?;
    let centres = |e: &[f64]| -> Vec<f64> { e.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect() };
    let (xs, ys) = (centres(&map.col_edges), centres(&map.row_edges));
    let values: Vec<f64> = map.bins.iter().map(|b| b.mean_error).collect();
    let title = format!("What remains in {} over the face", c.component.column());
    let value_label = format!("mean error (model − measured), {}", c.component.unit());
    Some(binned_heatmap_svg(
        &Heatmap {
            title: &title,
            x_label: "impact z (toward toe), mm",
            y_label: "impact y (up), mm",
            value_label: &value_label,
            xs: &xs,
            ys: &ys,
            values: &values,
            marker: Some((0.0, 0.0)),
            scale: Scale::Diverging,
        },
        &map.col_edges,
        &map.row_edges,
    ))
}
