//! The `[distribution]` table: Gaussian scatter of swings and impact locations.

use serde::{Deserialize, Serialize};
use toml::Spanned;

use super::defaults;
use crate::data::toml_check::did_you_mean;
use crate::data::{DataError, TomlDoc};
use crate::limits::{self, count_product};
use crate::study::distribution::{Distribution, Method};

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawDistribution {
    pub method: Option<Spanned<String>>,
    pub nodes: Option<Spanned<i64>>,
    pub samples: Option<Spanned<i64>>,
    pub seed: Option<Spanned<i64>>,
    #[serde(default, deserialize_with = "crate::data::toml_check::exact_opt")]
    pub impact_centre_mm: Option<Spanned<[f64; 2]>>,
    pub sigma_y_mm: Option<Spanned<f64>>,
    pub sigma_z_mm: Option<Spanned<f64>>,
    pub sigma_club_speed_mph: Option<Spanned<f64>>,
    pub sigma_attack_angle_deg: Option<Spanned<f64>>,
    pub sigma_club_path_deg: Option<Spanned<f64>>,
    pub sigma_dynamic_loft_deg: Option<Spanned<f64>>,
    pub sigma_face_angle_deg: Option<Spanned<f64>>,
}

fn parse_method(doc: &TomlDoc<'_>, r: &RawDistribution) -> Result<Method, DataError> {
    let name = r
        .method
        .as_ref()
        .map_or("quadrature", |m| m.get_ref().as_str());
    let method = match name {
        "quadrature" => {
            if let Some(s) = &r.samples {
                return Err(doc.err(
                    s.span(),
                    "distribution.samples",
                    "goes with method = \"samples\"; quadrature uses `nodes`",
                ));
            }
            Method::Quadrature {
                nodes: r.nodes.as_ref().map_or(Ok(defaults::NODES), |n| {
                    doc.count(n, "distribution.nodes", (1, 20))
                })?,
            }
        }
        "samples" => {
            if let Some(n) = &r.nodes {
                return Err(doc.err(
                    n.span(),
                    "distribution.nodes",
                    "goes with method = \"quadrature\"; samples uses `samples` and `seed`",
                ));
            }
            Method::Samples {
                samples: r.samples.as_ref().map_or(Ok(defaults::SAMPLES), |n| {
                    doc.count(n, "distribution.samples", (1, 1_000_000))
                })?,
                seed: r.seed.as_ref().map_or(Ok(defaults::SEED), |s| {
                    doc.count(s, "distribution.seed", (0, i64::MAX))
                        .map(|x| x as u64)
                })?,
            }
        }
        other => {
            let hint = did_you_mean(other, ["quadrature", "samples"].into_iter())
                .map_or_else(String::new, |m| format!(" (did you mean '{m}'?)"));
            return Err(doc.err(
                r.method.as_ref().map_or(0..0, |m| m.span()),
                "distribution.method",
                format!(
                    "unknown method '{}'{hint}; allowed: quadrature (Gauss–Hermite, \
                     deterministic), samples (fixed seed)",
                    crate::data::escape(other)
                ),
            ));
        }
    };
    if let (Method::Quadrature { .. }, Some(s)) = (&method, &r.seed) {
        return Err(doc.err(
            s.span(),
            "distribution.seed",
            "goes with method = \"samples\"",
        ));
    }
    Ok(method)
}

pub(super) fn parse_distribution(
    doc: &TomlDoc<'_>,
    sd: &Spanned<RawDistribution>,
) -> Result<Distribution, DataError> {
    let r = sd.get_ref();
    let method = parse_method(doc, r)?;
    let impact_centre_mm = match &r.impact_centre_mm {
        None => [0.0, 0.0],
        Some(c) => doc.each_ranged(
            c,
            "distribution.impact_centre_mm",
            limits::IMPACT_LOCATION_MM,
        )?,
    };
    let sigma = |v: &Option<Spanned<f64>>, key: &str, range| doc.opt_ranged(v, key, range, 0.0);
    let dist = Distribution {
        method,
        impact_centre_mm,
        sigma_y_mm: sigma(
            &r.sigma_y_mm,
            "distribution.sigma_y_mm",
            limits::SIGMA_LOCATION_MM,
        )?,
        sigma_z_mm: sigma(
            &r.sigma_z_mm,
            "distribution.sigma_z_mm",
            limits::SIGMA_LOCATION_MM,
        )?,
        sigma_club_speed_mph: sigma(
            &r.sigma_club_speed_mph,
            "distribution.sigma_club_speed_mph",
            limits::SIGMA_CLUB_SPEED_MPH,
        )?,
        sigma_attack_angle_deg: sigma(
            &r.sigma_attack_angle_deg,
            "distribution.sigma_attack_angle_deg",
            limits::SIGMA_ANGLE_DEG,
        )?,
        sigma_club_path_deg: sigma(
            &r.sigma_club_path_deg,
            "distribution.sigma_club_path_deg",
            limits::SIGMA_ANGLE_DEG,
        )?,
        sigma_dynamic_loft_deg: sigma(
            &r.sigma_dynamic_loft_deg,
            "distribution.sigma_dynamic_loft_deg",
            limits::SIGMA_ANGLE_DEG,
        )?,
        sigma_face_angle_deg: sigma(
            &r.sigma_face_angle_deg,
            "distribution.sigma_face_angle_deg",
            limits::SIGMA_ANGLE_DEG,
        )?,
    };
    if let Method::Quadrature { nodes } = dist.method {
        let dims: Vec<(&str, usize)> = sigmas(&dist)
            .into_iter()
            .filter(|(_, s)| *s > 0.0)
            .map(|(k, _)| (k, nodes))
            .collect();
        count_product(
            "quadrature points (nodes for each σ > 0)",
            &dims,
            defaults::MAX_QUADRATURE_POINTS,
            "use fewer nodes or method = \"samples\"",
        )
        .map_err(|e| doc.err(sd.span(), "distribution", e.to_string()))?;
    }
    Ok(dist)
}

fn sigmas(d: &Distribution) -> [(&'static str, f64); 7] {
    [
        ("sigma_y_mm", d.sigma_y_mm),
        ("sigma_z_mm", d.sigma_z_mm),
        ("sigma_club_speed_mph", d.sigma_club_speed_mph),
        ("sigma_attack_angle_deg", d.sigma_attack_angle_deg),
        ("sigma_club_path_deg", d.sigma_club_path_deg),
        ("sigma_dynamic_loft_deg", d.sigma_dynamic_loft_deg),
        ("sigma_face_angle_deg", d.sigma_face_angle_deg),
    ]
}

/// The distribution as a `[distribution]` table, every default written out.
pub(super) fn raw_distribution(d: &Distribution) -> RawDistribution {
    let s = |x: f64| Some(Spanned::new(0..0, x));
    let i = |x: usize| Some(Spanned::new(0..0, x as i64));
    let (method, nodes, samples, seed) = match d.method {
        Method::Quadrature { nodes } => ("quadrature", i(nodes), None, None),
        Method::Samples { samples, seed } => (
            "samples",
            None,
            i(samples),
            Some(Spanned::new(0..0, seed as i64)),
        ),
    };
    RawDistribution {
        method: Some(Spanned::new(0..0, method.to_owned())),
        nodes,
        samples,
        seed,
        impact_centre_mm: Some(Spanned::new(0..0, d.impact_centre_mm)),
        sigma_y_mm: s(d.sigma_y_mm),
        sigma_z_mm: s(d.sigma_z_mm),
        sigma_club_speed_mph: s(d.sigma_club_speed_mph),
        sigma_attack_angle_deg: s(d.sigma_attack_angle_deg),
        sigma_club_path_deg: s(d.sigma_club_path_deg),
        sigma_dynamic_loft_deg: s(d.sigma_dynamic_loft_deg),
        sigma_face_angle_deg: s(d.sigma_face_angle_deg),
    }
}
