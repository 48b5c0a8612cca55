//! `--report FILE.html`: the pages' structure without a browser (charts present, nothing fetched,
//! numbers equal to the JSON), and each page rendered in headless Chromium (screenshot not
//! blank, no console errors). The browser test skips loudly when Chromium is absent outside CI
//! and fails in CI (`CI=true`), where `.ci/run` installs it.

use crate::cli_support;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

use cli_support::smash_in_repo as smash;

fn ok(out: Output) -> String {
    assert!(
        out.status.success(),
        "smash failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("utf-8")
}

const CLUB: &str = "configs/clubs/paper_driver.toml";

/// The paper world's experiment (600 shots, 3 shafts, 20 golfers).
fn experiment(dir: &Path) -> PathBuf {
    let shots = dir.join("paper_world.csv");
    ok(smash(&[
        "synth",
        "--config",
        "configs/synth/paper_world.toml",
        "--out",
        shots.to_str().unwrap(),
    ]));
    shots
}

struct Reports {
    _dir: tempfile::TempDir,
    compare: (PathBuf, Value),
    calibrate: (PathBuf, Value),
    diagnose: (PathBuf, Value),
    study: PathBuf,
    /// A study of 18 variants (small multiples and difference maps).
    sweep: PathBuf,
    /// `infer-club`'s page (the inferred COR's face map, the ellipses).
    infer: PathBuf,
    /// `whatif`'s page (the landing patterns, the head from above and behind).
    whatif: PathBuf,
}

fn reports() -> Reports {
    let dir = tempfile::tempdir().unwrap();
    let shots = experiment(dir.path());
    let s = shots.to_str().unwrap();
    let path = |n: &str| dir.path().join(n);
    let compare = path("compare.html");
    let cj = ok(smash(&[
        "compare",
        "--club",
        CLUB,
        "--shots",
        s,
        "--json",
        "--report",
        compare.to_str().unwrap(),
    ]));
    let calibrate = path("calibrate.html");
    let kj = ok(smash(&[
        "calibrate",
        "--club",
        CLUB,
        "--shots",
        s,
        "--effects",
        "added_mass@group,ball_offset",
        "--json",
        "--report",
        calibrate.to_str().unwrap(),
    ]));
    let diagnose = path("diagnose.html");
    let dj = ok(smash(&[
        "diagnose",
        "--club",
        CLUB,
        "--shots",
        s,
        "--candidates",
        "added_mass@group,ball_offset,loft_bias",
        "--folds",
        "3",
        "--max-steps",
        "2",
        "--impact-noise-mm",
        "3,2.5",
        "--json",
        "--report",
        diagnose.to_str().unwrap(),
    ]));
    let study = path("study.html");
    ok(smash(&[
        "run",
        "configs/studies/face_map.toml",
        "--out",
        path("study").to_str().unwrap(),
        "--report",
        study.to_str().unwrap(),
    ]));
    let sweep = path("sweep.html");
    ok(smash(&[
        "run",
        "configs/studies/com_sweep.toml",
        "--out",
        path("sweep").to_str().unwrap(),
        "--report",
        sweep.to_str().unwrap(),
    ]));
    let infer = path("infer.html");
    ok(smash(&[
        "infer-club",
        "--start",
        CLUB,
        "--shots",
        s,
        "--no-profile",
        "--report",
        infer.to_str().unwrap(),
    ]));
    let whatif = path("whatif.html");
    ok(smash(&[
        "whatif",
        "--club",
        CLUB,
        "--speed",
        "95",
        "--face-sd",
        "1.5",
        "--move-mass",
        "5g:-70,-10,0:-80,-10,-10",
        "--report",
        whatif.to_str().unwrap(),
    ]));
    Reports {
        compare: (compare, serde_json::from_str(&cj).unwrap()),
        calibrate: (calibrate, serde_json::from_str(&kj).unwrap()),
        diagnose: (diagnose, serde_json::from_str(&dj).unwrap()),
        study,
        sweep,
        infer,
        whatif,
        _dir: dir,
    }
}

/// Charts on a page, by kind.
fn charts(html: &str) -> Vec<String> {
    html.match_indices("<figure class=\"chart\" data-kind=\"")
        .map(|(i, m)| {
            let rest = &html[i + m.len()..];
            rest[..rest.find('"').unwrap()].to_owned()
        })
        .collect()
}

/// Self-contained: no scripts, no external references, every chart an inline SVG.
fn assert_self_contained(html: &str, name: &str) {
    assert!(html.starts_with("<!DOCTYPE html>"), "{name}");
    assert!(!html.contains("<script"), "{name}: has a script");
    for bad in [
        "src=\"http",
        "href=\"http",
        "url(http",
        "@import",
        "@font-face",
    ] {
        assert!(!html.contains(bad), "{name}: fetches something ({bad})");
    }
    for fig in html.split("<figure class=\"chart\"").skip(1) {
        let fig = &fig[..fig.find("</figure>").unwrap()];
        assert!(fig.contains("<svg"), "{name}: a chart without an SVG");
        assert!(
            fig.contains("<text"),
            "{name}: a chart without text (axes, title)"
        );
    }
    assert!(
        !html.contains("NaN") && !html.contains("inf<"),
        "{name}: NaN or inf shown"
    );
}

/// Equal up to the last bit or two: serde_json's default float parser is not exactly rounding,
/// so the JSON read back can differ from the printed value in the last place.
fn same(a: f64, b: f64) -> bool {
    (a - b).abs() <= 4.0 * f64::EPSILON * a.abs().max(b.abs())
}

/// Every `data-key`/`data-value` pair on the page.
fn data_values(html: &str) -> Vec<(String, f64)> {
    html.match_indices("data-key=\"")
        .map(|(i, m)| {
            let rest = &html[i + m.len()..];
            let key = rest[..rest.find('"').unwrap()].to_owned();
            let v = &rest[rest.find("data-value=\"").unwrap() + 12..];
            let v: f64 = v[..v.find('"').unwrap()].parse().unwrap();
            (key, v)
        })
        .collect()
}

#[test]
fn pages_have_charts_and_the_json_numbers() {
    let r = reports();

    let html = std::fs::read_to_string(&r.whatif).unwrap();
    assert_self_contained(&html, "whatif");
    let kinds = charts(&html);
    assert_eq!(kinds, ["landing", "face", "head", "head"], "whatif");

    let html = std::fs::read_to_string(&r.compare.0).unwrap();
    assert_self_contained(&html, "compare");
    let kinds = charts(&html);
    assert_eq!(
        kinds.iter().filter(|k| *k == "table2").count(),
        5,
        "{kinds:?}"
    );
    assert_eq!(
        kinds.iter().filter(|k| *k == "trend").count(),
        4,
        "{kinds:?}"
    );
    assert!(
        kinds.iter().filter(|k| *k == "face").count() >= 1,
        "{kinds:?}"
    );
    // Table 2 on the page carries the JSON's numbers exactly.
    let vals = data_values(&html);
    let table2 = r.compare.1["table2"].as_array().unwrap();
    let mut checked = 0;
    for g in table2 {
        for c in g["components"].as_array().unwrap() {
            for what in ["mean", "std"] {
                let key = format!(
                    "{}/{}/{what}",
                    g["group"].as_str().unwrap(),
                    c["component"].as_str().unwrap()
                );
                let want = c[what].as_f64().unwrap();
                let got = vals.iter().find(|(k, _)| *k == key).map(|(_, v)| *v);
                assert!(
                    got.is_some_and(|g| same(g, want)),
                    "{key}: {got:?} vs {want}"
                );
                checked += 1;
            }
        }
    }
    assert_eq!(checked, 4 * 5 * 2);
    // Every finding is on the page.
    for f in r.compare.1["findings"].as_array().unwrap() {
        let text = f["text"]
            .as_str()
            .unwrap()
            .replace('&', "&amp;")
            .replace('<', "&lt;")
            .replace('>', "&gt;");
        assert!(html.contains(&text), "finding missing: {text}");
    }

    let html = std::fs::read_to_string(&r.calibrate.0).unwrap();
    assert_self_contained(&html, "calibrate");
    let kinds = charts(&html);
    assert!(kinds.len() >= 4, "{kinds:?}");
    assert_eq!(
        kinds.iter().filter(|k| *k == "table2").count(),
        5,
        "{kinds:?}"
    );
    assert!(kinds.contains(&"estimates".to_owned()), "{kinds:?}");
    let vals = data_values(&html);
    let params = r.calibrate.1["params"].as_array().unwrap();
    assert_eq!(params.len(), 5);
    for p in params {
        let label = match p["group"].as_str() {
            Some(g) => format!(
                "{}@{g}.{}",
                p["effect"].as_str().unwrap(),
                p["param"].as_str().unwrap()
            ),
            None => format!(
                "{}.{}",
                p["effect"].as_str().unwrap(),
                p["param"].as_str().unwrap()
            ),
        };
        let got = vals.iter().find(|(k, _)| *k == label).map(|(_, v)| *v);
        let want = p["value"].as_f64().unwrap();
        assert!(
            got.is_some_and(|g| same(g, want)),
            "{label}: {got:?} vs {want}"
        );
    }
    assert!(html.contains("before (nominal)") && html.contains("after (calibrated)"));

    let html = std::fs::read_to_string(&r.diagnose.0).unwrap();
    assert_self_contained(&html, "diagnose");
    let kinds = charts(&html);
    let steps = r.diagnose.1["steps"].as_array().unwrap().len();
    assert_eq!(
        kinds.iter().filter(|k| *k == "steps").count(),
        steps,
        "{kinds:?}"
    );
    for e in r.diagnose.1["estimates"].as_array().unwrap() {
        let v = e["value"].as_f64().unwrap();
        assert!(
            data_values(&html).iter().any(|(_, x)| same(*x, v)),
            "estimate {v} missing"
        );
    }
    // Every candidate of every step is named on its chart.
    for s in r.diagnose.1["steps"].as_array().unwrap() {
        for c in s["candidates"].as_array().unwrap() {
            assert!(html.contains(c["effect"].as_str().unwrap()));
        }
    }
    // The strata table: every stratum's row with its size, and every refitted value to four
    // decimals, as the JSON has them.
    assert!(html.contains("Stability across strata"));
    for f in r.diagnose.1["strata"]["families"].as_array().unwrap() {
        for st in f["strata"].as_array().unwrap() {
            let label = st["label"].as_str().unwrap();
            let label = label
                .replace('&', "&amp;")
                .replace('<', "&lt;")
                .replace('>', "&gt;");
            assert!(html.contains(&label), "stratum {label} missing");
            for v in st["values"].as_object().unwrap().values() {
                let cell = format!("{:.4}", v["value"].as_f64().unwrap());
                assert!(html.contains(&cell), "{label}: value {cell} missing");
            }
        }
    }

    let html = std::fs::read_to_string(&r.study).unwrap();
    assert_self_contained(&html, "study");
    assert!(charts(&html).iter().any(|k| k == "face"));
    let html = std::fs::read_to_string(&r.sweep).unwrap();
    assert_self_contained(&html, "study of 18 variants");
    let kinds = charts(&html);
    assert_eq!(kinds.iter().filter(|k| *k == "face").count(), 4 * 18);
    assert_eq!(kinds.iter().filter(|k| *k == "diff").count(), 4 * 17);
}

/// Chromium's binary, if installed.
fn chromium() -> Option<PathBuf> {
    for name in ["chromium", "chromium-browser", "google-chrome"] {
        if let Ok(out) = Command::new("sh")
            .args(["-c", &format!("command -v {name}")])
            .output()
        {
            let p = String::from_utf8_lossy(&out.stdout).trim().to_owned();
            if out.status.success() && !p.is_empty() {
                return Some(PathBuf::from(p));
            }
        }
    }
    None
}

/// Render `page` headless: (screenshot bytes, console lines, dumped DOM).
fn render(chrome: &Path, page: &Path, shot: &Path) -> (Vec<u8>, Vec<String>, String) {
    let profile = tempfile::tempdir().unwrap();
    let common = [
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-quic",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--hide-scrollbars",
        "--enable-logging=stderr",
        "--v=0",
    ];
    let url = format!("file://{}", page.display());
    let out = Command::new(chrome)
        .args(common)
        .arg(format!("--user-data-dir={}", profile.path().display()))
        .arg(format!("--screenshot={}", shot.display()))
        .arg("--window-size=1280,2000")
        .arg(&url)
        .output()
        .expect("chromium runs");
    assert!(
        out.status.success(),
        "chromium failed on {}",
        page.display()
    );
    let console: Vec<String> = String::from_utf8_lossy(&out.stderr)
        .lines()
        .filter(|l| l.contains("CONSOLE") || l.contains("Uncaught"))
        .map(str::to_owned)
        .collect();
    let profile2 = tempfile::tempdir().unwrap();
    let dom = Command::new(chrome)
        .args(common)
        .arg(format!("--user-data-dir={}", profile2.path().display()))
        .arg("--dump-dom")
        .arg(&url)
        .output()
        .expect("chromium runs");
    (
        std::fs::read(shot).expect("screenshot written"),
        console,
        String::from_utf8_lossy(&dom.stdout).into_owned(),
    )
}

#[test]
fn pages_render_in_chromium() {
    let Some(chrome) = chromium() else {
        if std::env::var("CI").is_ok_and(|v| v == "true") {
            panic!("Chromium is not installed in CI: .ci/run must install it (apt-get install chromium)");
        }
        eprintln!(
            "\n*** SKIPPED pages_render_in_chromium: chromium is not installed. ***\n\
             *** Install it (apt-get install chromium) or run .ci/run to check the reports in a browser. ***\n"
        );
        return;
    };
    let r = reports();
    let dir = tempfile::tempdir().unwrap();
    // A blank page at the same size: the baseline a rendered report must be far above.
    let blank = dir.path().join("blank.html");
    std::fs::write(&blank, "<!DOCTYPE html><html><body></body></html>").unwrap();
    let (blank_png, _, _) = render(&chrome, &blank, &dir.path().join("blank.png"));
    // The check can fail: a page logging an error to the console is caught.
    let noisy = dir.path().join("noisy.html");
    std::fs::write(
        &noisy,
        "<!DOCTYPE html><html><body><p>x</p><script>console.error('broken chart')</script></body></html>",
    )
    .unwrap();
    let (_, console, _) = render(&chrome, &noisy, &dir.path().join("noisy.png"));
    assert!(
        console.iter().any(|l| l.contains("broken chart")),
        "the console scan missed a console error: {console:?}"
    );
    for (name, page, min_charts) in [
        ("compare", &r.compare.0, 4),
        ("calibrate", &r.calibrate.0, 4),
        ("diagnose", &r.diagnose.0, 2),
        ("study", &r.study, 1),
        ("study of 18 variants", &r.sweep, 4 * 35),
        ("infer-club", &r.infer, 1),
        ("whatif", &r.whatif, 4),
    ] {
        let (png, console, dom) = render(&chrome, page, &dir.path().join(format!("{name}.png")));
        assert!(png.starts_with(b"\x89PNG"), "{name}: not a PNG");
        assert!(
            png.len() > 8 * blank_png.len() && png.len() > 30_000,
            "{name}: screenshot looks blank ({} bytes; a blank page is {})",
            png.len(),
            blank_png.len()
        );
        assert!(console.is_empty(), "{name}: console messages: {console:?}");
        let svgs = dom.matches("<svg").count();
        if name == "infer-club" {
            assert!(
                dom.contains("data-kind=\"face\"") && dom.contains("inferred COR over the face"),
                "infer-club: the browser's DOM has no face map of the inferred COR"
            );
        }
        assert!(
            svgs >= min_charts,
            "{name}: the browser's DOM has {svgs} SVG charts"
        );
        if name == "whatif" {
            assert_whatif_pictures(&dom);
        }
    }
}

/// The numbers of attribute `name` on the elements whose tag starts with `start`.
fn attr_values(html: &str, start: &str, name: &str) -> Vec<f64> {
    html.match_indices(start)
        .map(|(i, _)| {
            let tag = &html[i..i + html[i..].find('>').unwrap()];
            let key = format!(" {name}=\"");
            let v =
                &tag[tag.find(&key).unwrap_or_else(|| panic!("{tag}: no {name}")) + key.len()..];
            v[..v.find('"').unwrap()].parse().unwrap()
        })
        .collect()
}

/// The whatif page as the browser laid it out: both landing patterns with their dots and
/// ellipses (finite, positive radii) on axes in yards, and the head from above and from behind
/// with the CoM and the moved mass before and after.
fn assert_whatif_pictures(dom: &str) {
    for head in ["base", "changed"] {
        let group = format!("<g class=\"landing {head}\"");
        let i = dom
            .find(&group)
            .unwrap_or_else(|| panic!("whatif: no {head} landings"));
        let dots = dom[i..dom[i..].find("</g>").unwrap() + i]
            .matches("<circle")
            .count();
        assert!(dots >= 25, "whatif: {dots} {head} landing points");
        let ellipse = format!("<ellipse class=\"ellipse {head}\"");
        assert_eq!(
            dom.matches(&ellipse).count(),
            1,
            "whatif: the {head} ellipse"
        );
        for r in ["rx", "ry"] {
            let v = attr_values(dom, &ellipse, r)[0];
            assert!(
                v.is_finite() && v > 0.0,
                "whatif: the {head} ellipse's {r} is {v}"
            );
        }
    }
    assert!(
        dom.contains("offline, yd") && dom.contains(">carry, yd<"),
        "whatif: the landing plot's axes are not labelled in yards"
    );
    assert!(dom.contains("class=\"head-above\"") && dom.contains("class=\"head-behind\""));
    for class in ["com before", "com after", "mass from", "mass to"] {
        let n = dom.matches(&format!("<circle class=\"{class}\"")).count();
        assert_eq!(n, 2, "whatif: {class} drawn {n} times (once a view)");
    }
    assert!(
        dom.contains("data-kind=\"face\"") && dom.contains("Carry change over the face"),
        "whatif: no face map of the carry change"
    );
}

/// Width of the narrowest figure a page lays out, CSS px: the grid's smallest column (480 px,
/// `minmax(480px, 1fr)` in the page's CSS) less the figure's padding (6 px a side). In print the
/// figures are a full column of an A4 page, wider than this.
const NARROWEST_FIGURE_PX: f64 = 468.0;

/// Smallest legible label, CSS px: 8 px is 6 pt, the usual minimum for text in a printed
/// figure.
const MIN_LABEL_PX: f64 = 8.0;

/// Every chart's smallest text, as shown in the narrowest figure: `(svg width, smallest
/// font-size, shown size)` per `<svg>` of the page.
fn label_sizes(html: &str) -> Vec<(f64, f64, f64)> {
    let attr = |tag: &str, name: &str| -> Option<f64> {
        let key = format!(" {name}=\"");
        let i = tag.find(&key)? + key.len();
        tag[i..]
            .split('"')
            .next()?
            .trim_end_matches("px")
            .parse()
            .ok()
    };
    let mut out = Vec::new();
    for (start, _) in html.match_indices("<svg") {
        let end = html[start..]
            .find("</svg>")
            .map_or(html.len(), |e| start + e);
        let svg = &html[start..end];
        let width = attr(&svg[..svg.find('>').unwrap()], "width").expect("an svg with a width");
        let smallest = svg
            .match_indices('<')
            .filter_map(|(i, _)| {
                let tag = &svg[i..i + svg[i..].find('>').unwrap_or(0)];
                attr(tag, "font-size")
            })
            .fold(f64::INFINITY, f64::min);
        let shown = smallest * NARROWEST_FIGURE_PX.min(width) / width;
        out.push((width, smallest, shown));
    }
    out
}

#[test]
fn labels_are_legible_in_the_narrowest_figure() {
    // The check can fail: a chart drawn 1,800 px wide with 12 px labels (the step charts of a
    // default diagnose once were) shows them at 3 px.
    let wide = "<svg width=\"1800\" height=\"400\"><text font-size=\"12\">x</text></svg>";
    assert!(label_sizes(wide)[0].2 < 4.0);
    let r = reports();
    // And diagnose with every default candidate: 28 bars a step.
    let dir = tempfile::tempdir().unwrap();
    let shots = experiment(dir.path());
    let page = dir.path().join("diagnose_default.html");
    ok(smash(&[
        "diagnose",
        "--club",
        CLUB,
        "--shots",
        shots.to_str().unwrap(),
        "--max-steps",
        "1",
        "--report",
        page.to_str().unwrap(),
    ]));
    for (name, page) in [
        ("compare", &r.compare.0),
        ("calibrate", &r.calibrate.0),
        ("diagnose", &r.diagnose.0),
        ("diagnose, default candidates", &page),
        ("study", &r.study),
        ("study of 18 variants", &r.sweep),
        ("whatif", &r.whatif),
    ] {
        let html = std::fs::read_to_string(page).unwrap();
        let sizes = label_sizes(&html);
        assert!(!sizes.is_empty(), "{name}: no chart");
        for (width, font, shown) in sizes {
            assert!(
                shown >= MIN_LABEL_PX,
                "{name}: a chart {width} px wide has {font} px text, shown at {shown:.1} px in a \
                 {NARROWEST_FIGURE_PX} px figure (at least {MIN_LABEL_PX} px)"
            );
        }
    }
}

/// `page`'s document height and width, CSS px, laid out in a window `window_px` wide: a copy of
/// the page with a script that writes them into its title, read from the browser's DOM.
fn page_size(chrome: &Path, page: &Path, window_px: u32) -> (f64, f64) {
    let dir = tempfile::tempdir().unwrap();
    let copy = dir.path().join("measured.html");
    let html = std::fs::read_to_string(page).unwrap().replace(
        "</body>",
        "<script>document.title='size '+document.documentElement.scrollHeight+' '\
         +document.documentElement.scrollWidth</script></body>",
    );
    std::fs::write(&copy, html).unwrap();
    let out = Command::new(chrome)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--no-first-run",
        ])
        .arg(format!(
            "--user-data-dir={}",
            dir.path().join("p").display()
        ))
        .arg(format!("--window-size={window_px},1000"))
        .arg("--dump-dom")
        .arg(format!("file://{}", copy.display()))
        .output()
        .expect("chromium runs");
    let dom = String::from_utf8_lossy(&out.stdout);
    let title = &dom[dom.find("<title>size ").expect("the measuring script ran") + 12..];
    let mut it = title[..title.find('<').unwrap()]
        .split(' ')
        .map(|v| v.parse::<f64>().unwrap());
    (it.next().unwrap(), it.next().unwrap())
}

/// Width of an A4 page's printable area, CSS px (210 mm less 2 × 10 mm margins at 96 px per
/// inch).
const PRINT_WIDTH_PX: u32 = 718;

#[test]
fn study_pages_are_of_reasonable_height_and_fit_the_page_width() {
    let Some(chrome) = chromium() else {
        if std::env::var("CI").is_ok_and(|v| v == "true") {
            panic!("Chromium is not installed in CI: .ci/run must install it (apt-get install chromium)");
        }
        eprintln!("\n*** SKIPPED: chromium is not installed. ***\n");
        return;
    };
    let r = reports();
    for (name, page, max_height_px) in [("study", &r.study, 2500.0), ("sweep", &r.sweep, 6000.0)] {
        let (height, width) = page_size(&chrome, page, 1280);
        eprintln!("{name}: {height} px tall, {width} px wide in a 1280 px window");
        assert!(height <= max_height_px, "{name}: {height} px tall");
        assert!(width <= 1280.0, "{name}: {width} px wide");
        // No horizontal scroll at print width: the tables and maps fit.
        let (_, width) = page_size(&chrome, page, PRINT_WIDTH_PX);
        assert!(
            width <= f64::from(PRINT_WIDTH_PX),
            "{name}: {width} px wide at print width"
        );
    }
}
