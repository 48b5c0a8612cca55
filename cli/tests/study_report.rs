//! The report of `smash run` as a meeting reads it: `--json` and `--report` from the same run of
//! a study with 18 variants (`com_sweep`), the page's structure checked against the JSON (the
//! same typed value): the summary first, one colour scale per set of small multiples, no
//! difference map of the base against itself, integer ids that match the legend, tables that
//! fit, no note on measurements. The browser renders it in `report.rs`.

use crate::cli_support;

use std::collections::BTreeSet;
use std::path::Path;

use serde_json::Value;

use cli_support::{s, smash_in_repo as smash};

/// `smash run STUDY --json --report`: (stdout JSON, page, stderr).
fn run(study: &str, dir: &Path) -> (Value, String, String) {
    let page = dir.join("study.html");
    let out = smash(&[
        "run",
        study,
        "--out",
        s(&dir.join("out")),
        "--report",
        s(&page),
        "--json",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "smash run failed: {stderr}");
    let json: Value = serde_json::from_slice(&out.stdout).expect("stdout is one JSON object");
    (json, std::fs::read_to_string(page).unwrap(), stderr)
}

/// The value of attribute `name` in every tag of `html` that starts with `start`.
fn attrs(html: &str, start: &str, name: &str) -> Vec<String> {
    html.match_indices(start)
        .map(|(i, _)| {
            let tag = &html[i..i + html[i..].find('>').unwrap()];
            let key = format!(" {name}=\"");
            let j = tag.find(&key).unwrap_or_else(|| panic!("{tag}: no {name}")) + key.len();
            tag[j..j + tag[j..].find('"').unwrap()].to_owned()
        })
        .collect()
}

/// The figures of one kind (`face`, `diff`) in `html`: (variant id as written, limits).
fn figures(html: &str, kind: &str) -> Vec<(String, String)> {
    let start = format!("<figure class=\"chart\" data-kind=\"{kind}\"");
    attrs(html, &start, "data-variant")
        .into_iter()
        .zip(attrs(html, &start, "data-limits"))
        .collect()
}

/// The finite numbers of a JSON array of arrays (null: no value).
fn finite(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .flat_map(|m| m.as_array().unwrap().iter().filter_map(Value::as_f64))
        .collect()
}

fn pair(v: &Value) -> (f64, f64) {
    (v[0].as_f64().unwrap(), v[1].as_f64().unwrap())
}

#[test]
fn the_study_page_is_read_at_a_meeting() {
    let dir = tempfile::tempdir().unwrap();
    let (json, html, _) = run("configs/studies/com_sweep.toml", dir.path());
    assert_eq!(json["schema_version"], 1);
    assert_eq!(json["command"], "run");
    let variants = json["variants"].as_array().unwrap();
    assert_eq!(variants.len(), 18);
    // The base is the variant that changes nothing (com_dx 0, com_dy 0, inertia scale 1).
    let base = json["base_id"].as_u64().unwrap() as usize;
    assert_eq!(base, 8);
    assert_eq!(variants[base]["changes"], "base");
    assert_eq!(json["base_is_club"], true);

    // The summary comes first, before any map.
    let first = html.find("<section").unwrap();
    assert!(html[first..].starts_with("<section id=\"summary\">"));
    assert!(html.find("data-kind=\"face\"").unwrap() > html.find("</section>").unwrap());
    assert!(html.contains(&format!("The base is variant {base}")));
    // A design study measures nothing: no note about measured values.
    assert!(
        !html.contains("measured"),
        "a measurement note on a design study"
    );

    // Integer ids, each variant once in the legend, each map's id in it.
    let legend = &html[html.find("<section id=\"variants\">").unwrap()..];
    let legend = &legend[..legend.find("</section>").unwrap()];
    let ids: Vec<String> = legend
        .match_indices("<tr><td class=\"l\">")
        .map(|(i, m)| {
            let rest = &legend[i + m.len()..];
            rest[..rest.find('<').unwrap()].to_owned()
        })
        .collect();
    let expected: Vec<String> = (0..18)
        .map(|i| match i == base {
            true => format!("{i} (base)"),
            false => i.to_string(),
        })
        .collect();
    assert_eq!(ids, expected);

    let maps = json["face_maps"].as_array().unwrap();
    assert_eq!(maps.len(), 4, "one set per output of the study");
    let sections: Vec<&str> = html.split("<section class=\"maps\"").skip(1).collect();
    assert_eq!(sections.len(), maps.len());
    for (m, sec) in maps.iter().zip(&sections) {
        let sec = &sec[..sec.find("</section>").unwrap()];
        let column = m["column"].as_str().unwrap();
        // One shared scale: the JSON's limits are the min and max of every map of the set
        // (symmetric for signed outputs), and every multiple of the page is drawn on them.
        let values = finite(&m["values"]);
        let (lo, hi) = pair(&m["limits"]);
        let (min, max) = values
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(*v), b.max(*v))
            });
        if m["signed"].as_bool().unwrap() {
            assert_eq!(
                (lo, hi),
                (-min.abs().max(max.abs()), min.abs().max(max.abs()))
            );
        } else {
            assert_eq!((lo, hi), (min, max), "{column}");
        }
        let face = figures(sec, "face");
        let shown: Vec<usize> = face.iter().map(|f| f.0.parse().unwrap()).collect();
        assert_eq!(shown, (0..18).collect::<Vec<_>>(), "{column}");
        let limits: BTreeSet<&String> = face.iter().map(|f| &f.1).collect();
        assert_eq!(
            limits.len(),
            1,
            "{column}: several colour scales: {limits:?}"
        );
        // The page writes the limits in full; the JSON reads back within an ulp or so.
        let drawn: Vec<f64> = limits
            .first()
            .unwrap()
            .split(',')
            .map(|v| v.parse().unwrap())
            .collect();
        for (a, b) in drawn.iter().zip([lo, hi]) {
            assert!(
                (a - b).abs() <= 1e-12 * b.abs().max(1.0),
                "{column}: {a} against {b}"
            );
        }
        // One colour bar per set of multiples.
        assert_eq!(
            sec.matches("data-kind=\"colour-bar\"").count(),
            2,
            "{column}"
        );

        // Differences: every variant but the base, on one symmetric scale, equal to the
        // variant's map minus the base's.
        let diff = figures(sec, "diff");
        let diff_ids: Vec<usize> = diff.iter().map(|f| f.0.parse().unwrap()).collect();
        assert_eq!(diff_ids, (0..18).filter(|i| *i != base).collect::<Vec<_>>());
        let (dlo, dhi) = pair(&m["diff_limits"]);
        assert!(dlo == -dhi && dhi > 0.0, "{column}: {dlo}, {dhi}");
        let limits: BTreeSet<&String> = diff.iter().map(|f| &f.1).collect();
        assert_eq!(limits.len(), 1);
        let vals = m["values"].as_array().unwrap();
        let diffs = m["diffs"].as_array().unwrap();
        for (k, &i) in diff_ids.iter().enumerate() {
            for ((d, v), b) in diffs[k]
                .as_array()
                .unwrap()
                .iter()
                .zip(vals[i].as_array().unwrap())
                .zip(vals[base].as_array().unwrap())
            {
                match (d.as_f64(), v.as_f64(), b.as_f64()) {
                    // Within the JSON's parsing (correct to an ulp or so).
                    (Some(d), Some(v), Some(b)) => {
                        assert!(
                            (d - (v - b)).abs() <= 1e-12 * v.abs().max(1.0),
                            "{d}, {v}, {b}"
                        )
                    }
                    (None, _, _) => assert!(v.is_null() || b.is_null()),
                    other => panic!("{column}: {other:?}"),
                }
            }
        }
        // A CoM offset changes the ball speed map: the difference maps are not all zero.
        assert!(finite(&m["diffs"]).iter().any(|d| d.abs() > 1e-6));
    }
    // The first output is open, the others folded.
    assert_eq!(html.matches("<details open>").count(), 1);

    // Tables fit the page: at most 8 columns.
    for t in html.split("<table>").skip(1) {
        let header = &t[..t.find("</tr>").unwrap()];
        let n = header.matches("<th").count();
        assert!(n <= 8, "a table of {n} columns: {header}");
    }
    // Enough digits to tell the variants apart: no two variants' centre ball speed print the
    // same in the full table although they differ.
    let j = json["metrics"]
        .as_array()
        .unwrap()
        .iter()
        .position(|m| m["name"] == "cof_ball_speed_mph")
        .unwrap();
    let dp = json["metric_decimals"][j].as_u64().unwrap() as usize;
    let printed: BTreeSet<String> = variants
        .iter()
        .map(|v| format!("{:.dp$}", v["metrics"][j].as_f64().unwrap()))
        .collect();
    let distinct: BTreeSet<u64> = variants
        .iter()
        .map(|v| v["metrics"][j].as_f64().unwrap().to_bits())
        .collect();
    assert_eq!(printed.len(), distinct.len(), "{printed:?}");
    for p in &printed {
        assert!(
            html.contains(&format!("<td>{p}</td>")),
            "{p} not on the page"
        );
    }
}

#[test]
fn a_study_of_one_design_draws_its_maps_without_differences() {
    let dir = tempfile::tempdir().unwrap();
    let (json, html, _) = run("configs/studies/face_map.toml", dir.path());
    assert_eq!(json["variants"].as_array().unwrap().len(), 1);
    assert_eq!(json["base_id"], 0);
    let outputs = json["face_maps"].as_array().unwrap().len();
    assert_eq!(outputs, 6, "the default outputs");
    assert_eq!(figures(&html, "face").len(), outputs, "one map per output");
    assert!(figures(&html, "diff").is_empty());
    assert!(!html.contains("measured"));
}

#[test]
fn the_optimiser_and_the_yards_are_on_the_page() {
    let dir = tempfile::tempdir().unwrap();
    let (json, html, _) = run("configs/studies/optimise.toml", dir.path());
    let o = &json["optimiser"];
    assert_eq!(o["goal"], "maximise");
    assert!(o["best_objective"].as_f64().unwrap() > o["base_objective"].as_f64().unwrap());
    let summary = &html[..html.find("<section id=\"details\">").unwrap()];
    assert!(summary.contains("<h3>Optimum</h3>\n<p>Maximising the objective"));
    // The optimum's design to a thousandth of a millimetre, and the objective's metrics at the
    // base and the optimum.
    for (k, v) in o["best_design"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| (p[0].as_str().unwrap(), p[1].as_f64().unwrap()))
    {
        assert!(summary.contains(&format!("{k} = {v:.3}")), "{k}");
    }
    assert!(summary.contains("<td class=\"l\">mean_ball_speed_mph</td><td>mph</td>"));
    assert!(html.contains("<details><summary>Optimiser path</summary>"));
    assert!(html.contains("data-kind=\"optimiser\""));

    let (json, html, _) = run("configs/studies/yards_driver.toml", dir.path());
    let rows = json["yards"]["rows"].as_array().unwrap();
    assert!(rows.len() >= 2, "the base and the [yards.optimise] optimum");
    assert_eq!(rows[0]["label"], "base");
    let summary = &html[..html.find("<section id=\"details\">").unwrap()];
    assert!(summary.contains("In yards, against the base"));
    // Each head's change of mean carry, ± the quadrature's error, in the summary.
    for r in rows {
        let d = r["deltas"][0].as_f64().unwrap();
        let u = r["uncertainties"][0].as_f64().unwrap();
        assert!(summary.contains(&format!("{d:+.3} ± {u:.3}")), "{d} ± {u}");
    }
    assert!(!html.contains("measured"));
}

#[test]
fn a_merge_reports_what_the_unsharded_run_reports() {
    let dir = tempfile::tempdir().unwrap();
    let (whole, _, _) = run("configs/studies/com_sweep.toml", dir.path());
    let mut shards = Vec::new();
    for k in 0..3 {
        let d = dir.path().join(format!("shard{k}"));
        let out = smash(&[
            "run",
            "configs/studies/com_sweep.toml",
            "--shard",
            &format!("{k}/3"),
            "--out",
            s(&d),
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        shards.push(d);
    }
    let merged = dir.path().join("merged");
    let mut args = vec!["merge"];
    args.extend(shards.iter().map(|d| s(d)));
    args.extend(["--out", s(&merged), "--json"]);
    let out = smash(&args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: Value = serde_json::from_slice(&out.stdout).unwrap();
    // The text went to stderr.
    assert!(String::from_utf8_lossy(&out.stderr).contains("study 'com_sweep'"));
    assert_eq!(json, whole);
}
