//! Pictures drawn to scale (one unit is as long across as up), as SVG strings: the landing
//! patterns of two heads with their dispersion ellipses ([`landing_svg`]) and a head seen from
//! above or from behind with its CoM and a moved mass before and after ([`head_view_svg`]).
//! Each picture's elements carry classes (`landing base`, `ellipse changed`, `com after`, …)
//! that name what they show. Builds strings only; takes plain numbers, so the statistics stay
//! where they are computed (`crate::study::landing`).

mod head;
mod landing;

use std::fmt::Write as _;

use crate::report::heatmap::nice_ticks;
use crate::report::html::esc;

pub use head::{head_view_svg, HeadPoints, MovedMass, View};
pub use landing::{landing_svg, Pattern, PatternEllipse};

/// The colour of the base head (the charts' blue).
pub const BASE_COLOUR: &str = "#1f77b4";
/// The colour of the changed head (the charts' orange).
pub const CHANGED_COLOUR: &str = "#e67814";

/// Width of a picture, px (it scales with the page's CSS; labels stay legible in a 468 px
/// figure).
const WIDTH_PX: f64 = 520.0;

/// The plot area and the one scale of both axes.
struct Frame {
    left: f64,
    top: f64,
    plot_w: f64,
    plot_h: f64,
    /// Data at the plot's left and bottom edges.
    x0: f64,
    y0: f64,
    /// Pixels per data unit, both axes.
    px_per_unit: f64,
}

impl Frame {
    /// A frame holding every finite `(x, y)` of `points` with `pad` units around, at least
    /// `min_span` units across and up, in a plot `plot_w` px wide of at most `max_h` px.
    fn holding(points: &[(f64, f64)], pad: f64, min_span: f64, max_h: f64) -> Self {
        let finite = points.iter().filter(|p| p.0.is_finite() && p.1.is_finite());
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for &(x, y) in finite {
            (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
        }
        if x0 > x1 {
            (x0, x1, y0, y1) = (0.0, 0.0, 0.0, 0.0);
        }
        let widen = |a: f64, b: f64| {
            let span = (b - a + 2.0 * pad).max(min_span);
            let mid = 0.5 * (a + b);
            (mid - 0.5 * span, span)
        };
        let (x0, x_span) = widen(x0, x1);
        let (y0, y_span) = widen(y0, y1);
        let plot_w = WIDTH_PX - 90.0;
        // One scale: the width sets it unless the height would be too tall; the axis with room
        // to spare shows more, the data centred.
        let px_per_unit = (plot_w / x_span).min(max_h / y_span);
        let plot_h = (y_span * px_per_unit).max(0.5 * max_h);
        let (shown_w, shown_h) = (plot_w / px_per_unit, plot_h / px_per_unit);
        Frame {
            left: 70.0,
            top: 40.0,
            plot_w,
            plot_h,
            x0: x0 - 0.5 * (shown_w - x_span),
            y0: y0 - 0.5 * (shown_h - y_span),
            px_per_unit,
        }
    }

    fn px(&self, x: f64) -> f64 {
        self.left + (x - self.x0) * self.px_per_unit
    }

    fn py(&self, y: f64) -> f64 {
        self.top + self.plot_h - (y - self.y0) * self.px_per_unit
    }

    fn x1(&self) -> f64 {
        self.x0 + self.plot_w / self.px_per_unit
    }

    fn y1(&self) -> f64 {
        self.y0 + self.plot_h / self.px_per_unit
    }

    /// The picture's height, px (room below for the axis label and a legend line).
    fn height(&self) -> f64 {
        self.top + self.plot_h + 70.0
    }

    /// `<svg …>`, the background and the title.
    fn open(&self, s: &mut String, title: &str, kind: &str) {
        let (w, h) = (WIDTH_PX, self.height());
        let _ = writeln!(
            s,
            r#"<svg xmlns="http://www.w3.org/2000/svg" class="{kind}" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="Helvetica, Arial, sans-serif" font-size="13">"#
        );
        let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
        let _ = writeln!(
            s,
            r#"<text x="{}" y="24" font-size="16" text-anchor="middle">{}</text>"#,
            self.left + self.plot_w / 2.0,
            esc(title)
        );
    }

    /// The border, a light grid at the ticks, tick labels and both axis labels (with units).
    fn axes(&self, s: &mut String, x_label: &str, y_label: &str) {
        let (l, t, w, h) = (self.left, self.top, self.plot_w, self.plot_h);
        let b = t + h;
        for v in nice_ticks(self.x0, self.x1(), 7) {
            let x = self.px(v);
            let _ = writeln!(
                s,
                r##"<line x1="{x:.2}" y1="{t}" x2="{x:.2}" y2="{b}" stroke="#eee"/><line x1="{x:.2}" y1="{b}" x2="{x:.2}" y2="{}" stroke="black"/><text x="{x:.2}" y="{}" text-anchor="middle">{}</text>"##,
                b + 5.0,
                b + 18.0,
                tick(v)
            );
        }
        for v in nice_ticks(self.y0, self.y1(), 6) {
            let y = self.py(v);
            let _ = writeln!(
                s,
                r##"<line x1="{l}" y1="{y:.2}" x2="{}" y2="{y:.2}" stroke="#eee"/><line x1="{}" y1="{y:.2}" x2="{l}" y2="{y:.2}" stroke="black"/><text x="{}" y="{:.2}" text-anchor="end">{}</text>"##,
                l + w,
                l - 5.0,
                l - 8.0,
                y + 4.0,
                tick(v)
            );
        }
        let _ = writeln!(
            s,
            r#"<rect x="{l}" y="{t}" width="{w}" height="{h}" fill="none" stroke="black"/>"#
        );
        let _ = writeln!(
            s,
            r#"<text class="x-label" x="{}" y="{}" text-anchor="middle">{}</text>"#,
            l + w / 2.0,
            b + 38.0,
            esc(x_label)
        );
        let cy = t + h / 2.0;
        let _ = writeln!(
            s,
            r#"<text class="y-label" x="18" y="{cy}" text-anchor="middle" transform="rotate(-90 18 {cy})">{}</text>"#,
            esc(y_label)
        );
    }

    /// One legend line under the axis label: a swatch (SVG elements at `(0, 0)`, translated)
    /// and its text per entry, left to right.
    fn legend(&self, s: &mut String, entries: &[(String, String)]) {
        let y = self.top + self.plot_h + 58.0;
        let mut x = self.left;
        for (swatch, text) in entries {
            let _ = writeln!(
                s,
                r#"<g transform="translate({x:.1} {y:.1})">{swatch}</g><text x="{:.1}" y="{:.1}">{}</text>"#,
                x + 12.0,
                y + 4.5,
                esc(text)
            );
            x += 30.0 + 7.0 * text.chars().count() as f64;
        }
    }
}

/// A tick label: at most two decimals, no trailing zeros, no `-0`.
fn tick(v: f64) -> String {
    let s = format!("{v:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}

/// `v` if finite, else 0 (no NaN or inf reaches a picture).
fn fin(v: f64) -> f64 {
    if v.is_finite() {
        v
    } else {
        0.0
    }
}

/// An arrow from `a` to `b` (px) in `colour`, its elements of class `class`.
fn arrow(s: &mut String, class: &str, a: (f64, f64), b: (f64, f64), colour: &str) {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len = dx.hypot(dy);
    if !(len > 1.0) {
        return;
    }
    let (ux, uy) = (dx / len, dy / len);
    let head = 7.0f64.min(0.5 * len);
    let (bx, by) = (b.0 - head * ux, b.1 - head * uy);
    let _ = writeln!(
        s,
        r#"<g class="{class}" stroke="{colour}" fill="{colour}" stroke-width="1.6"><line x1="{:.2}" y1="{:.2}" x2="{bx:.2}" y2="{by:.2}"/><polygon points="{:.2},{:.2} {:.2},{:.2} {:.2},{:.2}" stroke="none"/></g>"#,
        a.0,
        a.1,
        b.0,
        b.1,
        bx - 0.45 * head * uy,
        by + 0.45 * head * ux,
        bx + 0.45 * head * uy,
        by - 0.45 * head * ux,
    );
}

#[cfg(test)]
mod tests;
