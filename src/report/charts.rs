//! Charts for the HTML reports, drawn with `plotters` into SVG strings (no fonts or scripts:
//! text is SVG `<text>` in the reader's sans-serif font). Each chart has a title, axes with
//! units and, where it shows more than one thing, a legend. Builds strings only.

use plotters::prelude::*;

mod path;

pub use path::path_svg;

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

/// A chart plotters could not draw (its SVG backend writes into a string, so a refused
/// coordinate or text rather than an I/O failure).
#[derive(Debug, thiserror::Error)]
#[error("drawing a chart: {0}")]
pub struct ChartError(String);

fn err<E: std::fmt::Display>(e: E) -> ChartError {
    ChartError(e.to_string())
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
) -> Result<Chart<'a, 'b>, ChartError> {
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
) -> Result<(), ChartError> {
    let y_tick = tick_for(chart.y_range());
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_label_formatter(&|_| String::new())
        .set_tick_mark_size(LabelAreaPosition::Bottom, 0)
        .y_desc(y_label)
        .y_label_formatter(&y_tick)
        .light_line_style(BLACK.mix(0.04))
        .label_style(("sans-serif", font_px))
        .draw()
        .map_err(err)
}

/// The mesh of a chart with a value on each axis, both labelled.
fn draw_value_mesh<'a, 'b: 'a>(
    chart: &mut Chart<'a, 'b>,
    x_label: &str,
    y_label: &str,
) -> Result<(), ChartError> {
    let (x_tick, y_tick) = (tick_for(chart.x_range()), tick_for(chart.y_range()));
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .x_label_formatter(&x_tick)
        .y_label_formatter(&y_tick)
        .label_style(("sans-serif", 13))
        .light_line_style(BLACK.mix(0.05))
        .draw()
        .map_err(err)
}

/// The legend box at `position`.
fn draw_legend<'a, 'b: 'a>(
    chart: &mut Chart<'a, 'b>,
    position: SeriesLabelPosition,
    font_px: u32,
) -> Result<(), ChartError> {
    chart
        .configure_series_labels()
        .position(position)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .label_font(("sans-serif", font_px))
        .draw()
        .map_err(err)
}

/// The names of a chart with one row per item (item `i` centred at `y = n − 1 − i + 0.5`, the
/// first on top), right-aligned left of `x`.
fn draw_row_labels<'l>(
    root: &Root<'_>,
    chart: &Chart<'_, '_>,
    labels: impl Iterator<Item = &'l str>,
    x: f64,
    n: usize,
) -> Result<(), ChartError> {
    for (i, l) in labels.enumerate() {
        let (px, py) = chart.backend_coord(&(x, (n - 1 - i) as f64 + 0.5));
        root.draw(&Text::new(
            l.to_owned(),
            (px - 8, py),
            ("sans-serif", 12).into_font().into_text_style(root).pos(
                plotters::style::text_anchor::Pos::new(
                    plotters::style::text_anchor::HPos::Right,
                    plotters::style::text_anchor::VPos::Center,
                ),
            ),
        ))
        .map_err(err)?;
    }
    Ok(())
}

/// The tick labeller of an axis spanning `range`: as many decimals as the ticks' spacing
/// needs to tell neighbours apart (plotters puts about ten ticks on an axis; a spacing of a
/// fiftieth of the span is taken, so ticks up to five times denser still differ), scientific
/// notation on an axis whose values are all tiny or huge, no trailing zeros, no `-0`, and 0
/// only for a tick at zero (within a millionth of the span).
pub fn tick_for(range: std::ops::Range<f64>) -> impl Fn(&f64) -> String {
    let span = (range.end - range.start).abs();
    let largest = range.start.abs().max(range.end.abs());
    move |v: &f64| tick_label(*v, span, largest)
}

fn tick_label(v: f64, span: f64, largest: f64) -> String {
    if !(span > 0.0 && span.is_finite()) {
        return crate::compare::sig3(v);
    }
    if v.abs() <= 1e-6 * span {
        return "0".into();
    }
    let spacing = span / 50.0;
    if !(1e-3..1e6).contains(&largest) {
        // Mantissa digits to resolve the spacing at the axis's magnitude.
        let digits = (largest.log10().floor() - spacing.log10().floor()).clamp(0.0, 12.0) as usize;
        return format!("{v:.digits$e}");
    }
    let digits = (-spacing.log10().floor()).clamp(0.0, 12.0) as usize;
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

/// One bar: a mean with its standard error, and the spread of what was averaged.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bar {
    /// Bar height (a mean).
    pub mean: f64,
    /// Standard error of the mean: the capped error bar (0 or not finite: none).
    pub se: f64,
    /// Standard deviation of the values averaged: a grey band of ± sd behind the bar (0 or not
    /// finite: none).
    pub sd: f64,
}

impl Bar {
    /// The bar of `n` values with mean `mean` and sample standard deviation `sd`.
    pub fn of(mean: f64, sd: f64, n: usize) -> Self {
        let se = if n > 1 && sd.is_finite() {
            sd / (n as f64).sqrt()
        } else {
            0.0
        };
        Self { mean, se, sd }
    }
}

/// One series of a grouped bar chart: a bar per category.
#[derive(Debug, Clone)]
pub struct BarSeries {
    /// Legend label.
    pub label: String,
    /// Colour.
    pub colour: RGBColor,
    /// Per category, `None` draws nothing.
    pub values: Vec<Option<Bar>>,
}

/// Grouped bars of means with their standard errors (capped error bars) and the spread of the
/// values as a grey band (e.g. mean error per group, before and after). The value axis leaves
/// room above the data for the legend, so it covers no bar.
pub fn grouped_bars_svg(
    title: &str,
    y_label: &str,
    categories: &[String],
    series: &[BarSeries],
) -> Result<String, ChartError> {
    let n = categories.len().max(1);
    let all = series.iter().flat_map(|s| {
        s.values.iter().flatten().flat_map(|b| {
            let sd = if b.sd.is_finite() { b.sd.abs() } else { 0.0 };
            [b.mean - sd, b.mean + sd, b.mean]
        })
    });
    let (lo, hi) = range(all, Some(0.0));
    let hi = if series.len() > 1 {
        hi + 0.3 * (hi - lo)
    } else {
        hi
    };
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
            let x0 = |i: usize| i as f64 + 0.1 + k as f64 * slot;
            let bands = s.values.iter().enumerate().filter_map(|(i, b)| {
                let b = (*b)?;
                (b.sd.is_finite() && b.sd > 0.0).then(|| {
                    Rectangle::new(
                        [(x0(i), b.mean - b.sd), (x0(i) + slot, b.mean + b.sd)],
                        BLACK.mix(0.08).filled(),
                    )
                })
            });
            chart.draw_series(bands).map_err(err)?;
            let colour = s.colour;
            let bars = s.values.iter().enumerate().filter_map(|(i, b)| {
                let b = (*b)?;
                Some(Rectangle::new(
                    [(x0(i) + 0.2 * slot, 0.0), (x0(i) + 0.8 * slot, b.mean)],
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
            for (i, b) in s.values.iter().enumerate() {
                let Some(b) = *b else { continue };
                if !(b.se.is_finite() && b.se > 0.0) {
                    continue;
                }
                let (xc, cap, v, e) = (x0(i) + 0.5 * slot, 0.12 * slot, b.mean, b.se);
                chart
                    .draw_series([
                        PathElement::new(vec![(xc, v - e), (xc, v + e)], BLACK.stroke_width(2)),
                        PathElement::new(
                            vec![(xc - cap, v - e), (xc + cap, v - e)],
                            BLACK.stroke_width(2),
                        ),
                        PathElement::new(
                            vec![(xc - cap, v + e), (xc + cap, v + e)],
                            BLACK.stroke_width(2),
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
) -> Result<String, ChartError> {
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
        draw_value_mesh(&mut chart, x_label, y_label)?;
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
pub fn estimates_svg(title: &str, unit: &str, rows: &[Estimate]) -> Result<String, ChartError> {
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
            .x_label_formatter(&tick_for(x0..x1))
            .label_style(("sans-serif", 12))
            .draw()
            .map_err(err)?;
        let row_y = |i: usize| (n - 1 - i) as f64 + 0.5;
        draw_row_labels(&root, &chart, rows.iter().map(|r| r.label.as_str()), x0, n)?;
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
/// the penalty that gain must beat). Horizontal: one row per candidate, its name on the left, so
/// the chart keeps its width (and its labels their size) however many candidates there are;
/// what the bars and marks are is said on the axis, not in a legend box that could cover them.
pub fn bars_with_line_svg(
    title: &str,
    x_label: &str,
    labels: &[String],
    values: &[f64],
    line: Option<(&[f64], &str)>,
) -> Result<String, ChartError> {
    let n = labels.len().max(1);
    let (lo, hi) = range(
        values
            .iter()
            .copied()
            .chain(line.iter().flat_map(|l| l.0.iter().copied())),
        Some(0.0),
    );
    let axis = match line {
        Some((_, what)) => format!("{x_label} (bars); {what} (red marks)"),
        None => x_label.to_owned(),
    };
    let mut svg = String::new();
    {
        let root =
            SVGBackend::with_string(&mut svg, (SIZE.0, 100 + 24 * n as u32)).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        let mut chart = build_chart(&root, title, (44, 190), lo..hi, 0.0..n as f64)?;
        chart
            .configure_mesh()
            .disable_y_mesh()
            .y_label_formatter(&|_| String::new())
            .set_tick_mark_size(LabelAreaPosition::Left, 0)
            .x_desc(axis)
            .x_label_formatter(&tick_for(lo..hi))
            .light_line_style(BLACK.mix(0.04))
            .label_style(("sans-serif", 12))
            .draw()
            .map_err(err)?;
        let row_y = |i: usize| (n - 1 - i) as f64;
        draw_row_labels(&root, &chart, labels.iter().map(String::as_str), lo, n)?;
        chart
            .draw_series(values.iter().enumerate().map(|(i, &v)| {
                Rectangle::new(
                    [(0.0, row_y(i) + 0.15), (v, row_y(i) + 0.85)],
                    BLUE_C.mix(0.85).filled(),
                )
            }))
            .map_err(err)?;
        if let Some((marks, _)) = line {
            chart
                .draw_series(marks.iter().enumerate().map(|(i, &v)| {
                    PathElement::new(
                        vec![(v, row_y(i) + 0.05), (v, row_y(i) + 0.95)],
                        RED_C.stroke_width(3),
                    )
                }))
                .map_err(err)?;
        }
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
mod tests;
