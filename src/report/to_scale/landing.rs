//! Landing patterns seen from above: every landing point of each pattern (its dot's area
//! grows with the point's weight), the pattern's mean and its dispersion ellipse, offline
//! across and carry up, both in yards to one scale.

use std::fmt::Write as _;

use super::{fin, Frame};
use crate::report::html::esc;

/// The dispersion ellipse of a pattern, yd.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatternEllipse {
    /// Centre: mean offline, yd (+ right).
    pub centre_offline_yd: f64,
    /// Centre: mean carry, yd.
    pub centre_carry_yd: f64,
    /// Semi-major axis, yd.
    pub semi_major_yd: f64,
    /// Semi-minor axis, yd.
    pub semi_minor_yd: f64,
    /// Angle of the major axis from the carry direction toward + offline, degrees.
    pub major_from_carry_deg: f64,
}

/// One pattern to draw.
#[derive(Debug, Clone, Copy)]
pub struct Pattern<'a> {
    /// Legend name (`base`, `changed`).
    pub label: &'a str,
    /// Class of its elements (`base`, `changed`): `landing base`, `ellipse base`, `mean base`.
    pub class: &'a str,
    /// Colour (`#rrggbb`).
    pub colour: &'a str,
    /// Landing points: `(offline yd, carry yd, weight)`.
    pub points: &'a [(f64, f64, f64)],
    /// Its ellipse.
    pub ellipse: PatternEllipse,
}

/// The patterns on one picture, with the target line (offline 0) and a legend; `confidence`
/// names the ellipses' level in the legend.
pub fn landing_svg(title: &str, confidence: f64, patterns: &[Pattern<'_>]) -> String {
    let mut extent = Vec::new();
    for p in patterns {
        extent.extend(p.points.iter().map(|q| (q.0, q.1)));
        let e = &p.ellipse;
        let r = fin(e.semi_major_yd);
        extent.push((e.centre_offline_yd - r, e.centre_carry_yd - r));
        extent.push((e.centre_offline_yd + r, e.centre_carry_yd + r));
    }
    extent.push((0.0, extent.first().map_or(0.0, |p| p.1)));
    let f = Frame::holding(&extent, 2.0, 10.0, 420.0);
    let mut s = String::new();
    f.open(&mut s, title, "landing-patterns");
    f.axes(
        &mut s,
        "offline, yd (+ right of the target line)",
        "carry, yd",
    );
    // The target line.
    if (f.x0..=f.x1()).contains(&0.0) {
        let x = f.px(0.0);
        let _ = writeln!(
            s,
            r##"<line class="target-line" x1="{x:.2}" y1="{}" x2="{x:.2}" y2="{}" stroke="#888" stroke-dasharray="5 4"/>"##,
            f.top,
            f.top + f.plot_h
        );
    }
    for p in patterns {
        draw_points(&mut s, &f, p);
    }
    for p in patterns {
        draw_ellipse(&mut s, &f, p);
    }
    let mut legend = Vec::new();
    for p in patterns {
        legend.push((
            format!(
                r#"<circle cx="0" cy="0" r="4" fill="{c}" fill-opacity="0.5"/><ellipse cx="0" cy="0" rx="8" ry="5" fill="none" stroke="{c}" stroke-width="2"/>"#,
                c = esc(p.colour)
            ),
            format!("{} ({:.0} % ellipse)", p.label, 100.0 * fin(confidence)),
        ));
    }
    f.legend(&mut s, &legend);
    s.push_str("</svg>\n");
    s
}

/// The pattern's landing points, each a dot whose area grows with its weight (at least a
/// visible speck).
fn draw_points(s: &mut String, f: &Frame, p: &Pattern<'_>) {
    let w_max = p
        .points
        .iter()
        .map(|q| fin(q.2))
        .fold(0.0f64, f64::max)
        .max(f64::MIN_POSITIVE);
    let _ = writeln!(
        s,
        r#"<g class="landing {}" fill="{}" fill-opacity="0.45">"#,
        esc(p.class),
        esc(p.colour)
    );
    for &(x, y, w) in p.points {
        if !(x.is_finite() && y.is_finite()) {
            continue;
        }
        let r = 1.5 + 4.0 * (fin(w).max(0.0) / w_max).sqrt();
        let _ = writeln!(
            s,
            r#"<circle cx="{:.2}" cy="{:.2}" r="{r:.2}"/>"#,
            f.px(x),
            f.py(y)
        );
    }
    s.push_str("</g>\n");
}

/// The ellipse (an SVG `<ellipse>` rotated to its major axis) and a cross at the mean.
fn draw_ellipse(s: &mut String, f: &Frame, p: &Pattern<'_>) {
    let e = &p.ellipse;
    let (cx, cy) = (f.px(fin(e.centre_offline_yd)), f.py(fin(e.centre_carry_yd)));
    let (rx, ry) = (
        fin(e.semi_major_yd).max(0.0) * f.px_per_unit,
        fin(e.semi_minor_yd).max(0.0) * f.px_per_unit,
    );
    // The major axis points (sin α, cos α) in (offline, carry), (sin α, −cos α) on the screen:
    // SVG's rotate(α − 90°) turns the ellipse's x axis there.
    let rot = fin(e.major_from_carry_deg) - 90.0;
    let _ = writeln!(
        s,
        r#"<ellipse class="ellipse {}" cx="{cx:.2}" cy="{cy:.2}" rx="{rx:.2}" ry="{ry:.2}" transform="rotate({rot:.3} {cx:.2} {cy:.2})" fill="none" stroke="{}" stroke-width="2.2" data-semi-major-yd="{}" data-semi-minor-yd="{}"/>"#,
        esc(p.class),
        esc(p.colour),
        fin(e.semi_major_yd),
        fin(e.semi_minor_yd),
    );
    let _ = writeln!(
        s,
        r#"<g class="mean {}" stroke="{}" stroke-width="2.2"><line x1="{:.2}" y1="{cy:.2}" x2="{:.2}" y2="{cy:.2}"/><line x1="{cx:.2}" y1="{:.2}" x2="{cx:.2}" y2="{:.2}"/></g>"#,
        esc(p.class),
        esc(p.colour),
        cx - 6.0,
        cx + 6.0,
        cy - 6.0,
        cy + 6.0
    );
}
