//! The JSON reports hold what `docs/json.md` says they hold: every top-level key a command
//! prints is listed in the command's table there and every listed key is printed, and each
//! object opens with `schema_version` (the documented version) and `command`.

use crate::cli_support;

use std::collections::BTreeSet;

use cli_support::{club, repo, s, smash, stderr, synth_world};

/// The keys listed in the first column of the table under `## \`smash CMD --json\``, and
/// the section's version (`(version N)` in its heading).
fn documented(cmd: &str) -> (BTreeSet<String>, u64) {
    let doc = std::fs::read_to_string(repo("docs/json.md")).unwrap();
    let head = format!("## `smash {cmd} --json` (version ");
    let start = doc
        .find(&head)
        .unwrap_or_else(|| panic!("docs/json.md has no section for {cmd}"));
    let section = &doc[start..];
    let version: u64 = section[head.len()..]
        .split(')')
        .next()
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("{cmd}: no version in the heading"));
    let end = section[3..].find("\n## ").map_or(section.len(), |e| e + 3);
    let mut keys = BTreeSet::new();
    for line in section[..end].lines() {
        let Some(first) = line.strip_prefix("| ").and_then(|l| l.split(" |").next()) else {
            continue;
        };
        // `a`, `b` lists several keys in one row.
        for part in first.split(", ") {
            if let Some(k) = part.strip_prefix('`').and_then(|k| k.strip_suffix('`')) {
                keys.insert(k.to_owned());
            }
        }
    }
    (keys, version)
}

/// The JSON text `smash ARGS` prints (the command must succeed).
fn json_of(args: &[&str]) -> String {
    let o = smash(args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    String::from_utf8(o.stdout).unwrap()
}

/// The top-level keys of the JSON `text`, checked against the documentation of `cmd`; the
/// object opens with its version and command. The parsed object.
fn check(cmd: &str, text: &str, optional: &[&str]) -> serde_json::Value {
    let (doc, version) = documented(cmd);
    let opening = format!("{{\n  \"schema_version\": {version},\n  \"command\": \"{cmd}\",\n");
    assert!(
        text.starts_with(&opening),
        "{cmd}: {}",
        &text[..text.len().min(200)]
    );
    let json: serde_json::Value =
        serde_json::from_str(text).unwrap_or_else(|e| panic!("{cmd}: {e}"));
    let keys: Vec<String> = json
        .as_object()
        .unwrap_or_else(|| panic!("{cmd}: not an object"))
        .keys()
        .cloned()
        .collect();
    let printed: BTreeSet<String> = keys.into_iter().collect();
    let undocumented: Vec<&String> = printed.difference(&doc).collect();
    assert!(
        undocumented.is_empty(),
        "{cmd} prints keys docs/json.md does not list: {undocumented:?}"
    );
    let missing: Vec<&String> = doc
        .difference(&printed)
        .filter(|k| !optional.contains(&k.as_str()))
        .collect();
    assert!(
        missing.is_empty(),
        "docs/json.md lists {cmd} keys it does not print: {missing:?}"
    );
    json
}

#[test]
fn every_json_report_is_documented_and_versioned() {
    let dir = tempfile::tempdir().unwrap();
    let shots = synth_world(dir.path(), "paper_world", 3);
    let club = club();
    let cmp = dir.path().join("cmp");
    let base = ["--club", club.as_str(), "--shots", s(&shots), "--json"];
    let with = |cmd: &str, more: &[&str]| {
        let mut a = vec![cmd];
        a.extend_from_slice(&base);
        a.extend_from_slice(more);
        json_of(&a)
    };
    // compare prints `club_mismatch` only when the shots are another club's.
    check("compare", &with("compare", &[]), &["club_mismatch"]);
    let o = smash(&[
        "compare",
        "--club",
        &club,
        "--shots",
        s(&shots),
        "--out-dir",
        s(&cmp),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let written = std::fs::read_to_string(cmp.join("compare.json")).unwrap();
    check("compare", &written, &["club_mismatch"]);
    check(
        "calibrate",
        &with("calibrate", &["--effects", "ball_offset"]),
        &[],
    );
    check("diagnose", &with("diagnose", &["--max-steps", "2"]), &[]);
    let launch = dir.path().join("rapsodo.csv");
    let o = smash(&[
        "import",
        "--format",
        "rapsodo",
        s(&repo("tests/data/real/rapsodo_mlm2pro_7i.csv")),
        "--out",
        s(&launch),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = dir.path().join("flight.csv");
    let flight = json_of(&["flight", "--shots", s(&launch), "--out", s(&out), "--json"]);
    let flight = check("flight", &flight, &[]);
    assert!(flight["diagnosis"].is_null(), "{flight}");
    let study = dir.path().join("study");
    let run = json_of(&[
        "run",
        s(&repo("configs/studies/optimise.toml")),
        "--out",
        s(&study),
        "--json",
    ]);
    let run = check("run", &run, &["yards"]);
    assert!(run["optimiser"].is_object(), "optimise.toml optimises");
    let effects = check("effects", &json_of(&["effects", "--json"]), &[]);
    assert!(effects["effects"][0]["params"].is_array(), "{effects}");
}

#[test]
fn infer_club_json_is_documented_and_versioned() {
    let dir = tempfile::tempdir().unwrap();
    let shots = synth_world(dir.path(), "face_curvature_world", 3);
    let club = club();
    let base = [
        "infer-club",
        "--start",
        club.as_str(),
        "--shots",
        s(&shots),
        "--json",
    ];
    let mut fit = base.to_vec();
    fit.push("--no-profile");
    let json = check("infer-club", &json_of(&fit), &[]);
    let params = json["params"].as_array().unwrap();
    assert_eq!(params.len(), 11, "{json}");
    for p in params {
        for key in ["name", "value", "stderr", "start", "determined"] {
            assert!(!p[key].is_null(), "{key} missing in {p}");
        }
    }
    let mut plan = base.to_vec();
    plan.extend(["--plan", "--plan-shots", "1200"]);
    let json = check("infer-club --plan", &json_of(&plan), &[]);
    assert_eq!(json["n_planned"], 1200, "{json}");
}
