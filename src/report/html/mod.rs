//! Self-contained HTML reports (`--report FILE.html`): one page with inline SVG charts and CSS,
//! no scripts, fonts or anything else fetched; readable offline and printable. Built from the
//! same typed report values the JSON serialises (`crate::report::{diagnose, calibrate, flight}`);
//! never from the JSON. Builds strings only.

mod diagnose;
mod figures;
mod flight;
mod infer;
mod pages;

use std::fmt::Write as _;

use crate::compare::VARIABLES;
use crate::physics::LaunchComponent;

pub use diagnose::diagnose_page;
pub use flight::flight_page;
pub use infer::infer_page;
pub use pages::{calibrate_page, compare_page};

/// Escape text for HTML.
pub fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// One chart with its caption.
#[derive(Debug, Clone)]
pub struct Figure {
    /// Kind, for tests and styling (`table2`, `trend`, `face`, `estimates`, …).
    pub kind: &'static str,
    /// Caption (text).
    pub caption: String,
    /// The SVG.
    pub svg: String,
}

/// A section of a page.
#[derive(Debug, Clone, Default)]
pub struct Section {
    /// Heading.
    pub heading: String,
    /// Paragraphs of HTML (already escaped).
    pub html: Vec<String>,
    /// Charts.
    pub figures: Vec<Figure>,
}

/// A whole report page.
#[derive(Debug, Clone, Default)]
pub struct Page {
    /// Title.
    pub title: String,
    /// One line under the title.
    pub subtitle: String,
    /// Sections in order.
    pub sections: Vec<Section>,
}

/// The pages' style (shared with the study page of `crate::study::report`).
pub const CSS: &str = "body{font-family:sans-serif;color:#222;margin:0 auto;max-width:1240px;padding:16px 24px;line-height:1.4}\
h1{font-size:1.5em;margin:.2em 0}h2{font-size:1.2em;border-bottom:1px solid #ccc;margin-top:1.6em}\
.sub{color:#555}.grid{display:grid;grid-template-columns:repeat(auto-fill,minmax(480px,1fr));gap:12px}\
figure{margin:0;border:1px solid #e4e4e4;padding:6px;background:#fff}figure svg{width:100%;height:auto;display:block}\
figcaption{font-size:.85em;color:#444;margin-top:4px}\
table{border-collapse:collapse;font-size:.9em;margin:.6em 0}td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}\
th{background:#f3f3f3}td.l,th.l{text-align:left}.sig{font-weight:bold}ol li{margin:.3em 0}\
@media print{body{max-width:none;padding:0}.grid{grid-template-columns:1fr}figure,table{break-inside:avoid}h2{break-after:avoid}}";

impl Page {
    /// The HTML document.
    pub fn render(&self) -> String {
        let mut s = String::new();
        let _ = write!(
            s,
            "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
             <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\
             <link rel=\"icon\" href=\"data:,\"><title>{}</title><style>{CSS}</style></head><body>\n",
            esc(&self.title)
        );
        let _ = writeln!(
            s,
            "<h1>{}</h1><p class=\"sub\">{}</p>",
            esc(&self.title),
            esc(&self.subtitle)
        );
        for sec in &self.sections {
            let _ = writeln!(s, "<section><h2>{}</h2>", esc(&sec.heading));
            for h in &sec.html {
                s.push_str(h);
                s.push('\n');
            }
            if !sec.figures.is_empty() {
                s.push_str("<div class=\"grid\">\n");
                for f in &sec.figures {
                    let _ = writeln!(
                        s,
                        "<figure class=\"chart\" data-kind=\"{}\">{}<figcaption>{}</figcaption></figure>",
                        f.kind,
                        f.svg,
                        esc(&f.caption)
                    );
                }
                s.push_str("</div>\n");
            }
            s.push_str("</section>\n");
        }
        let _ = writeln!(
            s,
            "<p class=\"sub\">Written by smash {}. Errors are model − measured.</p></body></html>",
            env!("CARGO_PKG_VERSION")
        );
        s
    }
}

/// Per-shot residuals against the delivery, for the trend charts.
#[derive(Debug, Clone)]
pub struct ShotResiduals {
    /// Delivery variable name (a [`VARIABLES`] name) → value per shot, file units.
    pub variables: Vec<(&'static str, &'static str, Vec<f64>)>,
    /// Model − measured per shot, file units, launch component order.
    pub errors: Vec<[f64; 5]>,
}

/// Variables the trend charts show: speed, loft and the two impact coordinates.
pub const TREND_VARIABLES: [&str; 4] = [
    "club_speed_mph",
    "dynamic_loft_deg",
    "impact_y_mm",
    "impact_z_mm",
];

impl ShotResiduals {
    /// From shots and their expected launches (same order).
    pub fn new(shots: &[crate::model::Shot], launches: &[crate::physics::Launch]) -> Self {
        let variables = VARIABLES
            .iter()
            .filter(|v| TREND_VARIABLES.contains(&v.name()))
            .map(|v| (v.name(), v.unit(), shots.iter().map(|s| v.get(s)).collect()))
            .collect();
        let errors = shots
            .iter()
            .zip(launches)
            .map(|(s, l)| {
                let m = s.measured.expect("compared shots are measured");
                std::array::from_fn(|c| {
                    let c = LaunchComponent::ALL[c];
                    l.get_file(c) - m.get_file(c)
                })
            })
            .collect();
        Self { variables, errors }
    }
}
