//! What `smash whatif` reports, as one value: [`WhatIfReport`], one design change answered in
//! yards against the base head for a stated golfer and mishit pattern. Its text is a table of
//! the quantities (base, changed, change ± the quadrature's error) and the heads in numbers;
//! its page ([`crate::report::render::Render`]) draws both landing patterns with their
//! dispersion ellipses, the head from above and from behind with its CoM and the moved mass
//! before and after, and the carry change over the face, then the table and the heads in
//! numbers. The pages' shared style; no scripts; the pictures are inline SVG.

use std::fmt::Write as _;

use crate::report::charts::ChartError;
use crate::report::heatmap::{heatmap_svg, Heatmap, Scale};
use crate::report::html::{esc, CSS};
use crate::report::render::Render;
use crate::report::text::wrap_long;
use crate::report::to_scale::{
    head_view_svg, landing_svg, HeadPoints, MovedMass, Pattern, PatternEllipse, View, BASE_COLOUR,
    CHANGED_COLOUR,
};
use crate::study::landing::Landing;
use crate::study::whatif::{head_text, CarryChangeMap, HeadChange, WhatIf};
use crate::study::yards_variants::{decimals, delta, delta_text, QUANTITIES};
use crate::units::M_PER_MM;

/// What `smash whatif` reports.
pub struct WhatIfReport {
    /// The base club's name.
    pub club: String,
    /// The change asked about.
    pub change: HeadChange,
    /// The golfer and the mishit pattern, in words.
    pub setting: String,
    /// Both heads in yards.
    pub whatif: WhatIf,
    /// The carry change over the face and the mishit pattern's centre `[y, z]`, mm, when it
    /// could be computed (the page leaves its figure out otherwise).
    pub map: Option<(CarryChangeMap, [f64; 2])>,
}

impl Render for WhatIfReport {
    type Context = ();

    /// The change and the setting as sentences (wrapped, as the other reports' prose is, to fit
    /// a terminal), the heads in numbers and the table.
    fn text(&self, _: &()) -> String {
        let mut text = wrap_long(&format!(
            "what if: {} ({}, nominal head)\n{}\n",
            self.change.describe().join("; "),
            self.club,
            self.setting
        ));
        text.push_str(&head_text(&self.whatif));
        text.push_str(&table_text(&self.whatif));
        text
    }

    fn html(&self, _: &()) -> Option<Result<String, ChartError>> {
        Some(Ok(page(
            &self.club,
            &self.change,
            &self.setting,
            &self.whatif,
            self.map.as_ref().map(|(m, c)| (m, *c)),
        )))
    }
}

/// The comparison table: quantity, base, changed, change ± the quadrature's error estimate.
fn table_text(w: &WhatIf) -> String {
    let mut t = format!(
        "{:<34} {:>10} {:>10} {:>20}\n",
        "quantity", "base", "changed", "change ± quad. err"
    );
    for q in &QUANTITIES {
        let n = decimals(q);
        let (d, u) = delta(q, &w.base, &w.changed);
        let _ = writeln!(
            t,
            "{:<34} {:>10.n$} {:>10.n$} {:>20}",
            format!("{} ({})", q.label, q.unit),
            (q.get)(&w.base.metrics),
            (q.get)(&w.changed.metrics),
            delta_text(d, u, n)
        );
    }
    let a = w.base.metrics.ellipse_area_yd2;
    if a > 0.0 {
        let _ = writeln!(
            t,
            "dispersion-ellipse area change: {:+.2} %",
            100.0 * (w.changed.metrics.ellipse_area_yd2 - a) / a
        );
    }
    for (head, m) in [("base", &w.base.metrics), ("changed", &w.changed.metrics)] {
        if let Some(note) = m.grounded_note() {
            let _ = writeln!(t, "{head} head: {note}");
        }
    }
    t
}

/// A figure of the page: its kind (for tests), the SVG and its caption.
fn figure(kind: &str, svg: &str, caption: &str) -> String {
    format!(
        "<figure class=\"chart\" data-kind=\"{kind}\">{svg}<figcaption>{}</figcaption></figure>",
        esc(caption)
    )
}

/// `(offline, carry, weight)` of every landing point, and the ellipse at `confidence`.
fn pattern_numbers(l: &Landing, confidence: f64) -> (Vec<(f64, f64, f64)>, PatternEllipse) {
    let e = l.ellipse(confidence);
    (
        l.points
            .iter()
            .map(|p| (p.offline_yd, p.carry_yd, p.weight))
            .collect(),
        PatternEllipse {
            centre_offline_yd: e.centre_offline_yd,
            centre_carry_yd: e.centre_carry_yd,
            semi_major_yd: e.semi_major_yd,
            semi_minor_yd: e.semi_minor_yd,
            major_from_carry_deg: e.major_from_carry_deg,
        },
    )
}

/// Both landing patterns on one picture.
fn landing_figure(w: &WhatIf) -> String {
    let confidence = w.base.metrics.confidence;
    let (bp, be) = pattern_numbers(&w.base_landing, confidence);
    let (cp, ce) = pattern_numbers(&w.changed_landing, confidence);
    let svg = landing_svg(
        "Where the balls land",
        confidence,
        &[
            Pattern {
                label: "base",
                class: "base",
                colour: BASE_COLOUR,
                points: &bp,
                ellipse: be,
            },
            Pattern {
                label: "changed",
                class: "changed",
                colour: CHANGED_COLOUR,
                points: &cp,
                ellipse: ce,
            },
        ],
    );
    let caption = format!(
        "Each dot is one swing and impact of the pattern (its area grows with the point's \
         weight in the quadrature); the ellipses hold {:.0} % of the landings of a bivariate \
         normal with the pattern's covariance (areas {:.0} and {:.0} yd²); the crosses are the \
         means. Seen from above, carry up the page, offline across, both in yards to one scale.",
        100.0 * confidence,
        w.base.metrics.ellipse_area_yd2,
        w.changed.metrics.ellipse_area_yd2
    );
    figure("landing", &svg, &caption)
}

/// The head from above and from behind.
fn head_figures(w: &WhatIf, change: &HeadChange) -> [String; 2] {
    let mm = |v: nalgebra::Vector3<f64>| [v.x / M_PER_MM, v.y / M_PER_MM, v.z / M_PER_MM];
    let h = HeadPoints {
        com_before_mm: mm(w.base_params.club_com_m),
        com_after_mm: mm(w.changed_params.club_com_m),
        hosel_mm: mm(w.base_params.hosel_m),
        mass: change.mass_move.map(|m| MovedMass {
            mass_g: m.mass_g,
            from_mm: m.from_mm,
            to_mm: m.to_mm,
        }),
    };
    let caption = "The face frame to scale, mm from the face centre: the CoM before (blue) and \
                   after (orange), the moved mass where it was (hollow) and where it goes \
                   (filled), and the hosel. A CoM shift too short to see is drawn again, \
                   magnified by the factor written beside it.";
    [View::Above, View::Behind].map(|v| figure("head", &head_view_svg(&h, v), caption))
}

/// The face map of the carry change, the mishit pattern's centre marked.
fn carry_change_figure(m: &CarryChangeMap, centre_mm: [f64; 2]) -> String {
    let values: Vec<f64> = m.d_carry_yd.iter().map(|d| d.unwrap_or(f64::NAN)).collect();
    let svg = heatmap_svg(&Heatmap {
        title: "Carry change over the face (changed − base)",
        x_label: "impact z (toward the toe), mm",
        y_label: "impact y (up), mm",
        value_label: "carry change, yd",
        xs: &m.zs_mm,
        ys: &m.ys_mm,
        values: &values,
        marker: Some((centre_mm[1], centre_mm[0])),
        scale: Scale::Diverging,
    });
    figure(
        "face",
        &svg,
        "The face seen from the front, each cell the carry change of an impact there at the \
         golfer's central swing (red: the changed head carries farther, blue: shorter); the \
         circle marks the centre of the mishit pattern, the map spans ± 2.5 σ of it.",
    )
}

/// The comparison table: quantity, base, changed, change ± the quadrature's error estimate.
fn table_html(w: &WhatIf) -> String {
    let mut h = String::from(
        "<table><tr><th class=\"l\">quantity</th><th>base</th><th>changed</th>\
         <th>change ± quadrature error</th></tr>\n",
    );
    for q in &QUANTITIES {
        let n = decimals(q);
        let (d, u) = delta(q, &w.base, &w.changed);
        let _ = writeln!(
            h,
            "<tr><td class=\"l\">{} ({})</td><td>{:.n$}</td><td>{:.n$}</td><td>{}</td></tr>",
            esc(q.label),
            esc(q.unit),
            (q.get)(&w.base.metrics),
            (q.get)(&w.changed.metrics),
            esc(&delta_text(d, u, n))
        );
    }
    h.push_str("</table>\n");
    h
}

/// The one-page report: what was asked, the pictures, the table and the heads in numbers.
/// `map` is the carry change over the face and the mishit pattern's centre `[y, z]`, mm (its
/// figure is left out when it could not be computed).
fn page(
    club: &str,
    change: &HeadChange,
    setting: &str,
    w: &WhatIf,
    map: Option<(&CarryChangeMap, [f64; 2])>,
) -> String {
    let title = format!("What if: {}", change.describe().join("; "));
    let mut h = format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\
         <link rel=\"icon\" href=\"data:,\"><title>{t}</title><style>{CSS}</style></head><body>\n\
         <h1>{t}</h1>\n<p class=\"sub\">Base club: {}.</p>\n<p class=\"sub\">{}.</p>\n",
        esc(club),
        esc(setting),
        t = esc(&title)
    );
    let face = map.map_or(String::new(), |(m, c)| carry_change_figure(m, c));
    let _ = writeln!(
        h,
        "<section><h2>Where the balls go</h2>\n<div class=\"grid\">\n{}\n{face}\n</div></section>",
        landing_figure(w)
    );
    let [above, behind] = head_figures(w, change);
    let _ = writeln!(
        h,
        "<section><h2>The head</h2>\n<div class=\"grid\">\n{above}\n{behind}\n</div></section>"
    );
    let _ = writeln!(
        h,
        "<section><h2>In numbers</h2>\n{}<pre>{}</pre>\n<p>Both heads fly the same swings and \
         impacts; the quadrature error is the change's difference from the one computed with \
         one node fewer per dimension.</p></section>\n</body></html>",
        table_html(w),
        esc(&head_text(w))
    );
    h
}
