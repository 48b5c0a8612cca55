//! Drawing a heatmap as SVG: the plot frame (geometry and data-to-pixel maps), the cells, the
//! axes, the marker and the colour bar, each a function writing its elements.

use std::fmt::Write as _;

use super::{colour, edges, esc, label, limits, nice_ticks, Heatmap};

/// Where things go in the picture: the plot area, the colour bar and the data ranges.
struct Frame {
    /// Plot area: left and top edges and size, px.
    left: f64,
    top: f64,
    plot_w: f64,
    plot_h: f64,
    /// Left edge of the colour bar, px.
    bar_x: f64,
    /// Cell edges along x and y, data units.
    xe: Vec<f64>,
    ye: Vec<f64>,
    /// Data range of the axes.
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
}

impl Frame {
    fn new(map: &Heatmap<'_>) -> Self {
        Self::on_edges(edges(map.xs), edges(map.ys))
    }

    /// The frame of cells with edges `xe` and `ye` (ascending, one more than the cells).
    fn on_edges(xe: Vec<f64>, ye: Vec<f64>) -> Self {
        let (left, top, plot_w) = (80.0, 50.0, 560.0);
        Frame {
            left,
            top,
            plot_w,
            plot_h: 420.0,
            bar_x: left + plot_w + 30.0,
            x0: xe[0],
            x1: xe[xe.len() - 1],
            y0: ye[0],
            y1: ye[ye.len() - 1],
            xe,
            ye,
        }
    }

    /// Pixel column of data `x`.
    fn px(&self, x: f64) -> f64 {
        self.left + (x - self.x0) / (self.x1 - self.x0) * self.plot_w
    }

    /// Pixel row of data `y` (up is up).
    fn py(&self, y: f64) -> f64 {
        self.top + self.plot_h - (y - self.y0) / (self.y1 - self.y0) * self.plot_h
    }

    /// Bottom edge of the plot area, px.
    fn bottom(&self) -> f64 {
        self.top + self.plot_h
    }
}

/// The picture: title, cells, axes, marker, colour bar and, when some cells have no value,
/// their legend.
pub(super) fn draw_svg(map: &Heatmap<'_>) -> String {
    draw_framed(map, &Frame::new(map))
}

/// The picture of `map` whose cells have the edges `xe` and `ye` (bins of unequal width, e.g.
/// quantiles), instead of edges halfway between the cell centres.
pub(super) fn draw_svg_on_edges(map: &Heatmap<'_>, xe: &[f64], ye: &[f64]) -> String {
    assert!(
        xe.len() == map.xs.len() + 1 && ye.len() == map.ys.len() + 1,
        "a heatmap needs one edge more than cells on each axis"
    );
    draw_framed(map, &Frame::on_edges(xe.to_vec(), ye.to_vec()))
}

fn draw_framed(map: &Heatmap<'_>, f: &Frame) -> String {
    let width = f.bar_x + 110.0;
    let height = f.top + f.plot_h + 76.0;
    let (lo, hi) = limits(map);
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="Helvetica, Arial, sans-serif" font-size="14">"#
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<text x="{}" y="28" font-size="17" text-anchor="middle">{}</text>"#,
        f.left + f.plot_w / 2.0,
        esc(map.title)
    );
    draw_cells(&mut s, map, f, lo, hi);
    draw_axes(&mut s, map, f);
    draw_marker(&mut s, map, f);
    draw_colour_bar(&mut s, map, f, lo, hi);
    if map.values.iter().any(|v| !v.is_finite()) {
        let _ = writeln!(
            s,
            r##"<rect x="{left}" y="{y}" width="10" height="10" fill="#e0e0e0" stroke="black"/><text x="{}" y="{}">no value (off the face or no data)</text>"##,
            f.left + 14.0,
            f.bottom() + 68.0,
            left = f.left,
            y = f.bottom() + 59.0
        );
    }
    s.push_str("</svg>\n");
    s
}

/// One rectangle per cell, coloured by value; cells without a value light grey.
fn draw_cells(s: &mut String, map: &Heatmap<'_>, f: &Frame, lo: f64, hi: f64) {
    let nx = map.xs.len();
    let _ = writeln!(s, r#"<g shape-rendering="crispEdges">"#);
    // `<rect x="{xa:.2}" y="{ya:.2}" width="{w:.2}" height="{h:.2}" fill="{fill}"/>` per cell,
    // with x and width formatted once per column and y and height once per row.
    let cols: Vec<(String, String)> = (0..nx)
        .map(|j| {
            let (xa, xb) = (f.px(f.xe[j]), f.px(f.xe[j + 1]));
            (
                format!(r#"<rect x="{xa:.2}" y=""#),
                format!(r#"" width="{:.2}" height=""#, (xb - xa) + 0.3),
            )
        })
        .collect();
    for i in 0..map.ys.len() {
        let (ya, yb) = (f.py(f.ye[i + 1]), f.py(f.ye[i]));
        let (y, h) = (format!("{ya:.2}"), format!("{:.2}", (yb - ya) + 0.3));
        for (j, (head, width)) in cols.iter().enumerate() {
            let v = map.values[i * nx + j];
            let fill = if v.is_finite() {
                colour(map, v, lo, hi)
            } else {
                "#e0e0e0".into()
            };
            for part in [head, &y, width, &h, "\" fill=\"", &fill, "\"/>\n"] {
                s.push_str(part);
            }
        }
    }
    let _ = writeln!(s, "</g>");
}

/// The plot's border, ticks with labels on both axes, and the axis labels.
fn draw_axes(s: &mut String, map: &Heatmap<'_>, f: &Frame) {
    let (left, top, plot_w, plot_h) = (f.left, f.top, f.plot_w, f.plot_h);
    let _ = writeln!(
        s,
        r#"<rect x="{left}" y="{top}" width="{plot_w}" height="{plot_h}" fill="none" stroke="black"/>"#
    );
    for t in nice_ticks(f.x0, f.x1, 8) {
        let x = f.px(t);
        let _ = writeln!(
            s,
            r#"<line x1="{x:.2}" y1="{b}" x2="{x:.2}" y2="{b2}" stroke="black"/><text x="{x:.2}" y="{ty}" text-anchor="middle">{}</text>"#,
            label(t),
            b = top + plot_h,
            b2 = top + plot_h + 5.0,
            ty = top + plot_h + 19.0
        );
    }
    for t in nice_ticks(f.y0, f.y1, 6) {
        let y = f.py(t);
        let _ = writeln!(
            s,
            r#"<line x1="{l2}" y1="{y:.2}" x2="{left}" y2="{y:.2}" stroke="black"/><text x="{tx}" y="{:.2}" text-anchor="end">{}</text>"#,
            y + 4.0,
            label(t),
            l2 = left - 5.0,
            tx = left - 8.0
        );
    }
    let _ = writeln!(
        s,
        r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#,
        left + plot_w / 2.0,
        top + plot_h + 42.0,
        esc(map.x_label)
    );
    let _ = writeln!(
        s,
        r#"<text x="22" y="{cy}" text-anchor="middle" transform="rotate(-90 22 {cy})">{}</text>"#,
        esc(map.y_label),
        cy = top + plot_h / 2.0
    );
}

/// A cross-hair circle at the map's marker, when it lies inside the plot.
fn draw_marker(s: &mut String, map: &Heatmap<'_>, f: &Frame) {
    let Some((mx, my)) = map.marker else { return };
    if (f.x0..=f.x1).contains(&mx) && (f.y0..=f.y1).contains(&my) {
        let (cx, cy) = (f.px(mx), f.py(my));
        let _ = writeln!(
            s,
            r#"<g stroke="black" stroke-width="1.5" fill="none"><circle cx="{cx:.2}" cy="{cy:.2}" r="6"/><line x1="{:.2}" y1="{cy:.2}" x2="{:.2}" y2="{cy:.2}"/><line x1="{cx:.2}" y1="{:.2}" x2="{cx:.2}" y2="{:.2}"/></g>"#,
            cx - 10.0,
            cx + 10.0,
            cy - 10.0,
            cy + 10.0
        );
    }
}

/// The colour bar from `lo` to `hi`: 64 bands, a border, ticks and the value label with unit.
fn draw_colour_bar(s: &mut String, map: &Heatmap<'_>, f: &Frame, lo: f64, hi: f64) {
    let (bar_x, top, plot_h) = (f.bar_x, f.top, f.plot_h);
    let steps = 64;
    for k in 0..steps {
        let t0 = k as f64 / steps as f64;
        let v = lo + (t0 + 0.5 / steps as f64) * (hi - lo);
        let y = top + plot_h - (k + 1) as f64 / steps as f64 * plot_h;
        let _ = writeln!(
            s,
            r#"<rect x="{bar_x}" y="{y:.2}" width="18" height="{:.2}" fill="{}" shape-rendering="crispEdges"/>"#,
            plot_h / steps as f64 + 0.3,
            colour(map, v, lo, hi)
        );
    }
    let _ = writeln!(
        s,
        r#"<rect x="{bar_x}" y="{top}" width="18" height="{plot_h}" fill="none" stroke="black"/>"#
    );
    for t in nice_ticks(lo, hi, 6) {
        let y = top + plot_h - (t - lo) / (hi - lo) * plot_h;
        let _ = writeln!(
            s,
            r#"<line x1="{a}" y1="{y:.2}" x2="{b}" y2="{y:.2}" stroke="black"/><text x="{tx}" y="{:.2}">{}</text>"#,
            y + 4.0,
            label(t),
            a = bar_x + 18.0,
            b = bar_x + 23.0,
            tx = bar_x + 26.0
        );
    }
    let _ = writeln!(
        s,
        r#"<text x="{cx}" y="{cy}" text-anchor="middle" transform="rotate(90 {cx} {cy})">{}</text>"#,
        esc(map.value_label),
        cx = bar_x + 88.0,
        cy = top + plot_h / 2.0
    );
}
