//! Charts for the HTML reports, drawn with `plotters` into SVG strings (no fonts or scripts:
//! text is SVG `<text>` in the reader's sans-serif font). Each chart has a title, axes with
//! units and, where it shows more than one thing, a legend. Builds strings only.

use plotters::prelude::*;

/// Width and height of a chart, px (scaled by the page's CSS).
const SIZE: (u32, u32) = (560, 340);

/// Series colours: blue (before / the model), orange (after), grey (reference lines).
pub const BLUE_C: RGBColor = RGBColor(31, 119, 180);
/// Second series.
pub const ORANGE_C: RGBColor = RGBColor(230, 120, 20);
/// Trend and penalty lines.
pub const RED_C: RGBColor = RGBColor(200, 30, 40);
/// Plausible ranges.
pub const GREEN_C: RGBColor = RGBColor(60, 160, 80);

fn err<E: std::fmt::Display>(e: E) -> String {
    format!("drawing a chart: {e}")
}

/// A drawing area over an SVG string.
type Root<'b> = DrawingArea<SVGBackend<'b>, plotters::coord::Shift>;
/// A chart with two `f64` axes on [`Root`].
type Chart<'a, 'b> = ChartContext<
    'a,
    SVGBackend<'b>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

/// A titled chart over `x` × `y` with label areas of `(x_area, y_area)` px.
fn build_chart<'a, 'b>(
    root: &'a Root<'b>,
    title: &str,
    (x_area, y_area): (u32, u32),
    x: std::ops::Range<f64>,
    y: std::ops::Range<f64>,
) -> Result<Chart<'a, 'b>, String> {
    ChartBuilder::on(root)
        .caption(title, ("sans-serif", 17))
        .margin(12)
        .x_label_area_size(x_area)
        .y_label_area_size(y_area)
        .build_cartesian_2d(x, y)
        .map_err(err)
}

/// The mesh of a chart whose x axis holds categories (labelled by the caller, one per unit).
fn draw_category_mesh<'a, 'b: 'a>(
    chart: &mut Chart<'a, 'b>,
    y_label: &str,
    font_px: u32,
) -> Result<(), String> {
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_label_formatter(&|_| String::new())
        .set_tick_mark_size(LabelAreaPosition::Bottom, 0)
        .y_desc(y_label)
        .y_label_formatter(&tick)
        .light_line_style(BLACK.mix(0.04))
        .label_style(("sans-serif", font_px))
        .draw()
        .map_err(err)
}

/// The legend box at `position`.
fn draw_legend<'a, 'b: 'a>(
    chart: &mut Chart<'a, 'b>,
    position: SeriesLabelPosition,
    font_px: u32,
) -> Result<(), String> {
    chart
        .configure_series_labels()
        .position(position)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .label_font(("sans-serif", font_px))
        .draw()
        .map_err(err)
}

/// Tick label: at most four decimals, no trailing zeros, no `-0`.
pub fn tick(v: &f64) -> String {
    let v = *v;
    if v.abs() < 1e-9 {
        return "0".into();
    }
    let digits = if v.abs() >= 100.0 {
        0
    } else if v.abs() >= 1.0 {
        2
    } else {
        4
    };
    let s = format!("{v:.digits$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        s
    }
}

/// A padded, non-empty range containing every finite value (and `always`, e.g. zero).
fn range(values: impl IntoIterator<Item = f64>, always: Option<f64>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.into_iter().chain(always).filter(|v| v.is_finite()) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return (-1.0, 1.0);
    }
    let span = hi - lo;
    let pad = if span > 0.0 {
        0.08 * span
    } else {
        0.5 * lo.abs().max(1.0)
    };
    (lo - pad, hi + pad)
}

/// One series of a grouped bar chart: a value and an error half-width per category.
#[derive(Debug, Clone)]
pub struct BarSeries {
    /// Legend label.
    pub label: String,
    /// Colour.
    pub colour: RGBColor,
    /// Per category: (bar height, error-bar half-width); `None` draws nothing.
    pub values: Vec<Option<(f64, f64)>>,
}

/// Grouped bars with error bars (e.g. mean error ± STD per group, before and after).
pub fn grouped_bars_svg(
    title: &str,
    y_label: &str,
    categories: &[String],
    series: &[BarSeries],
) -> Result<String, String> {
    let n = categories.len().max(1);
    let all = series.iter().flat_map(|s| {
        s.values
            .iter()
            .flatten()
            .flat_map(|&(v, e)| [v - e.abs(), v + e.abs(), v])
    });
    let (lo, hi) = range(all, Some(0.0));
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        let mut chart = build_chart(&root, title, (34, 64), 0.0..n as f64, lo..hi)?;
        draw_category_mesh(&mut chart, y_label, 13)?;
        chart
            .draw_series(LineSeries::new(
                [(0.0, 0.0), (n as f64, 0.0)],
                BLACK.stroke_width(1),
            ))
            .map_err(err)?;
        for (i, c) in categories.iter().enumerate() {
            let (px, py) = chart.backend_coord(&(i as f64 + 0.5, lo));
            root.draw(&Text::new(
                c.clone(),
                (px, py + 8),
                ("sans-serif", 14).into_font().into_text_style(&root).pos(
                    plotters::style::text_anchor::Pos::new(
                        plotters::style::text_anchor::HPos::Center,
                        plotters::style::text_anchor::VPos::Top,
                    ),
                ),
            ))
            .map_err(err)?;
        }
        let m = series.len().max(1) as f64;
        let slot = 0.8 / m;
        for (k, s) in series.iter().enumerate() {
            let colour = s.colour;
            let bars = s.values.iter().enumerate().filter_map(|(i, v)| {
                let (v, _) = (*v)?;
                let x0 = i as f64 + 0.1 + k as f64 * slot;
                Some(Rectangle::new(
                    [(x0 + 0.05 * slot, 0.0), (x0 + 0.95 * slot, v)],
                    colour.mix(0.85).filled(),
                ))
            });
            chart
                .draw_series(bars)
                .map_err(err)?
                .label(s.label.clone())
                .legend(move |(x, y)| {
                    Rectangle::new([(x, y - 6), (x + 14, y + 6)], colour.filled())
                });
            for (i, v) in s.values.iter().enumerate() {
                let Some((v, e)) = *v else { continue };
                if !(e.is_finite() && e > 0.0) {
                    continue;
                }
                let xc = i as f64 + 0.1 + (k as f64 + 0.5) * slot;
                let cap = 0.15 * slot;
                chart
                    .draw_series([
                        PathElement::new(vec![(xc, v - e), (xc, v + e)], BLACK.stroke_width(1)),
                        PathElement::new(
                            vec![(xc - cap, v - e), (xc + cap, v - e)],
                            BLACK.stroke_width(1),
                        ),
                        PathElement::new(
                            vec![(xc - cap, v + e), (xc + cap, v + e)],
                            BLACK.stroke_width(1),
                        ),
                    ])
                    .map_err(err)?;
            }
        }
        if series.len() > 1 {
            draw_legend(&mut chart, SeriesLabelPosition::UpperRight, 13)?;
        }
        root.present().map_err(err)?;
    }
    Ok(svg)
}

/// A straight trend line `y = intercept + slope·x` with its legend label.
#[derive(Debug, Clone)]
pub struct Trend {
    /// Slope, y unit per x unit.
    pub slope: f64,
    /// Intercept, y unit.
    pub intercept: f64,
    /// Legend label (e.g. `trend: r = 0.41, p < 1%`).
    pub label: String,
}

/// Residuals of every shot against a delivery variable, with the trend line and bin means.
pub fn scatter_trend_svg(
    title: &str,
    x_label: &str,
    y_label: &str,
    points: &[(f64, f64)],
    trend: Option<&Trend>,
    bin_means: &[(f64, f64)],
) -> Result<String, String> {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|(x, y)| x.is_finite() && y.is_finite())
        .collect();
    let (x0, x1) = range(pts.iter().map(|p| p.0), None);
    let (y0, y1) = range(
        pts.iter().map(|p| p.1).chain(bin_means.iter().map(|b| b.1)),
        Some(0.0),
    );
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        let mut chart = build_chart(&root, title, (40, 64), x0..x1, y0..y1)?;
        chart
            .configure_mesh()
            .x_desc(x_label)
            .y_desc(y_label)
            .x_label_formatter(&tick)
            .y_label_formatter(&tick)
            .label_style(("sans-serif", 13))
            .light_line_style(BLACK.mix(0.05))
            .draw()
            .map_err(err)?;
        chart
            .draw_series(LineSeries::new(
                [(x0, 0.0), (x1, 0.0)],
                BLACK.stroke_width(1),
            ))
            .map_err(err)?;
        chart
            .draw_series(
                pts.iter()
                    .map(|&(x, y)| Circle::new((x, y), 2, BLUE_C.mix(0.35).filled())),
            )
            .map_err(err)?
            .label("shots")
            .legend(|(x, y)| Circle::new((x + 7, y), 3, BLUE_C.filled()));
        if !bin_means.is_empty() {
            chart
                .draw_series(LineSeries::new(
                    bin_means.iter().copied(),
                    BLACK.stroke_width(2),
                ))
                .map_err(err)?
                .label("bin means")
                .legend(|(x, y)| {
                    PathElement::new(vec![(x, y), (x + 14, y)], BLACK.stroke_width(2))
                });
            chart
                .draw_series(
                    bin_means
                        .iter()
                        .map(|&(x, y)| Circle::new((x, y), 4, BLACK.filled())),
                )
                .map_err(err)?;
        }
        if let Some(t) = trend {
            chart
                .draw_series(LineSeries::new(
                    [
                        (x0, t.intercept + t.slope * x0),
                        (x1, t.intercept + t.slope * x1),
                    ],
                    RED_C.stroke_width(2),
                ))
                .map_err(err)?
                .label(t.label.clone())
                .legend(|(x, y)| {
                    PathElement::new(vec![(x, y), (x + 14, y)], RED_C.stroke_width(2))
                });
        }
        draw_legend(&mut chart, SeriesLabelPosition::UpperRight, 13)?;
        root.present().map_err(err)?;
    }
    Ok(svg)
}

/// One estimated parameter: value, uncertainty interval and the plausible range.
#[derive(Debug, Clone)]
pub struct Estimate {
    /// Row label (`added_mass@A.dm_g`).
    pub label: String,
    /// Estimate.
    pub value: f64,
    /// Uncertainty interval (e.g. ± 2 standard errors), when known.
    pub interval: Option<(f64, f64)>,
    /// Plausible range for a real driver.
    pub plausible: (f64, f64),
}

/// Estimates of parameters sharing one unit: plausible ranges as green bands, estimates as
/// points with their intervals.
pub fn estimates_svg(title: &str, unit: &str, rows: &[Estimate]) -> Result<String, String> {
    let n = rows.len().max(1);
    let (x0, x1) = range(
        rows.iter().flat_map(|r| {
            [
                r.value,
                r.plausible.0,
                r.plausible.1,
                r.interval.map_or(r.value, |i| i.0),
                r.interval.map_or(r.value, |i| i.1),
            ]
        }),
        None,
    );
    let height = 110 + 44 * n as u32;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (SIZE.0, height)).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        let mut chart = build_chart(&root, title, (40, 170), x0..x1, 0.0..n as f64)?;
        chart
            .configure_mesh()
            .disable_y_mesh()
            .y_label_formatter(&|_| String::new())
            .set_tick_mark_size(LabelAreaPosition::Left, 0)
            .x_desc(unit)
            .x_label_formatter(&tick)
            .label_style(("sans-serif", 12))
            .draw()
            .map_err(err)?;
        let row_y = |i: usize| (n - 1 - i) as f64 + 0.5;
        for (i, r) in rows.iter().enumerate() {
            let (px, py) = chart.backend_coord(&(x0, row_y(i)));
            root.draw(&Text::new(
                r.label.clone(),
                (px - 8, py),
                ("sans-serif", 12).into_font().into_text_style(&root).pos(
                    plotters::style::text_anchor::Pos::new(
                        plotters::style::text_anchor::HPos::Right,
                        plotters::style::text_anchor::VPos::Center,
                    ),
                ),
            ))
            .map_err(err)?;
        }
        chart
            .draw_series(rows.iter().enumerate().map(|(i, r)| {
                Rectangle::new(
                    [
                        (r.plausible.0, row_y(i) - 0.3),
                        (r.plausible.1, row_y(i) + 0.3),
                    ],
                    GREEN_C.mix(0.25).filled(),
                )
            }))
            .map_err(err)?
            .label("plausible range")
            .legend(|(x, y)| {
                Rectangle::new([(x, y - 6), (x + 14, y + 6)], GREEN_C.mix(0.4).filled())
            });
        for (i, r) in rows.iter().enumerate() {
            if let Some((a, b)) = r.interval {
                let y = row_y(i);
                chart
                    .draw_series([
                        PathElement::new(vec![(a, y), (b, y)], BLACK.stroke_width(2)),
                        PathElement::new(vec![(a, y - 0.12), (a, y + 0.12)], BLACK.stroke_width(2)),
                        PathElement::new(vec![(b, y - 0.12), (b, y + 0.12)], BLACK.stroke_width(2)),
                    ])
                    .map_err(err)?;
            }
        }
        chart
            .draw_series(
                rows.iter()
                    .enumerate()
                    .map(|(i, r)| Circle::new((r.value, row_y(i)), 5, BLUE_C.filled())),
            )
            .map_err(err)?
            .label("estimate ± 2 SE")
            .legend(|(x, y)| Circle::new((x + 7, y), 4, BLUE_C.filled()));
        draw_legend(&mut chart, SeriesLabelPosition::LowerRight, 12)?;
        root.present().map_err(err)?;
    }
    Ok(svg)
}

/// Bars per candidate, each with a red threshold mark (e.g. cross-validated gain per effect and
/// the penalty that gain must beat).
pub fn bars_with_line_svg(
    title: &str,
    y_label: &str,
    labels: &[String],
    values: &[f64],
    line: Option<(&[f64], &str)>,
) -> Result<String, String> {
    let n = labels.len().max(1);
    let (lo, hi) = range(
        values
            .iter()
            .copied()
            .chain(line.iter().flat_map(|l| l.0.iter().copied())),
        Some(0.0),
    );
    let mut svg = String::new();
    {
        let root =
            SVGBackend::with_string(&mut svg, (SIZE.0.max(60 * n as u32 + 140), SIZE.1 + 60))
                .into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        let mut chart = build_chart(&root, title, (110, 64), 0.0..n as f64, lo..hi)?;
        draw_category_mesh(&mut chart, y_label, 12)?;
        chart
            .draw_series(values.iter().enumerate().map(|(i, &v)| {
                Rectangle::new(
                    [(i as f64 + 0.15, 0.0), (i as f64 + 0.85, v)],
                    BLUE_C.mix(0.85).filled(),
                )
            }))
            .map_err(err)?
            .label("gain")
            .legend(|(x, y)| Rectangle::new([(x, y - 6), (x + 14, y + 6)], BLUE_C.filled()));
        for (i, l) in labels.iter().enumerate() {
            let (px, py) = chart.backend_coord(&(i as f64 + 0.5, lo));
            root.draw(&Text::new(
                l.clone(),
                (px, py + 6),
                ("sans-serif", 12)
                    .into_font()
                    .transform(FontTransform::Rotate90)
                    .into_text_style(&root),
            ))
            .map_err(err)?;
        }
        if let Some((marks, label)) = line {
            chart
                .draw_series(marks.iter().enumerate().map(|(i, &v)| {
                    PathElement::new(
                        vec![(i as f64 + 0.05, v), (i as f64 + 0.95, v)],
                        RED_C.stroke_width(3),
                    )
                }))
                .map_err(err)?
                .label(label.to_owned())
                .legend(|(x, y)| {
                    PathElement::new(vec![(x, y), (x + 14, y)], RED_C.stroke_width(2))
                });
        }
        draw_legend(&mut chart, SeriesLabelPosition::UpperRight, 12)?;
        root.present().map_err(err)?;
    }
    Ok(svg)
}

/// Least-squares line through `points` (`None` with fewer than two distinct x).
pub fn fit_line(points: &[(f64, f64)]) -> Option<(f64, f64)> {
    let n = points.len() as f64;
    if points.len() < 2 {
        return None;
    }
    let mx = points.iter().map(|p| p.0).sum::<f64>() / n;
    let my = points.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    if sxx <= 0.0 || !sxx.is_finite() {
        return None;
    }
    let slope = sxy / sxx;
    Some((slope, my - slope * mx))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn charts_are_svg_with_titles_and_legends() {
        let svg = grouped_bars_svg(
            "Ball speed",
            "error, mph",
            &["A".into(), "B".into()],
            &[
                BarSeries {
                    label: "before".into(),
                    colour: BLUE_C,
                    values: vec![Some((-2.0, 1.0)), Some((-1.5, 0.5))],
                },
                BarSeries {
                    label: "after".into(),
                    colour: ORANGE_C,
                    values: vec![Some((0.1, 1.0)), None],
                },
            ],
        )
        .unwrap();
        assert!(svg.starts_with("<svg"), "{}", &svg[..50]);
        for t in [
            "Ball speed",
            "error, mph",
            "before",
            "after",
            "\nA\n</text>",
            "\nB\n</text>",
        ] {
            assert!(svg.contains(t), "missing {t}");
        }
        let pts: Vec<(f64, f64)> = (0..50).map(|i| (i as f64, 2.0 * i as f64 + 1.0)).collect();
        let (s, c) = fit_line(&pts).unwrap();
        assert!((s - 2.0).abs() < 1e-12 && (c - 1.0).abs() < 1e-9);
        let t = Trend {
            slope: s,
            intercept: c,
            label: "trend".into(),
        };
        let svg =
            scatter_trend_svg("t", "x, mph", "y, rpm", &pts, Some(&t), &[(1.0, 3.0)]).unwrap();
        assert!(svg.contains("x, mph") && svg.contains("trend") && svg.contains("<circle"));
        let svg = estimates_svg(
            "dm",
            "g",
            &[Estimate {
                label: "added_mass.dm_g".into(),
                value: 2.0,
                interval: Some((1.0, 3.0)),
                plausible: (0.0, 15.0),
            }],
        )
        .unwrap();
        assert!(svg.contains("plausible range") && svg.contains("added_mass.dm_g"));
        let svg = bars_with_line_svg(
            "g",
            "gain",
            &["a".into()],
            &[3.0],
            Some((&[2.0][..], "penalty")),
        )
        .unwrap();
        assert!(svg.contains("penalty"));
    }
}
