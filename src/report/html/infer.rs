//! The `smash infer-club --report` page: the prior and the rule, the estimates with their
//! standard errors, prior shares and profile intervals, what the shots determine before and
//! after fitting, the face map of the inferred COR and the uncertainty ellipses of the
//! correlated pairs.

use std::fmt::Write as _;

use super::{esc, Figure, Page, Section};
use crate::infer::report::fmt_num;
use crate::infer::Report;
use crate::physics::laws::{Restitution, COR_REFERENCE_SPEED_M_S};
use crate::report::heatmap::{heatmap_svg, Heatmap, Scale};

/// Correlation beyond which a pair gets an ellipse.
const ELLIPSE_MIN_CORRELATION: f64 = 0.5;

/// Most ellipses drawn (the strongest correlations).
const MAX_ELLIPSES: usize = 8;

/// Cells of the COR face map along each axis.
const FACE_CELLS: usize = 41;

/// Half-width of the COR face map per axis, in SDs of the session's impact locations (about
/// every shot inside), and its smallest half-width, mm.
const FACE_HALF_WIDTH_SD: f64 = 2.5;
const FACE_MIN_HALF_WIDTH_MM: f64 = 10.0;

/// The inferred club's COR over the face (the model's restitution law, `physics::laws`, at its
/// reference approach speed, where the speed terms vanish), centred on the face centre and
/// spanning the session's impact locations.
fn cor_face_map(r: &Report) -> Figure {
    let law = Restitution::of(&r.club.params_for_group("all"));
    let axis = |sd_mm: f64| -> Vec<f64> {
        let half_mm = (FACE_HALF_WIDTH_SD * sd_mm).max(FACE_MIN_HALF_WIDTH_MM);
        (0..FACE_CELLS)
            .map(|i| -half_mm + 2.0 * half_mm * i as f64 / (FACE_CELLS - 1) as f64)
            .collect()
    };
    let (ys_mm, zs_mm) = (axis(r.impact_spread_mm[0]), axis(r.impact_spread_mm[1]));
    let values: Vec<f64> = ys_mm
        .iter()
        .flat_map(|&y_mm| {
            zs_mm
                .iter()
                .map(move |&z_mm| law.cor(COR_REFERENCE_SPEED_M_S, y_mm * 1e-3, z_mm * 1e-3))
        })
        .collect();
    let svg = heatmap_svg(&Heatmap {
        title: "inferred COR over the face",
        x_label: "impact z (toward toe), mm",
        y_label: "impact y (up), mm",
        value_label: "COR",
        xs: &zs_mm,
        ys: &ys_mm,
        values: &values,
        marker: Some((0.0, 0.0)),
        scale: Scale::Sequential,
    });
    let cor = |key: &str| r.params.iter().find(|p| p.name == key);
    let words = match (cor("cor"), cor("cor_radial.c_per_mm2")) {
        (Some(c), Some(f)) => format!(
            " (COR {} ± {} at the centre, falling by {} ± {} per mm² of squared distance)",
            fmt_num(c.value),
            fmt_num(c.stderr),
            fmt_num(f.value),
            fmt_num(f.stderr)
        ),
        _ => String::new(),
    };
    Figure {
        kind: "face",
        caption: format!(
            "The inferred head's COR over the face at the model's reference approach speed \
             ({COR_REFERENCE_SPEED_M_S} m/s){words}, over {FACE_HALF_WIDTH_SD} SDs of the \
             session's impact locations each way; + marks the face centre."
        ),
        svg,
    }
}

fn estimates_table(r: &Report) -> String {
    let mut s = String::from(
        "<table><tr><th class=\"l\">parameter</th><th>value</th><th>SE</th><th>start</th>\
         <th>prior SD</th><th>data SE</th><th>prior share</th><th>determined</th>\
         <th>profile (Δχ² = 1)</th></tr>",
    );
    for p in &r.params {
        let prof = p.profile.map_or("–".to_owned(), |[a, b]| {
            format!("[{}, {}]", fmt_num(a), fmt_num(b))
        });
        let _ = write!(
            s,
            "<tr><td class=\"l\">{} <span class=\"sub\">({}, {})</span></td><td>{}</td><td>{}</td>\
             <td>{}</td><td>{}</td><td>{}</td><td>{:.1} %</td><td>{}</td><td>{}</td></tr>",
            esc(&p.name),
            esc(p.words),
            esc(p.unit),
            fmt_num(p.value),
            fmt_num(p.stderr),
            fmt_num(p.start),
            fmt_num(p.prior_sd),
            p.data_stderr.map_or("–".to_owned(), fmt_num),
            100.0 * p.prior_share,
            if p.determined { "yes" } else { "<b>no</b>" },
            prof
        );
    }
    s.push_str("</table>");
    s
}

fn ident_html(id: &crate::infer::ident::Identifiability) -> String {
    let list = |v: &[String]| {
        if v.is_empty() {
            "none".to_owned()
        } else {
            esc(&v.join(", "))
        }
    };
    let mut s = format!(
        "<p>Determined: {}.<br>Not determined: {}.</p>",
        list(&id.determined_params),
        list(&id.undetermined_params)
    );
    let weak: Vec<&String> = id
        .directions
        .iter()
        .filter(|d| d.weak)
        .map(|d| &d.text)
        .collect();
    if !weak.is_empty() {
        s.push_str("<ul>");
        for w in weak {
            let _ = write!(s, "<li>{}</li>", esc(w));
        }
        s.push_str("</ul>");
    }
    s
}

/// The 1- and 2-SE ellipses of parameters `a` and `b` with correlation `rho`, in axes of their
/// own standard errors (so an uncorrelated pair is a circle).
fn ellipse_svg(r: &Report, a: usize, b: usize, rho: f64) -> String {
    let (w, h, m) = (360.0, 300.0, 48.0);
    let span = 2.6;
    let x = |u: f64| m + (u + span) / (2.0 * span) * (w - 2.0 * m);
    let y = |v: f64| h - m - (v + span) / (2.0 * span) * (h - 2.0 * m);
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {w} {h}\" font-size=\"12\">\
         <rect x=\"{m}\" y=\"{m}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#999\"/>",
        w - 2.0 * m,
        h - 2.0 * m
    );
    let root = (1.0 - rho * rho).max(0.0).sqrt();
    for (k, colour) in [(1.0, "#1f5fa8"), (2.0, "#7fa7d6")] {
        let mut d = String::new();
        for i in 0..=72 {
            let t = std::f64::consts::TAU * f64::from(i) / 72.0;
            let (u, v) = (k * t.cos(), k * (rho * t.cos() + root * t.sin()));
            let _ = write!(
                d,
                "{}{:.2},{:.2}",
                if i == 0 { "M" } else { "L" },
                x(u),
                y(v)
            );
        }
        let _ = write!(
            s,
            "<path d=\"{d}Z\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"2\"/>"
        );
    }
    let (pa, pb) = (&r.params[a], &r.params[b]);
    let _ = write!(
        s,
        "<circle cx=\"{:.2}\" cy=\"{:.2}\" r=\"3\" fill=\"#222\"/>\
         <text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{} ({}): {} ± {}</text>\
         <text x=\"14\" y=\"{:.1}\" text-anchor=\"middle\" transform=\"rotate(-90 14 {:.1})\">{} ({}): {} ± {}</text>\
         <text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">r = {:.2}</text></svg>",
        x(0.0),
        y(0.0),
        w / 2.0,
        h - 14.0,
        esc(&pa.name),
        esc(pa.unit),
        fmt_num(pa.value),
        fmt_num(pa.stderr),
        h / 2.0,
        h / 2.0,
        esc(&pb.name),
        esc(pb.unit),
        fmt_num(pb.value),
        fmt_num(pb.stderr),
        w / 2.0,
        m - 12.0,
        rho
    );
    s
}

fn ellipses(r: &Report) -> Vec<Figure> {
    let n = r.params.len();
    let mut pairs: Vec<(usize, usize, f64)> = (0..n)
        .flat_map(|a| (a + 1..n).map(move |b| (a, b)))
        .map(|(a, b)| (a, b, r.correlation[a][b]))
        .filter(|(_, _, rho)| rho.abs() >= ELLIPSE_MIN_CORRELATION)
        .collect();
    pairs.sort_by(|p, q| q.2.abs().total_cmp(&p.2.abs()));
    pairs.truncate(MAX_ELLIPSES);
    pairs
        .into_iter()
        .map(|(a, b, rho)| Figure {
            kind: "ellipse",
            caption: format!(
                "{} against {}: 1- and 2-SE ellipses, each axis in its own SE (correlation {:.2})",
                r.params[a].name, r.params[b].name, rho
            ),
            svg: ellipse_svg(r, a, b, rho),
        })
        .collect()
}

/// The page of an infer-club report.
pub fn infer_page(r: &Report, title: &str) -> String {
    let mut sections = vec![
        Section {
            heading: "Prior and rule".into(),
            html: vec![
                format!("<p>Prior: {}.</p>", esc(&r.prior)),
                format!("<p>{}.</p>", esc(&r.determined_rule)),
            ],
            figures: vec![],
        },
        Section {
            heading: "Before fitting: the start head, the instruments' noise".into(),
            html: vec![ident_html(&r.before)],
            figures: vec![],
        },
        Section {
            heading: "Estimates".into(),
            html: vec![estimates_table(r), ident_html(&r.after)],
            figures: vec![],
        },
    ];
    sections.push(Section {
        heading: "The inferred COR over the face".into(),
        html: vec![],
        figures: vec![cor_face_map(r)],
    });
    let figures = ellipses(r);
    sections.push(Section {
        heading: "Correlated pairs".into(),
        html: vec![if figures.is_empty() {
            format!(
                "<p>No two estimates are correlated beyond |r| = {ELLIPSE_MIN_CORRELATION}.</p>"
            )
        } else {
            format!(
                "<p>Pairs correlated beyond |r| = {ELLIPSE_MIN_CORRELATION}, strongest first: \
                 the shots determine the direction along an ellipse's long axis least.</p>"
            )
        }],
        figures,
    });
    Page {
        title: title.to_owned(),
        subtitle: format!(
            "{} shots; impact spread {:.1} mm up, {:.1} mm heel-toe (SD); χ² data {:.1} over {} rows",
            r.n_shots, r.impact_spread_mm[0], r.impact_spread_mm[1], r.chi2_data, r.n_residuals
        ),
        sections,
    }
    .render()
}
