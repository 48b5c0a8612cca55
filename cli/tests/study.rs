//! Design studies: parsing, maps vs the impact solve, sensitivities vs independent finite
//! differences, gear-effect signs, the optimiser, shard merges, and the CLI end to end.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use nalgebra::{Matrix3, Vector3};
use smash::data::club_file::read_club;
use smash::study::metrics::metric_names;
use smash::study::optimise::optimise;
use smash::study::sensitivity::sensitivities;
use smash::study::{parse_study, resolved_toml, Prepared};
use smash::{Delivery, ImpactModel, LaunchComponent, ModelParams};

fn root() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
}

fn club_path() -> String {
    root()
        .join("configs/clubs/paper_driver.toml")
        .to_string_lossy()
        .into_owned()
}

/// A small study using the paper driver, with `extra` appended.
fn study_text(extra: &str) -> String {
    format!(
        r#"[study]
name = "t"
club = "{}"

[delivery]
club_speed_mph = 100.0
dynamic_loft_deg = 12.0

[grid]
y_mm = {{ from = -10.0, to = 10.0, count = 5 }}
z_mm = {{ from = -20.0, to = 20.0, count = 9 }}
{extra}"#,
        club_path()
    )
}

fn parse(text: &str) -> Result<smash::study::Study, String> {
    parse_study(Path::new("study.toml"), text).map_err(|e| e.to_string())
}

fn smash() -> Command {
    Command::new(env!("CARGO_BIN_EXE_smash"))
}

fn base_model() -> ImpactModel {
    read_club(&root().join("configs/clubs/paper_driver.toml"))
        .unwrap()
        .model_for_group("all")
        .unwrap()
}

fn delivery(y_mm: f64, z_mm: f64) -> Delivery {
    Delivery {
        club_speed_m_s: 100.0 * 0.44704,
        attack_angle_rad: 0.0,
        club_path_rad: 0.0,
        dynamic_loft_rad: 12f64.to_radians(),
        face_angle_rad: 0.0,
        lie_tilt_rad: 0.0,
        club_omega_rad_s: Vector3::zeros(),
        impact_y_m: y_mm * 1e-3,
        impact_z_m: z_mm * 1e-3,
        shaft_mass_g: None,
    }
}

/// Every file under `dir`, relative path → bytes.
fn tree(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                out.insert(
                    p.strip_prefix(dir).unwrap().to_path_buf(),
                    std::fs::read(&p).unwrap(),
                );
            }
        }
    }
    out
}

fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_owned)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(str::to_owned).collect())
        .collect();
    (header, rows)
}

#[test]
fn study_parsing_names_the_bad_key() {
    assert!(parse(&study_text("")).is_ok());
    let cases: &[(&str, &str, &str)] = &[
        // (what is appended or replaced, expected text, expected text)
        ("[design]\ncom_dq_mm = [1.0]\n", "design.com_dq_mm", "allowed"),
        ("[design]\ncom_dx_mm = \"a\"\n", "design.com_dx_mm", "string"),
        ("[design]\ncom_dx_mm = { from = 0.0, to = 1.0 }\n", "design.com_dx_mm", "count"),
        ("[design]\ncom_dx_mm = { from = 0.0, to = 1.0, step = 0.3 }\n", "design.com_dx_mm.step", "whole steps"),
        ("[design]\nmass_dx_mm = [1.0]\n", "design.mass_dx_mm", "discretionary_mass"),
        ("[design]\ndiscretionary_mass = { mass_g = 500.0, at_mm = [0.0, 0.0, 0.0] }\n", "mass_g", "below the head mass"),
        ("[distribution]\nmethod = \"monte\"\n", "distribution.method", "quadrature"),
        ("[distribution]\nsigma_y_mm = -1.0\n", "distribution.sigma_y_mm", "physical range [0, 100] mm"),
        ("[distribution]\nnodes = 50\n", "distribution.nodes", "1 to 20"),
        ("[distribution]\nsamples = 10\n", "distribution.samples", "quadrature"),
        ("[distribution]\nsigmaz = 1.0\n", "unknown field `sigmaz`", "sigma_z_mm"),
        ("[summary]\nstep_mm = 50.0\n", "summary.step_mm", "half_width_mm"),
        ("[sensitivity]\nvariables = [\"com_dw_mm\"]\n", "sensitivity.variables", "allowed"),
        ("[sensitivity]\nvariables = [\"com_dx_mm\"]\nsteps = { com_dx_mm = -1.0 }\n", "sensitivity.steps.com_dx_mm", "> 0"),
        ("[optimise]\ngoal = \"up\"\nobjective = { cof_ball_speed_mph = 1.0 }\nbounds = { com_dx_mm = [-1.0, 1.0] }\n", "optimise.goal", "maximise"),
        ("[optimise]\ngoal = \"maximise\"\nobjective = { mean_ball_speed_mph = 1.0 }\nbounds = { com_dx_mm = [-1.0, 1.0] }\n", "optimise.objective.mean_ball_speed_mph", "need a [distribution]"),
        ("[optimise]\ngoal = \"maximise\"\nobjective = { cof_ball_speed_mph = 1.0 }\nbounds = { com_dx_mm = [1.0, 2.0] }\n", "optimise.bounds.com_dx_mm", "base value 0"),
        ("[extra]\na = 1\n", "unknown field `extra`", "[study]"),
    ];
    for (extra, a, b) in cases {
        let e = parse(&study_text(extra)).expect_err(extra);
        assert!(e.contains(a) && e.contains(b), "{extra:?} gave: {e}");
        assert!(e.contains("study.toml:"), "no line in: {e}");
    }
    // Replacements in the fixed part.
    let bad = [
        (
            "club_speed_mph = 100.0",
            "club_speed_mph = -3.0",
            "delivery.club_speed_mph",
        ),
        (
            "club_speed_mph = 100.0",
            "club_speed = 100.0",
            "club_speed_mph",
        ),
        ("count = 5", "count = 0", "grid.y_mm.count"),
        (
            "from = -10.0, to = 10.0",
            "from = 10.0, to = -10.0",
            "grid.y_mm",
        ),
        ("name = \"t\"", "name = \"../x\"", "study.name"),
    ];
    for (from, to, key) in bad {
        let e = parse(&study_text("").replace(from, to)).expect_err(to);
        assert!(e.contains(key), "{to:?} gave: {e}");
    }
    // Line numbers point at the key.
    let e = parse(&study_text("[design]\ncom_dx_mm = true\n")).unwrap_err();
    assert!(e.contains("study.toml:13"), "{e}");
}

#[test]
fn invalid_variants_are_reported_with_their_values() {
    let s = parse(&study_text("[design]\niyy_scale = [1.0, 1.5]\n")).unwrap();
    let e = Prepared::new(s).unwrap_err().to_string();
    assert!(
        e.contains("variant 1") && e.contains("iyy_scale = 1.5"),
        "{e}"
    );
    assert!(e.contains("triangle inequality"), "{e}");
    let s = parse(&study_text("[design]\nd_i1_gcm2 = [0.0, -3000.0]\n")).unwrap();
    let e = Prepared::new(s).unwrap_err().to_string();
    assert!(
        e.contains("d_i1_gcm2 = -3000") && e.contains("positive definite"),
        "{e}"
    );
}

#[test]
fn resolved_study_reparses_to_itself() {
    let s = parse(&study_text(
        "[distribution]\nmethod = \"samples\"\nsigma_z_mm = 5.0\n[design]\ncom_dx_mm = { from = -2.0, to = 2.0, step = 1.0 }\ndiscretionary_mass = { mass_g = 8.0, at_mm = [-60.0, 0.0, 0.0] }\n[sensitivity]\n[optimise]\ngoal = \"minimise\"\nobjective = { std_sidespin_rpm = 1.0 }\nbounds = { mass_dz_mm = [-10.0, 10.0] }\n",
    ))
    .unwrap();
    let t = resolved_toml(&s);
    assert!(
        t.contains("count = 5")
            && t.contains("seed = 1")
            && t.contains("[sensitivity.steps]\ncom_dx_mm = 0.5"),
        "{t}"
    );
    let again = parse_study(Path::new("/elsewhere/study.toml"), &t).unwrap();
    assert_eq!(resolved_toml(&again), t);
}

#[test]
fn face_map_from_smash_run_equals_the_impact_solve_and_marks_off_face_points() {
    let dir = tempfile::tempdir().unwrap();
    // Rows at ±320 mm lie outside the 305 mm roll torus.
    let text = study_text("").replace(
        "y_mm = { from = -10.0, to = 10.0, count = 5 }",
        "y_mm = [-320.0, -12.5, 0.0, 7.0, 320.0]",
    );
    let study = dir.path().join("s.toml");
    std::fs::write(&study, text).unwrap();
    let out = dir.path().join("out");
    let st = smash()
        .arg("run")
        .arg(&study)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        st.status.success(),
        "{}",
        String::from_utf8_lossy(&st.stderr)
    );
    let stderr = String::from_utf8_lossy(&st.stderr);
    assert!(
        stderr.contains("impact evaluations") && stderr.contains("impacts/s"),
        "{stderr}"
    );

    let (h, rows) = read_csv(&out.join("maps_long.csv"));
    let col = |n: &str| h.iter().position(|x| x == n).unwrap();
    let model = base_model();
    let mut valid = 0;
    for r in &rows {
        let (y, z): (f64, f64) = (
            r[col("y_mm")].parse().unwrap(),
            r[col("z_mm")].parse().unwrap(),
        );
        if y.abs() > 300.0 {
            assert_eq!(r[col("valid")], "0");
            for c in LaunchComponent::ALL {
                assert_eq!(r[col(c.column())], "", "off-face cell must be empty");
            }
            assert_eq!(r[col("smash_factor")], "");
            continue;
        }
        valid += 1;
        assert_eq!(r[col("valid")], "1");
        let o = model.solve(&delivery(y, z)).unwrap();
        let l = o.launch();
        for c in LaunchComponent::ALL {
            let got: f64 = r[col(c.column())].parse().unwrap();
            let want = l.get_file(c);
            assert!(
                (got - want).abs() <= 1e-9 * want.abs().max(1.0),
                "{c:?} at ({y}, {z}): {got} vs {want}"
            );
        }
        // Map values are written to ten significant digits (5e-10 relative at most).
        let sf: f64 = r[col("smash_factor")].parse().unwrap();
        assert!((sf - o.smash_factor()).abs() <= 5.000_001e-10 * o.smash_factor());
    }
    assert_eq!(valid, 3 * 9);
    // Matrix CSV: top row (y = 320) first, all empty; SVG has the grey no-value key. No NaN anywhere.
    let m = std::fs::read_to_string(out.join("maps/v000_ball_speed_mph.csv")).unwrap();
    let second = m.lines().nth(1).unwrap();
    assert!(
        second.starts_with("320,") && second.trim_start_matches("320").chars().all(|c| c == ','),
        "{second}"
    );
    for (p, bytes) in tree(&out) {
        let t = String::from_utf8(bytes).unwrap().to_lowercase();
        assert!(
            !t.contains("nan") && !t.contains("inf"),
            "{} has NaN/inf",
            p.display()
        );
    }
    assert!(
        std::fs::read_to_string(out.join("maps/v000_sidespin_rpm.svg"))
            .unwrap()
            .contains("no value")
    );
}

/// Independent model with the CoM moved and the inertia transformed by hand.
fn model_with(com_dx_mm: f64, iyy_scale: f64) -> ImpactModel {
    let club = read_club(&root().join("configs/clubs/paper_driver.toml")).unwrap();
    let mut p: ModelParams = club.nominal.clone();
    p.club_com_m.x += com_dx_mm * 1e-3;
    let s = iyy_scale.sqrt();
    let d = Matrix3::from_diagonal(&Vector3::new(1.0, s, 1.0));
    p.club_inertia_kgm2 = d * p.club_inertia_kgm2 * d;
    ImpactModel::new(p).unwrap()
}

#[test]
fn sensitivities_match_independent_finite_differences() {
    let s = parse(&study_text(
        "[distribution]\nimpact_centre_mm = [0.0, 15.0]\nsigma_y_mm = 3.0\nsigma_z_mm = 3.0\nnodes = 4\n[sensitivity]\nvariables = [\"com_dx_mm\", \"iyy_scale\"]\n",
    ))
    .unwrap();
    let p = Prepared::new(s).unwrap();
    let sens = sensitivities(&p).unwrap();
    let names = metric_names(true);
    let idx = |n: &str| names.iter().position(|m| m == n).unwrap();
    let speed = |m: &ImpactModel, y: f64, z: f64| {
        m.solve(&delivery(y, z))
            .unwrap()
            .launch()
            .get_file(LaunchComponent::BallSpeed)
    };
    let side = |m: &ImpactModel, y: f64, z: f64| {
        m.solve(&delivery(y, z))
            .unwrap()
            .launch()
            .get_file(LaunchComponent::Sidespin)
    };

    // d(ball speed at CoF)/d(com_dx), mph/mm, with a different step (forward-backward, 0.05 mm).
    let h = 0.05;
    let fd =
        (speed(&model_with(h, 1.0), 0.0, 0.0) - speed(&model_with(-h, 1.0), 0.0, 0.0)) / (2.0 * h);
    let got = sens[0].metrics[idx("cof_ball_speed_mph")];
    assert!(
        (got - fd).abs() <= 1e-4 * fd.abs().max(1e-3),
        "{got} vs {fd}"
    );

    // d(mean sidespin over a toe strike pattern)/d(iyy_scale): independent quadrature by hand.
    let (x, w) = smash::study::distribution::gauss_hermite(4);
    let mean_side = |m: &ImpactModel| {
        let mut s = 0.0;
        for (xi, wi) in x.iter().zip(&w) {
            for (xj, wj) in x.iter().zip(&w) {
                s += wi * wj * side(m, 3.0 * xi, 15.0 + 3.0 * xj);
            }
        }
        s
    };
    let h = 0.002;
    let fd =
        (mean_side(&model_with(0.0, 1.0 + h)) - mean_side(&model_with(0.0, 1.0 - h))) / (2.0 * h);
    let got = sens[1].metrics[idx("mean_sidespin_rpm")];
    assert!((got - fd).abs() <= 1e-3 * fd.abs(), "{got} vs {fd}");
    assert!(
        fd.abs() > 1.0,
        "a stiffer heel-toe MOI changes toe-strike sidespin: {fd}"
    );

    // A map cell: d(sidespin at (y = 5, z = 20))/d(com_dx).
    let nz = p.zs_mm.len();
    let (iy, iz) = (
        p.ys_mm.iter().position(|y| *y == 5.0).unwrap(),
        p.zs_mm.iter().position(|z| *z == 20.0).unwrap(),
    );
    let h = 0.05;
    let fd =
        (side(&model_with(h, 1.0), 5.0, 20.0) - side(&model_with(-h, 1.0), 5.0, 20.0)) / (2.0 * h);
    let got = sens[0].maps(&p)[4][iy * nz + iz];
    assert!((got - fd).abs() <= 1e-4 * fd.abs(), "{got} vs {fd}");
}

#[test]
fn gear_effect_hooks_toe_strikes_and_speed_falls_off_centre() {
    // The paper driver's CoM is 42.3 mm behind the face (com_mm x < 0). A toe strike turns the
    // head open about its CoM; the gear effect then spins the ball the other way: hook spin,
    // which is negative sidespin in the signs of docs/conventions.md (+ = slice). Heel strikes slice.
    let model = base_model();
    assert!(model.params().club_com_m.x < 0.0);
    let toe = model.solve(&delivery(0.0, 20.0)).unwrap().launch();
    let heel = model.solve(&delivery(0.0, -20.0)).unwrap().launch();
    assert!(toe.sidespin_rad_s < 0.0 && heel.sidespin_rad_s > 0.0);
    // High strikes spin less (vertical gear effect).
    let high = model.solve(&delivery(10.0, 0.0)).unwrap().launch();
    let low = model.solve(&delivery(-10.0, 0.0)).unwrap().launch();
    assert!(high.backspin_rad_s < low.backspin_rad_s);

    let p = Prepared::new(parse(&study_text("")).unwrap()).unwrap();
    let m = smash::study::evaluate::evaluate(&p.models[0], &p.study, &p.groups);
    let names = metric_names(false);
    let get = |n: &str| m[names.iter().position(|x| x == n).unwrap()];
    assert!(get("gear_sidespin_rpm_per_mm") < 0.0);
    assert!(get("gear_backspin_rpm_per_mm") < 0.0);
    for side in ["toe", "heel", "crown", "sole"] {
        let v = get(&format!("speed_loss_{side}_mph_per_mm"));
        assert!(v > 0.0, "speed loss toward the {side}: {v}");
    }
    // A CoM further back strengthens the gear effect.
    let p =
        Prepared::new(parse(&study_text("[design]\ncom_dx_mm = [-10.0, 0.0]\n")).unwrap()).unwrap();
    let back = smash::study::evaluate::evaluate(&p.models[0], &p.study, &p.groups);
    let i = names
        .iter()
        .position(|x| x == "gear_sidespin_rpm_per_mm")
        .unwrap();
    assert!(back[i] < get("gear_sidespin_rpm_per_mm"));
}

#[test]
fn optimiser_beats_the_base_within_bounds_at_constant_mass() {
    let p = Prepared::new(
        smash::study::read_study(&root().join("configs/studies/optimise.toml")).unwrap(),
    )
    .unwrap();
    let spec = p.study.optimise.clone().unwrap();
    let o = optimise(&p).unwrap().unwrap();
    assert!(
        o.best_objective > o.base_objective + 0.05,
        "{} vs {}",
        o.best_objective,
        o.base_objective
    );
    for (v, lo, hi) in &spec.bounds {
        let x = o.best.get(*v);
        assert!(
            *lo <= x && x <= *hi,
            "{} = {x} outside [{lo}, {hi}]",
            v.key()
        );
        for pt in &o.path {
            assert!(*lo <= pt.design.get(*v) && pt.design.get(*v) <= *hi);
        }
    }
    // The path's best objective never gets worse.
    for w in o.path.windows(2) {
        assert!(w[1].objective >= w[0].objective - 1e-12);
    }
    // Mass constraint: the total is unchanged and the CoM moved by m_d·Δ/M.
    let base = &p.study.club.nominal;
    let md = p.study.design.discretionary_mass.unwrap();
    let best = o.best.apply(base, Some(&md)).unwrap();
    assert_eq!(best.club_mass_kg, base.club_mass_kg);
    let delta = Vector3::new(o.best.values[0], o.best.values[1], o.best.values[2]) * 1e-3;
    let shift = best.club_com_m - base.club_com_m;
    assert!((shift - delta * (md.mass_kg / base.club_mass_kg)).norm() < 1e-15);
    // The reported optimum objective is what an independent evaluation gives.
    let model = smash::study::sweep::design_model(&p.study, &o.best).unwrap();
    let m = smash::study::evaluate::evaluate(&model, &p.study, &p.groups);
    assert_eq!(m, o.best_metrics);
}

fn run_ok(args: &[&std::ffi::OsStr]) -> String {
    let o = smash().args(args).output().unwrap();
    assert!(
        o.status.success(),
        "smash {:?}: {}",
        args,
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8_lossy(&o.stdout).into_owned()
}

#[test]
fn shard_merge_equals_the_unsharded_run_byte_for_byte() {
    let dir = tempfile::tempdir().unwrap();
    let study = dir.path().join("s.toml");
    std::fs::write(
        &study,
        study_text(
            "[distribution]\nsigma_z_mm = 6.0\nnodes = 3\n[design]\ncom_dy_mm = [-2.0, 2.0]\ninertia_scale = [0.95, 1.0, 1.05]\n[sensitivity]\nvariables = [\"com_dz_mm\"]\n",
        ),
    )
    .unwrap();
    let full = dir.path().join("full");
    run_ok(&[
        "run".as_ref(),
        study.as_os_str(),
        "--out".as_ref(),
        full.as_os_str(),
    ]);
    let expected = tree(&full);
    assert!(expected.len() > 20);
    for n in [1usize, 3, 7] {
        let mut shard_dirs = Vec::new();
        // Shards in reverse order, to show order does not matter.
        for k in (0..n).rev() {
            let d = dir.path().join(format!("n{n}_k{k}"));
            let spec = format!("{k}/{n}");
            run_ok(&[
                "run".as_ref(),
                study.as_os_str(),
                "--shard".as_ref(),
                spec.as_ref(),
                "--out".as_ref(),
                d.as_os_str(),
            ]);
            shard_dirs.push(d);
        }
        let merged = dir.path().join(format!("merged{n}"));
        let mut args: Vec<&std::ffi::OsStr> = vec!["merge".as_ref()];
        args.extend(shard_dirs.iter().map(|d| d.as_os_str()));
        args.extend(["--out".as_ref(), merged.as_os_str()]);
        run_ok(&args);
        let got = tree(&merged);
        assert_eq!(
            got.keys().collect::<Vec<_>>(),
            expected.keys().collect::<Vec<_>>(),
            "N = {n}"
        );
        for (k, v) in &expected {
            assert!(got[k] == *v, "N = {n}: {} differs", k.display());
        }
        if n == 3 {
            // A missing shard is an error naming it.
            let o = smash()
                .arg("merge")
                .arg(&shard_dirs[0])
                .arg(&shard_dirs[2])
                .arg("--out")
                .arg(dir.path().join("bad"))
                .output()
                .unwrap();
            assert!(!o.status.success());
            assert!(String::from_utf8_lossy(&o.stderr).contains("shards 1 of 3 are missing"));
            assert!(!dir.path().join("bad").exists());
        }
    }
}

#[test]
fn shipped_studies_run_end_to_end_and_reproduce_from_their_resolved_study() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["face_map", "com_sweep", "optimise"] {
        let out = dir.path().join(name);
        let cfg = root().join(format!("configs/studies/{name}.toml"));
        let stdout = run_ok(&[
            "run".as_ref(),
            cfg.as_os_str(),
            "--out".as_ref(),
            out.as_os_str(),
        ]);
        let files = tree(&out);
        for f in [
            "study.toml",
            "variants.csv",
            "maps_long.csv",
            "maps/v000_ball_speed_mph.csv",
            "maps/v000_ball_speed_mph.svg",
        ] {
            assert!(files.contains_key(Path::new(f)), "{name}: no {f}");
        }
        let svg =
            String::from_utf8(files[Path::new("maps/v000_ball_speed_mph.svg")].clone()).unwrap();
        assert!(
            svg.contains("ball speed, mph")
                && svg.contains("<circle")
                && svg.contains("toward toe), mm")
        );
        match name {
            "com_sweep" => {
                assert!(files.contains_key(Path::new("sensitivity.csv")));
                assert!(
                    files.contains_key(Path::new("sensitivity/d_ball_speed_mph__d_com_dx_mm.svg"))
                );
                assert!(files.contains_key(Path::new("maps/v017_sidespin_rpm.csv")));
            }
            "optimise" => {
                assert!(stdout.contains("optimum:"), "{stdout}");
                let (h, rows) = read_csv(&out.join("optimise/result.csv"));
                assert_eq!(h[0], "quantity");
                let obj = rows.iter().find(|r| r[0] == "objective").unwrap();
                assert!(obj[3].parse::<f64>().unwrap() > obj[2].parse::<f64>().unwrap());
                let mass = rows.iter().find(|r| r[0] == "club_mass_g").unwrap();
                assert_eq!(mass[2], mass[3]);
                let club = read_club(&out.join("optimise/optimum_club.toml")).unwrap();
                assert!((club.nominal.club_mass_kg - 0.204).abs() < 1e-15);
                let (ph, path) = read_csv(&out.join("optimise/path.csv"));
                assert_eq!(&ph[..2], ["iteration", "objective"]);
                assert!(path.len() > 5);
            }
            _ => {}
        }
        // The resolved study repeats the run exactly.
        let again = dir.path().join(format!("{name}_again"));
        run_ok(&[
            "run".as_ref(),
            out.join("study.toml").as_os_str(),
            "--out".as_ref(),
            again.as_os_str(),
        ]);
        assert!(
            tree(&again) == files,
            "{name}: rerun from study.toml differs"
        );
    }
}

#[test]
fn a_failing_run_leaves_no_output_file() {
    let dir = tempfile::tempdir().unwrap();
    for (i, extra) in [
        "[design]\niyy_scale = [1.0, 2.5]\n",
        "[design]\ncom_dx_mm = [0.0]\nbogus = 1\n",
    ]
    .iter()
    .enumerate()
    {
        let study = dir.path().join(format!("bad{i}.toml"));
        std::fs::write(&study, study_text(extra)).unwrap();
        let out = dir.path().join(format!("out{i}"));
        let o = smash()
            .arg("run")
            .arg(&study)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        assert!(!o.status.success());
        let e = String::from_utf8_lossy(&o.stderr);
        assert!(e.starts_with("error: ") && e.lines().count() == 1, "{e}");
        assert!(!out.exists(), "a failed run created {}", out.display());
    }
    // Bad shard specs are refused before anything runs.
    let study = dir.path().join("ok.toml");
    std::fs::write(&study, study_text("")).unwrap();
    for spec in ["3/3", "a/2", "1"] {
        let o = smash()
            .arg("run")
            .arg(&study)
            .arg("--shard")
            .arg(spec)
            .arg("--out")
            .arg(dir.path().join("s"))
            .output()
            .unwrap();
        assert!(!o.status.success(), "{spec}");
        assert!(!dir.path().join("s").exists());
    }
}

#[test]
fn parquet_long_table_reads_back_to_the_csv_numbers() {
    use parquet::file::reader::SerializedFileReader;
    use parquet::record::Field;

    let dir = tempfile::tempdir().unwrap();
    let study = dir.path().join("s.toml");
    // A grid reaching off the face (invalid cells), two design variables, four outputs.
    let text = study_text("[design]\ncom_dy_mm = [-2.0, 2.0]\ninertia_scale = [0.95, 1.05]\n")
        .replace(
            "y_mm = { from = -10.0, to = 10.0, count = 5 }",
            "y_mm = [-320.0, -30.0, -20.0, -12.5, -5.0, 0.0, 5.0, 12.5, 20.0, 30.0, 320.0]",
        )
        .replace(
            "[delivery]",
            "outputs = [\"ball_speed_mph\", \"launch_angle_deg\", \"sidespin_rpm\", \"smash_factor\"]\n\n[delivery]",
        );
    std::fs::write(&study, text).unwrap();
    let (csv_dir, pq_dir) = (dir.path().join("csv"), dir.path().join("pq"));
    for (out, format) in [(&csv_dir, "csv"), (&pq_dir, "parquet")] {
        run_ok(&[
            "run".as_ref(),
            study.as_os_str(),
            "--out".as_ref(),
            out.as_os_str(),
            "--format".as_ref(),
            format.as_ref(),
        ]);
    }
    // Everything but the long table is the same file.
    let (mut a, mut b) = (tree(&csv_dir), tree(&pq_dir));
    let csv_long = a
        .remove(Path::new("maps_long.csv"))
        .expect("csv long table");
    assert!(b.remove(Path::new("maps_long.parquet")).is_some());
    // The manifests of what smash wrote differ by that one file name.
    assert!(a.remove(Path::new(".smash-outputs")).is_some());
    assert!(b.remove(Path::new(".smash-outputs")).is_some());
    assert_eq!(a, b);

    let (header, rows) = read_csv(&csv_dir.join("maps_long.csv"));
    assert!(!csv_long.is_empty());
    let outputs = [
        "ball_speed_mph",
        "launch_angle_deg",
        "sidespin_rpm",
        "smash_factor",
    ];
    let file = std::fs::File::open(pq_dir.join("maps_long.parquet")).unwrap();
    let reader = SerializedFileReader::new(file).unwrap();
    let mut n = 0;
    let mut invalid = 0;
    for (row, csv) in reader.into_iter().zip(&rows) {
        let row = row.unwrap();
        let cols: Vec<(&String, &Field)> = row.get_column_iter().collect();
        assert_eq!(cols.len(), header.len());
        for ((name, field), (h, cell)) in cols.iter().zip(header.iter().zip(csv)) {
            assert_eq!(*name, h);
            match field {
                Field::Int(i) => assert_eq!(i.to_string(), *cell),
                Field::Bool(v) => assert_eq!(if *v { "1" } else { "0" }, cell),
                // Coordinates and design values are exact in both; output values are exact
                // doubles in Parquet and rounded to ten significant digits in the CSV.
                Field::Double(x) if outputs.contains(&h.as_str()) => {
                    let ten: f64 = format!("{x:.9e}").parse().unwrap();
                    assert_eq!(format!("{ten}"), *cell, "{h}");
                    assert!((cell.parse::<f64>().unwrap() - x).abs() <= 5.000_001e-10 * x.abs());
                }
                Field::Double(x) => {
                    assert_eq!(x.to_bits(), cell.parse::<f64>().unwrap().to_bits(), "{h}")
                }
                Field::Null => {
                    assert!(cell.is_empty(), "{h}: null vs '{cell}'");
                    invalid += 1;
                }
                other => panic!("unexpected field {other:?} in {h}"),
            }
        }
        n += 1;
    }
    assert_eq!(n, rows.len());
    assert_eq!(n, 4 * 11 * 9);
    assert!(invalid > 0, "rows at ±320 mm lie off the face");
}

#[test]
fn a_shard_too_large_to_hold_is_refused_with_the_shard_count_that_fits() {
    let dir = tempfile::tempdir().unwrap();
    let study = dir.path().join("s.toml");
    let text = study_text("")
        .replace(
            "y_mm = { from = -10.0, to = 10.0, count = 5 }",
            "y_mm = { from = -10.0, to = 10.0, count = 3000 }",
        )
        .replace(
            "z_mm = { from = -20.0, to = 20.0, count = 9 }",
            "z_mm = { from = -20.0, to = 20.0, count = 3000 }",
        );
    std::fs::write(&study, text).unwrap();
    let o = smash()
        .args([
            "run".as_ref(),
            study.as_os_str(),
            "--shard".as_ref(),
            "0/1".as_ref(),
        ])
        .args(["--out".as_ref(), dir.path().join("shard").as_os_str()])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(err.contains("use at least 2 shards"), "{err}");
    assert!(!dir.path().join("shard").exists());
}
