//! Small multiples: compact face maps drawn on limits the caller gives (one colour scale shared
//! by a set of maps), and the one colour bar of such a set. Sized to be read at print size in
//! a column a third of a page wide: 240 px wide pictures with 12 px labels and up.

use std::fmt::Write as _;

use super::{edges, esc, label, nice_ticks, ramp, Scale, DIVERGING, VIRIDIS};

/// Width of a small multiple, px.
pub const SMALL_WIDTH_PX: f64 = 240.0;

/// One small multiple: the cells of a map (row-major, `ys × xs`, NaN where there is no value)
/// under a short title.
#[derive(Debug, Clone, Copy)]
pub struct SmallMap<'a> {
    /// Title above the map (e.g. `1` or `3 − base`).
    pub title: &'a str,
    /// Column centres (toward the toe), mm, ascending.
    pub xs: &'a [f64],
    /// Row centres (up the face), mm, ascending.
    pub ys: &'a [f64],
    /// Values, row-major, `ys.len() × xs.len()`.
    pub values: &'a [f64],
    /// Colour-scale limits `(low, high)` shared by the set; `high > low`.
    pub limits: (f64, f64),
    /// Colour scale.
    pub scale: Scale,
}

/// The colour of `v` on `scale` between `lo` and `hi`.
pub fn scale_colour(scale: Scale, v: f64, lo: f64, hi: f64) -> String {
    let t = (v - lo) / (hi - lo);
    match scale {
        Scale::Sequential => ramp(&VIRIDIS, t),
        Scale::Diverging => ramp(&DIVERGING, t),
    }
}

/// Colour limits of a set of maps: the finite min and max of every value (symmetric about 0 on
/// a diverging scale), widened when flat; `None` when no value is finite.
pub fn shared_limits<'a>(
    values: impl IntoIterator<Item = &'a f64>,
    scale: Scale,
) -> Option<(f64, f64)> {
    let mut it = values.into_iter().copied().filter(|v| v.is_finite());
    let first = it.next()?;
    let (lo, hi) = it.fold((first, first), |(lo, hi), v| (lo.min(v), hi.max(v)));
    let (lo, hi) = match scale {
        Scale::Sequential => (lo, hi),
        Scale::Diverging => {
            let m = lo.abs().max(hi.abs());
            (-m, m)
        }
    };
    Some(if hi > lo {
        (lo, hi)
    } else {
        let pad = if lo == 0.0 { 1.0 } else { lo.abs() * 1e-3 };
        (lo - pad, hi + pad)
    })
}

/// A compact picture of one map: cells in the shared colours, the face centre marked, ticks at
/// the round millimetres of both axes. No colour bar (see [`colour_bar_svg`]).
pub fn small_map_svg(m: &SmallMap<'_>) -> String {
    assert_eq!(
        m.values.len(),
        m.xs.len() * m.ys.len(),
        "values must be ys × xs"
    );
    let (left, top, w) = (36.0, 24.0, SMALL_WIDTH_PX - 46.0);
    let (xe, ye) = (edges(m.xs), edges(m.ys));
    let (x0, x1, y0, y1) = (xe[0], xe[xe.len() - 1], ye[0], ye[ye.len() - 1]);
    // The face in proportion, within limits.
    let h = (w * (y1 - y0) / (x1 - x0)).clamp(60.0, 200.0);
    let px = |x: f64| left + (x - x0) / (x1 - x0) * w;
    let py = |y: f64| top + h - (y - y0) / (y1 - y0) * h;
    let height = top + h + 20.0;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{SMALL_WIDTH_PX}" height="{height:.0}" viewBox="0 0 {SMALL_WIDTH_PX} {height:.0}" font-family="Helvetica, Arial, sans-serif" font-size="12">"#
    );
    let _ = writeln!(
        s,
        r#"<text x="{:.1}" y="16" font-size="14" text-anchor="middle" font-weight="bold">{}</text>"#,
        left + w / 2.0,
        esc(m.title)
    );
    let _ = writeln!(s, r#"<g shape-rendering="crispEdges">"#);
    let (lo, hi) = m.limits;
    let nx = m.xs.len();
    for i in 0..m.ys.len() {
        let (ya, yb) = (py(ye[i + 1]), py(ye[i]));
        for j in 0..nx {
            let (xa, xb) = (px(xe[j]), px(xe[j + 1]));
            let v = m.values[i * nx + j];
            let fill = if v.is_finite() {
                scale_colour(m.scale, v, lo, hi)
            } else {
                "#e0e0e0".into()
            };
            let _ = writeln!(
                s,
                r#"<rect x="{xa:.1}" y="{ya:.1}" width="{:.1}" height="{:.1}" fill="{fill}"/>"#,
                xb - xa + 0.3,
                yb - ya + 0.3
            );
        }
    }
    let _ = writeln!(s, "</g>");
    let _ = writeln!(
        s,
        r#"<rect x="{left}" y="{top}" width="{w}" height="{h:.1}" fill="none" stroke="black"/>"#
    );
    for t in nice_ticks(x0, x1, 4) {
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text>"#,
            px(t),
            top + h + 14.0,
            label(t)
        );
    }
    for t in nice_ticks(y0, y1, 5) {
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="end">{}</text>"#,
            left - 3.0,
            py(t) + 4.0,
            label(t)
        );
    }
    if (x0..=x1).contains(&0.0) && (y0..=y1).contains(&0.0) {
        let _ = writeln!(
            s,
            r#"<circle cx="{:.1}" cy="{:.1}" r="4" fill="none" stroke="black" stroke-width="1.2"/>"#,
            px(0.0),
            py(0.0)
        );
    }
    s.push_str("</svg>\n");
    s
}

/// The one horizontal colour bar of a set of small multiples: `lo` to `hi` on `scale`, ticks,
/// and the value label with its unit.
pub fn colour_bar_svg(value_label: &str, limits: (f64, f64), scale: Scale) -> String {
    let (lo, hi) = limits;
    let (left, w, width, height) = (20.0, 420.0, 460.0, 62.0);
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="Helvetica, Arial, sans-serif" font-size="12">"#
    );
    let steps = 64;
    for k in 0..steps {
        let v = lo + (k as f64 + 0.5) / steps as f64 * (hi - lo);
        let _ = writeln!(
            s,
            r#"<rect x="{:.2}" y="4" width="{:.2}" height="16" fill="{}" shape-rendering="crispEdges"/>"#,
            left + k as f64 / steps as f64 * w,
            w / steps as f64 + 0.3,
            scale_colour(scale, v, lo, hi)
        );
    }
    let _ = writeln!(
        s,
        r#"<rect x="{left}" y="4" width="{w}" height="16" fill="none" stroke="black"/>"#
    );
    for t in nice_ticks(lo, hi, 6) {
        let x = left + (t - lo) / (hi - lo) * w;
        let _ = writeln!(
            s,
            r#"<line x1="{x:.2}" y1="20" x2="{x:.2}" y2="25" stroke="black"/><text x="{x:.2}" y="37" text-anchor="middle">{}</text>"#,
            label(t)
        );
    }
    let _ = writeln!(
        s,
        r#"<text x="{:.1}" y="56" text-anchor="middle">{}</text>"#,
        left + w / 2.0,
        esc(value_label)
    );
    s.push_str("</svg>\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shared_limits_cover_every_map_and_are_symmetric_when_diverging() {
        let a = [1.0, 2.0, f64::NAN];
        let b = [-4.0, 3.0];
        assert_eq!(
            shared_limits(a.iter().chain(&b), Scale::Sequential),
            Some((-4.0, 3.0))
        );
        assert_eq!(
            shared_limits(a.iter().chain(&b), Scale::Diverging),
            Some((-4.0, 4.0))
        );
        assert_eq!(shared_limits(&[f64::NAN], Scale::Sequential), None);
        // A flat set (a difference map of the base against itself) is widened, never 0/0.
        let (lo, hi) = shared_limits(&[0.0, 0.0], Scale::Diverging).unwrap();
        assert!(lo < 0.0 && hi > 0.0);
    }

    #[test]
    fn the_same_value_has_the_same_colour_in_every_multiple() {
        let (xs, ys) = ([-1.0, 1.0], [0.0]);
        let draw = |v: [f64; 2]| {
            small_map_svg(&SmallMap {
                title: "1",
                xs: &xs,
                ys: &ys,
                values: &v,
                limits: (0.0, 10.0),
                scale: Scale::Sequential,
            })
        };
        let colour = scale_colour(Scale::Sequential, 5.0, 0.0, 10.0);
        // Alone, each map's own range would colour 5 differently (lowest in one, highest in
        // the other); on the shared limits it is one colour.
        assert!(draw([5.0, 9.0]).contains(&colour));
        assert!(draw([1.0, 5.0]).contains(&colour));
        assert!(!draw([1.0, 5.0]).to_lowercase().contains("nan"));
    }
}
