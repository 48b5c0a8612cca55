//! The `smash flight --report` page, from its [`FlightReport`]: the flight model against
//! measured flights, per club.

use super::{esc, Figure, Page, Section};
use crate::data::flight_summary::{FlightSummary, SUMMARY_QUANTITIES};
use crate::report::charts::{
    grouped_bars_svg, scatter_trend_svg, Bar, BarSeries, ChartError, BLUE_C,
};
use crate::report::flight::FlightReport;

/// The `--report` page: the carry, side, apex and land-angle errors per club (mean ± its
/// standard error, the shots' SD as a band) and every shot's carry error against its measured
/// carry, under the model and conditions flown.
pub fn flight_page(r: &FlightReport) -> Result<String, ChartError> {
    let summary = &r.errors;
    let categories: Vec<String> = summary.rows.iter().map(|r| r.group.clone()).collect();
    let mut figures = Vec::new();
    for (name, label, unit) in SUMMARY_QUANTITIES {
        let values: Vec<Option<Bar>> = summary
            .rows
            .iter()
            .map(|r| {
                r.errors.iter().find(|e| e.0 == name).map(|e| {
                    // The errors' SD from their RMSE and mean: rmse² = bias² + sd²·(n−1)/n.
                    let n = e.1.n as f64;
                    let sd = if e.1.n > 1 {
                        ((e.1.rmse.powi(2) - e.1.bias.powi(2)).max(0.0) * n / (n - 1.0)).sqrt()
                    } else {
                        0.0
                    };
                    Bar::of(e.1.bias, sd, e.1.n)
                })
            })
            .collect();
        if values.iter().all(Option::is_none) {
            continue;
        }
        let series = [BarSeries {
            label: "bias".into(),
            colour: BLUE_C,
            values,
        }];
        let svg = grouped_bars_svg(
            &format!("{label} error per club"),
            &format!("predicted - measured, {unit}"),
            &categories,
            &series,
        )?;
        figures.push(Figure {
            kind: "flight-bias",
            caption: format!(
                "{label}: mean error per club and over all shots (bar) ± its standard error (black); \
                 the grey band is ± one standard deviation of the shots, {unit}"
            ),
            svg,
        });
    }
    if !summary.carry_points.is_empty() {
        let svg = scatter_trend_svg(
            "carry error against measured carry",
            "measured carry, yd",
            "predicted - measured, yd",
            &summary.carry_points,
            None,
            &[],
        )?;
        figures.push(Figure {
            kind: "flight-carry",
            caption: "every shot's carry error against its measured carry".into(),
            svg,
        });
    }
    // What the run warned about (rows left out, modelled flights compared), before the table.
    let mut html: Vec<String> = r
        .warnings
        .iter()
        .map(|w| format!("<p><b>Note:</b> {}</p>", esc(w)))
        .collect();
    html.push(table_html(summary));
    Ok(Page {
        title: "Flight against measured flights".into(),
        subtitle: r.flown.clone(),
        sections: vec![Section {
            heading: "Flight against measured flights".into(),
            html,
            figures,
        }],
    }
    .render())
}

/// The carry statistics as an HTML table.
fn table_html(summary: &FlightSummary) -> String {
    let mut t = String::from(
        "<table><tr><th class=\"l\">club</th><th>n</th><th>carry bias yd</th><th>carry RMSE yd</th>\
         <th>median |err| %</th><th>P90 |err| %</th></tr>",
    );
    for r in &summary.rows {
        let Some((_, s)) = r.errors.iter().find(|e| e.0 == "carry_yd") else {
            continue;
        };
        let pct = |x: Option<f64>| x.map_or(String::new(), |v| format!("{v:.2}"));
        t.push_str(&format!(
            "<tr><td class=\"l\">{}</td><td>{}</td><td>{:.2}</td><td>{:.2}</td><td>{}</td><td>{}</td></tr>",
            esc(&r.group),
            s.n,
            s.bias,
            s.rmse,
            pct(s.median_abs_pct),
            pct(s.p90_abs_pct)
        ));
    }
    t.push_str("</table>");
    t
}
