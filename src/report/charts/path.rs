//! The path of an iterative search: the best value after each iteration, as a line with a
//! point per iteration, on an axis fitted to the values (the changes of an optimiser's last
//! iterations are small against the value itself).

use plotters::prelude::*;

use super::{build_chart, draw_value_mesh, err, range, ChartError, BLUE_C, SIZE};

/// `points` (iteration, value) as a line with markers, titled, with both axes labelled.
pub fn path_svg(
    title: &str,
    x_label: &str,
    y_label: &str,
    points: &[(f64, f64)],
) -> Result<String, ChartError> {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|(x, y)| x.is_finite() && y.is_finite())
        .collect();
    let (x0, x1) = range(pts.iter().map(|p| p.0), None);
    let (y0, y1) = range(pts.iter().map(|p| p.1), None);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        let mut chart = build_chart(&root, title, (40, 80), x0..x1, y0..y1)?;
        draw_value_mesh(&mut chart, x_label, y_label)?;
        chart
            .draw_series(LineSeries::new(pts.iter().copied(), BLUE_C.stroke_width(2)))
            .map_err(err)?;
        chart
            .draw_series(
                pts.iter()
                    .map(|&(x, y)| Circle::new((x, y), 3, BLUE_C.filled())),
            )
            .map_err(err)?;
        root.present().map_err(err)?;
    }
    Ok(svg)
}
