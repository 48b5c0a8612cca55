//! Yards per design, against the base: the robust yard metrics of every head a study (or a
//! what-if) asks about, each beside the base head's and as a change from it, with the
//! quadrature's own error estimate where the distribution is a quadrature.
//!
//! The error estimate: the same metrics computed with the lower-order companion rule (one node
//! fewer per scattered dimension); the uncertainty of a change `Δ` is `|Δₙ − Δₙ₋₁|`, the usual
//! embedded-rule estimate (conservative for the `n`-node rule, which is the more accurate of the
//! two). Sampled distributions have no such estimate (their rows leave it empty), and neither
//! has a one-node rule.
//!
//! Pure: no I/O.

use std::fmt::Write as _;

use super::distribution::{Distribution, Method, SwingSpec};
use super::landing::Landing;
use super::output::cell;
use super::yards::{yard_landing, yard_metrics, YardMetrics, YardsError};
use crate::flight::FlightConfig;
use crate::physics::{ImpactModel, ModelParams};

/// The yard metrics of one head, and those of the companion rule when there is one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeadYards {
    /// Metrics over the distribution as given.
    pub metrics: YardMetrics,
    /// Metrics over the companion quadrature (one node fewer per dimension), when it exists
    /// and every impact of it is on the face.
    pub companion: Option<YardMetrics>,
}

/// The lower-order companion of a quadrature (`None` for samples or a one-node rule).
pub fn companion(dist: &Distribution) -> Option<Distribution> {
    match dist.method {
        Method::Quadrature { nodes } if nodes >= 2 => Some(Distribution {
            method: Method::Quadrature { nodes: nodes - 1 },
            ..*dist
        }),
        _ => None,
    }
}

/// Everything a head's yard metrics are computed with besides the head.
#[derive(Debug, Clone, Copy)]
pub struct YardSetting<'a> {
    /// The swing at the centre of the distribution.
    pub swing: &'a SwingSpec,
    /// Swings and impacts.
    pub dist: &'a Distribution,
    /// Ball flight.
    pub flight: &'a FlightConfig,
    /// Confidence level of the dispersion ellipse.
    pub confidence: f64,
}

/// The yard metrics of the head `p` (and of the companion rule).
pub fn head_yards(p: &ModelParams, s: &YardSetting<'_>) -> Result<HeadYards, YardsError> {
    head_landing(p, s).map(|(h, _)| h)
}

/// [`head_yards`] and the landing pattern of the distribution as given.
pub fn head_landing(
    p: &ModelParams,
    s: &YardSetting<'_>,
) -> Result<(HeadYards, Landing), YardsError> {
    let model = ImpactModel::new(p.clone())?;
    let (metrics, landing) = yard_landing(&model, s.swing, s.dist, s.flight, s.confidence)?;
    let companion = companion(s.dist)
        .and_then(|d| yard_metrics(&model, s.swing, &d, s.flight, s.confidence).ok());
    Ok((HeadYards { metrics, companion }, landing))
}

/// One row of the comparison: a head and what it is.
#[derive(Debug, Clone, PartialEq)]
pub struct YardRow {
    /// The design variant's id in the study's `variants.csv` (and `maps/v<id>_…`), for a row
    /// that is one of the `[design]` variants; `None` for the base, an optimum or a what-if.
    pub variant_id: Option<usize>,
    /// Short name: `base`, `variant 3`, `optimum ([yards.optimise])`, `what-if`.
    pub label: String,
    /// The design's values (`key = value, …`), or `base`.
    pub design: String,
    /// Its metrics.
    pub head: HeadYards,
}

/// A compared quantity: column name, unit for text, and how to read it.
pub struct Quantity {
    /// Column name (with its unit).
    pub column: &'static str,
    /// Name for text.
    pub label: &'static str,
    /// Unit for text.
    pub unit: &'static str,
    /// Its value.
    pub get: fn(&YardMetrics) -> f64,
}

/// The compared quantities, in table order.
pub const QUANTITIES: [Quantity; 8] = [
    Quantity {
        column: "mean_carry_yd",
        label: "mean carry",
        unit: "yd",
        get: |m| m.mean_carry_yd,
    },
    Quantity {
        column: "std_carry_yd",
        label: "carry spread (sd)",
        unit: "yd",
        get: |m| m.std_carry_yd,
    },
    Quantity {
        column: "ellipse_area_yd2",
        label: "dispersion-ellipse area",
        unit: "yd²",
        get: |m| m.ellipse_area_yd2,
    },
    Quantity {
        column: "mean_offline_yd",
        label: "mean offline (+ right)",
        unit: "yd",
        get: |m| m.mean_offline_yd,
    },
    Quantity {
        column: "std_offline_yd",
        label: "offline spread (sd)",
        unit: "yd",
        get: |m| m.std_offline_yd,
    },
    Quantity {
        column: "mean_ball_speed_mph",
        label: "mean ball speed",
        unit: "mph",
        get: |m| m.mean_ball_speed_mph,
    },
    Quantity {
        column: "mean_backspin_rpm",
        label: "mean backspin",
        unit: "rpm",
        get: |m| m.mean_backspin_rpm,
    },
    Quantity {
        column: "mean_sidespin_rpm",
        label: "mean sidespin (+ right)",
        unit: "rpm",
        get: |m| m.mean_sidespin_rpm,
    },
];

/// The change of `q` from `base` to `head`, and its quadrature uncertainty.
pub fn delta(q: &Quantity, base: &HeadYards, head: &HeadYards) -> (f64, Option<f64>) {
    let d = (q.get)(&head.metrics) - (q.get)(&base.metrics);
    let unc = match (&base.companion, &head.companion) {
        (Some(b), Some(h)) => Some((d - ((q.get)(h) - (q.get)(b))).abs()),
        _ => None,
    };
    (d, unc)
}

/// `yards/variants.csv`: one row per head (the base first), keyed by `variant_id` (the id of
/// the study's `variants.csv`, empty for the base, an optimum or a what-if, which are no
/// variant), each quantity, its change from the base and the change's quadrature uncertainty
/// (empty where there is none), the ellipse area's change in per cent, and the share of the
/// distribution's weight whose balls never left the ground (`grounded_pct`, counted with 0 yd
/// carry).
pub fn rows_csv(base: &HeadYards, rows: &[YardRow]) -> Vec<u8> {
    let mut t = String::from("variant_id,label,design");
    for q in &QUANTITIES {
        let _ = write!(t, ",{c},d_{c},d_{c}_unc", c = q.column);
    }
    t.push_str(",d_ellipse_area_pct,confidence,grounded_pct\n");
    for r in rows {
        let id = r.variant_id.map_or(String::new(), |i| i.to_string());
        let _ = write!(t, "{id},{},\"{}\"", r.label, r.design.replace('"', "'"));
        for q in &QUANTITIES {
            let (d, unc) = delta(q, base, &r.head);
            let _ = write!(
                t,
                ",{},{},{}",
                cell((q.get)(&r.head.metrics)),
                cell(d),
                unc.map_or(String::new(), cell)
            );
        }
        let area = base.metrics.ellipse_area_yd2;
        let pct = if area > 0.0 {
            cell(100.0 * (r.head.metrics.ellipse_area_yd2 - area) / area)
        } else {
            String::new()
        };
        let _ = writeln!(
            t,
            ",{pct},{},{}",
            cell(r.head.metrics.confidence),
            cell(100.0 * r.head.metrics.grounded_share)
        );
    }
    t.into_bytes()
}

/// `Δ ± u` in a fixed number of decimals (`± u` only where there is an uncertainty).
pub fn delta_text(d: f64, unc: Option<f64>, decimals: usize) -> String {
    match unc {
        Some(u) => format!("{d:+.decimals$} ± {u:.decimals$}"),
        None => format!("{d:+.decimals$}"),
    }
}

/// Decimals a quantity is shown with in text (yards to 0.01 yd, areas to 0.1 yd², speeds to
/// 0.01 mph, spins to 1 rpm).
pub fn decimals(q: &Quantity) -> usize {
    match q.unit {
        "yd" | "mph" => 2,
        "yd²" => 1,
        _ => 0,
    }
}

/// A text table for the terminal: the base's values, then per row the change of each quantity
/// (± the quadrature uncertainty), at most `max_rows` rows. Each column is as wide as its
/// widest cell; with `width`, the quantities are split into blocks of lines at most that wide
/// (the design names repeated in each), else all on one line.
pub fn rows_text(
    base: &HeadYards,
    rows: &[YardRow],
    max_rows: usize,
    width: Option<usize>,
) -> String {
    let name = |r: &YardRow| {
        if r.design == "base" || r.label.starts_with("optimum") {
            r.label.clone()
        } else {
            format!("{} ({})", r.label, r.design)
        }
    };
    let shown = &rows[..rows.len().min(max_rows)];
    let names: Vec<String> = shown.iter().map(name).collect();
    let name_w = names
        .iter()
        .map(|n| n.chars().count())
        .max()
        .unwrap_or(6)
        .max(6);
    // cells[q][row]
    let cells: Vec<Vec<String>> = QUANTITIES
        .iter()
        .map(|q| {
            shown
                .iter()
                .map(|r| {
                    if r.label == "base" {
                        format!("{:.*}", decimals(q), (q.get)(&r.head.metrics))
                    } else {
                        let (d, u) = delta(q, base, &r.head);
                        delta_text(d, u, decimals(q))
                    }
                })
                .collect()
        })
        .collect();
    let col_w: Vec<usize> = QUANTITIES
        .iter()
        .zip(&cells)
        .map(|(q, c)| {
            c.iter()
                .map(|s| s.chars().count())
                .chain([q.column.len()])
                .max()
                .unwrap_or(0)
        })
        .collect();
    // Blocks of quantities that fit `width` (at least one quantity each).
    let mut blocks: Vec<Vec<usize>> = vec![Vec::new()];
    let mut used = name_w;
    for (i, w) in col_w.iter().enumerate() {
        let block = blocks.last_mut().expect("a block");
        if width.is_some_and(|max| !block.is_empty() && used + 2 + w > max) {
            blocks.push(vec![i]);
            used = name_w + 2 + w;
        } else {
            block.push(i);
            used += 2 + w;
        }
    }
    let mut t = String::new();
    for (b, block) in blocks.iter().enumerate() {
        if b > 0 {
            t.push('\n');
        }
        let _ = write!(t, "{:<name_w$}", "design");
        for &i in block {
            let _ = write!(t, "  {:>w$}", QUANTITIES[i].column, w = col_w[i]);
        }
        t.push('\n');
        for (r, n) in names.iter().enumerate() {
            let _ = write!(t, "{n:<name_w$}");
            for &i in block {
                let _ = write!(t, "  {:>w$}", cells[i][r], w = col_w[i]);
            }
            t.push('\n');
        }
    }
    if rows.len() > max_rows {
        let _ = writeln!(
            t,
            "… {} more row(s): see yards/variants.csv",
            rows.len() - max_rows
        );
    }
    for (r, n) in shown.iter().zip(&names) {
        if let Some(note) = r.head.metrics.grounded_note() {
            let _ = writeln!(t, "{n}: {note}");
        }
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    fn metrics(carry: f64, area: f64) -> YardMetrics {
        YardMetrics {
            mean_carry_yd: carry,
            std_carry_yd: 1.0,
            mean_offline_yd: 0.0,
            std_offline_yd: 1.0,
            ellipse_area_yd2: area,
            confidence: 0.95,
            mean_ball_speed_mph: 140.0,
            mean_backspin_rpm: 2500.0,
            mean_sidespin_rpm: 0.0,
            impacts: 25,
            grounded: 0,
            grounded_share: 0.0,
        }
    }

    #[test]
    fn the_uncertainty_is_the_change_between_the_two_rules() {
        let base = HeadYards {
            metrics: metrics(200.0, 100.0),
            companion: Some(metrics(200.5, 90.0)),
        };
        let head = HeadYards {
            metrics: metrics(201.0, 110.0),
            companion: Some(metrics(201.2, 95.0)),
        };
        let (d, u) = delta(&QUANTITIES[0], &base, &head);
        assert!((d - 1.0).abs() < 1e-12);
        // Δ₅ = 1.0, Δ₄ = 0.7.
        assert!((u.unwrap() - 0.3).abs() < 1e-12);
        let (d, u) = delta(&QUANTITIES[2], &base, &head);
        assert!((d - 10.0).abs() < 1e-12 && (u.unwrap() - 5.0).abs() < 1e-12);
        let none = HeadYards {
            companion: None,
            ..head
        };
        assert_eq!(delta(&QUANTITIES[0], &base, &none).1, None);
        let csv = String::from_utf8(rows_csv(
            &base,
            &[
                YardRow {
                    variant_id: None,
                    label: "base".into(),
                    design: "base".into(),
                    head: base,
                },
                YardRow {
                    variant_id: Some(1),
                    label: "variant 1".into(),
                    design: "com_dz_mm = 4".into(),
                    head: none,
                },
            ],
        ))
        .unwrap();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines.len(), 3);
        assert!(lines[0].starts_with(
            "variant_id,label,design,mean_carry_yd,d_mean_carry_yd,d_mean_carry_yd_unc,"
        ));
        // The base row: no change, no uncertainty of it either way (its companion exists: 0).
        assert!(
            lines[1].starts_with(",base,\"base\",200,0,0,"),
            "{}",
            lines[1]
        );
        // A row without a companion has an empty uncertainty; the area grew by 10 %.
        assert!(
            lines[2].starts_with("1,variant 1,\"com_dz_mm = 4\",201,1,,"),
            "{}",
            lines[2]
        );
        assert!(lines[2].ends_with(",10,0.95,0"), "{}", lines[2]);
    }

    #[test]
    fn companion_of_a_quadrature_has_one_node_fewer() {
        let d = Distribution {
            method: Method::Quadrature { nodes: 5 },
            impact_centre_mm: [0.0, 0.0],
            sigma_y_mm: 4.0,
            sigma_z_mm: 8.0,
            sigma_club_speed_mph: 0.0,
            sigma_attack_angle_deg: 0.0,
            sigma_club_path_deg: 0.0,
            sigma_dynamic_loft_deg: 0.0,
            sigma_face_angle_deg: 0.0,
        };
        assert_eq!(
            companion(&d).unwrap().method,
            Method::Quadrature { nodes: 4 }
        );
        let one = Distribution {
            method: Method::Quadrature { nodes: 1 },
            ..d
        };
        assert!(companion(&one).is_none());
        let s = Distribution {
            method: Method::Samples {
                samples: 64,
                seed: 1,
            },
            ..d
        };
        assert!(companion(&s).is_none());
    }
}
