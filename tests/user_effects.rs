//! User-defined effects (`[[define_effect]]`) in the library: the same compiled expression on the
//! scalar solve and the kernel's lanes (1e-12 with every library effect and every settable
//! quantity on); a user-written `cor_power2` equal to the library's `cor_power` bit for bit and
//! in a fit; recovery of `cor_power` from a synthetic world as either; a calibrated club carrying
//! its definitions; every class of definition error as one line; a value out of range at
//! evaluation named; allocation-free evaluation (a counting allocator). The commands:
//! `cli/tests/cli_user_effects.rs`.

mod common;

use std::cell::Cell;
use std::path::{Path, PathBuf};

use smash::data::effect_defs::parse_effect_defs;
use smash::effects::user::UserEffect;
use smash::effects::{Effect, EffectId, EffectKind};
use smash::fit::{calibrate, parse_effect_list, CalibrateOptions};
use smash::physics::{ImpactModel, ModelParams};
use smash::sweep::face_map;
use smash::{Delivery, LaunchComponent};

// ---------------------------------------------------------------------------------------------
// A counting allocator: allocations made by this thread (tests run on several threads).

struct Counting;

thread_local! {
    static ALLOCS: Cell<usize> = const { Cell::new(0) };
}

unsafe impl std::alloc::GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: std::alloc::Layout) -> *mut u8 {
        let _ = ALLOCS.try_with(|c| c.set(c.get() + 1));
        unsafe { std::alloc::System.alloc(l) }
    }
    unsafe fn dealloc(&self, p: *mut u8, l: std::alloc::Layout) {
        unsafe { std::alloc::System.dealloc(p, l) }
    }
    unsafe fn realloc(&self, p: *mut u8, l: std::alloc::Layout, n: usize) -> *mut u8 {
        let _ = ALLOCS.try_with(|c| c.set(c.get() + 1));
        unsafe { std::alloc::System.realloc(p, l, n) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn allocations() -> usize {
    ALLOCS.with(Cell::get)
}

// ---------------------------------------------------------------------------------------------

fn repo(p: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(p)
}

fn example_defs() -> PathBuf {
    repo("configs/effects/example_effects.toml")
}

fn load_examples() {
    smash::data::effect_defs::read_effect_defs(&example_defs()).expect("example effects load");
}

fn user(name: &str) -> EffectId {
    EffectId::from_name(name).expect("registered")
}

fn define(text: &str) -> Vec<&'static UserEffect> {
    parse_effect_defs(Path::new("test_effects.toml"), text).expect("definitions load")
}

const EVERY_QUANTITY: &str = r#"
[[define_effect]]
name = "sink_all"
doc = "every settable quantity except mu, with every function"
params = [
  { key = "a", unit = "1", default = 0.0, lower = -1.0, upper = 1.0 },
  { key = "b", unit = "1", default = 0.0, lower = -1.0, upper = 1.0 },
]
cor = "cor * (1 - a * 0.02 * ut_m_s / 10) - 0.01 * b * (impact_y_mm ^ 2 + impact_z_mm ^ 2) / 100"
et = "min(et + 0.1 * a * exp(-u1n_m_s / 50), ln(2))"
club_mass_g = "club_mass_g + 3 * a + 0.05 * b * (shaft_mass_g - 65)"
ball_dy_mm = "ball_dy_mm + 0.3 * b + 0.02 * a * impact_y_mm"
ball_dz_mm = "ball_dz_mm - 0.1 * a"
com_dx_mm = "com_dx_mm + a * (club_speed_mph - 100) / 20"
com_dy_mm = "1.5 * b + club_omega_z_rad_s / 100"
com_dz_mm = "-b"
inertia_scale = "inertia_scale * (1 + 0.05 * a)"
loft_deg = "loft_deg + a * 0.5 + lie_tilt_deg / 10 - 0.03 * b * impact_z_mm"
face_deg = "face_deg - b * 0.3 + 0.01 * max(attack_angle_deg, club_path_deg) + dynamic_loft_deg / 1000 - face_angle_deg / 1000"

[[define_effect]]
name = "sink_fixed"
doc = "mass and geometry that depend on the delivery only (the kernel's precomputed path)"
params = [{ key = "a", unit = "1", default = 0.0, lower = -1.0, upper = 1.0 }]
cor = "cor * (1 - a * 0.02 * ut_m_s / 10)"
club_mass_g = "club_mass_g + 3 * a + 0.1 * (shaft_mass_g - 65)"
com_dy_mm = "com_dy_mm + 1.5 * a + club_omega_z_rad_s / 100"
inertia_scale = "inertia_scale * (1 + 0.05 * a)"
loft_deg = "loft_deg + a * 0.5"

[[define_effect]]
name = "sink_mu"
doc = "friction rising with the tangential speed"
params = [{ key = "c", unit = "1", default = 0.3, lower = 0.01, upper = 1.0 }]
mu = "c + 0.01 * sqrt(ut_m_s)"
"#;

/// The test deliveries, with shaft masses (some unknown: the default applies).
fn deliveries_with_shafts() -> Vec<Delivery> {
    let mut ds = common::deliveries();
    for (i, d) in ds.iter_mut().enumerate() {
        d.shaft_mass_g = [None, Some(52.0), Some(74.5), Some(81.0)][i % 4];
    }
    ds
}

#[test]
fn kernel_matches_the_scalar_solve_with_every_library_and_user_effect_on() {
    define(EVERY_QUANTITY);
    let sink_mu = user("sink_mu");
    // sink_all's mass and geometry read the impact location (a kernel per point), sink_fixed's
    // do not (computed once per delivery).
    for (sink, friction) in [
        ("sink_all", false),
        ("sink_all", true),
        ("sink_fixed", false),
        ("sink_fixed", true),
    ] {
        let sink = user(sink);
        let mut p = ModelParams::paper_driver();
        for kind in EffectKind::ALL {
            if kind == EffectKind::Friction && !friction {
                continue;
            }
            kind.apply(&common::active_values(kind.params()), &mut p);
        }
        sink.apply(&[0.6, -0.4][..sink.params().len()], &mut p);
        if friction {
            sink_mu.apply(&[0.05], &mut p);
        }
        let model = ImpactModel::new(p).unwrap();
        let ys: Vec<f64> = (0..13).map(|i| (-24.0 + 4.0 * i as f64) * 1e-3).collect();
        let zs: Vec<f64> = (0..21).map(|i| (-40.0 + 4.0 * i as f64) * 1e-3).collect();
        let mut valid = 0;
        let mut slipped = 0;
        for d0 in deliveries_with_shafts() {
            let grid = face_map(&model, &d0, &ys, &zs);
            for (iy, &y) in ys.iter().enumerate() {
                for (iz, &z) in zs.iter().enumerate() {
                    let k = iy * zs.len() + iz;
                    let d = Delivery {
                        impact_y_m: y,
                        impact_z_m: z,
                        ..d0
                    };
                    match model.solve(&d) {
                        Ok(o) => {
                            assert!(grid.valid[k], "solve ok, kernel invalid at ({y}, {z})");
                            valid += 1;
                            slipped += o.slipped as usize;
                            let l = o.launch();
                            for c in LaunchComponent::ALL {
                                let (got, want) = (grid.component(c)[k], l.get_si(c));
                                let dev = (got - want).abs();
                                assert!(
                                    dev <= 1e-12 * want.abs() || dev <= 1e-9,
                                    "{c:?} at ({y}, {z}): kernel {got} vs solve {want}"
                                );
                            }
                        }
                        Err(_) => assert!(!grid.valid[k]),
                    }
                }
            }
        }
        assert!(valid > 1000, "{valid} valid points");
        if friction {
            assert!(slipped > 0, "the user-defined mu never limited friction");
        }
        // The user terms do something: the same model without them differs.
        let mut q = ModelParams::paper_driver();
        for kind in EffectKind::ALL {
            if kind == EffectKind::Friction && !friction {
                continue;
            }
            kind.apply(&common::active_values(kind.params()), &mut q);
        }
        let plain = ImpactModel::new(q).unwrap();
        let d = common::deliveries()[5];
        let (a, b) = (
            model.solve(&d).unwrap().launch(),
            plain.solve(&d).unwrap().launch(),
        );
        assert!(
            (a.get_file(LaunchComponent::Backspin) - b.get_file(LaunchComponent::Backspin)).abs()
                > 10.0
        );
    }
}

#[test]
fn cor_power2_predicts_exactly_as_the_library_cor_power() {
    load_examples();
    let cp2 = user("cor_power2");
    for q in [0.0, 0.07, 0.15, 0.4] {
        let mut a = ModelParams::paper_driver();
        EffectKind::CorPower.apply(&[q], &mut a);
        let mut b = ModelParams::paper_driver();
        cp2.apply(&[q], &mut b);
        let (a, b) = (ImpactModel::new(a).unwrap(), ImpactModel::new(b).unwrap());
        for d in common::deliveries() {
            let (oa, ob) = (a.solve(&d).unwrap(), b.solve(&d).unwrap());
            assert_eq!(oa.cor_effective.to_bits(), ob.cor_effective.to_bits());
            assert_eq!(oa.ball_velocity_m_s, ob.ball_velocity_m_s);
            assert_eq!(oa.ball_spin_rad_s, ob.ball_spin_rad_s);
            // And on the kernel's lanes.
            let ys = [-0.01, 0.0, 0.012];
            let zs = [-0.02, -0.005, 0.0, 0.007, 0.015, 0.03];
            let (ga, gb) = (face_map(&a, &d, &ys, &zs), face_map(&b, &d, &ys, &zs));
            for c in LaunchComponent::ALL {
                let bits = |g: &smash::sweep::LaunchGrid| {
                    g.component(c)
                        .iter()
                        .map(|v| v.to_bits())
                        .collect::<Vec<_>>()
                };
                assert_eq!(bits(&ga), bits(&gb), "{c:?} at q = {q}");
            }
        }
    }
}

#[test]
fn cor_power_hidden_in_a_synth_world_is_recovered_as_user_and_library_effect() {
    load_examples();
    let path = repo("configs/synth/cor_power_world.toml");
    let cfg = smash::synth::read_config(&path).unwrap();
    assert_eq!(cfg.hidden[0].kind(), EffectKind::CorPower);
    let q = cfg.hidden[0].values()[0];
    let run = smash::synth::generate(&cfg, &common::paper_club()).unwrap();
    let shots: Vec<_> = run.shots.iter().map(|s| s.to_shot()).collect();
    let mut fitted = Vec::new();
    for request in ["cor_power", "cor_power2"] {
        let cal = calibrate(
            &common::paper_club(),
            &shots,
            &parse_effect_list(request).unwrap(),
            &CalibrateOptions::default(),
            None,
        )
        .unwrap();
        let p = &cal.params[0];
        let se = p.stderr.expect("identifiable");
        eprintln!("{request}: q = {:.5} ± {:.5} (truth {q})", p.value, se);
        assert!(
            (p.value - q).abs() < 2.0 * se,
            "{request}: {} ± {se} vs truth {q}",
            p.value
        );
        assert!(se < 0.2 * q, "{request}: standard error {se}");
        assert!(cal.chi2_before - cal.chi2 > 25.0);
        fitted.push((p.value, se, cal.chi2));
    }
    // The same physics: the same fit.
    let ((a, sa, ca), (b, sb, cb)) = (fitted[0], fitted[1]);
    assert!((a - b).abs() <= 1e-9 * a.abs(), "{a} vs {b}");
    assert!((sa - sb).abs() <= 1e-6 * sa, "{sa} vs {sb}");
    assert!((ca - cb).abs() <= 1e-9 * ca, "{ca} vs {cb}");
}

#[test]
fn a_calibrated_club_carries_its_definitions_and_reads_back_alone() {
    load_examples();
    let club = common::paper_club()
        .with_effects(vec![
            Effect::new(user("cor_oblique"), &[0.002], None).unwrap(),
            Effect::new(EffectKind::AddedMass, &[2.0], Some("A".into())).unwrap(),
            Effect::new(user("speed_loft"), &[0.4], Some("B".into())).unwrap(),
        ])
        .unwrap();
    let text = smash::data::club_file::club_toml(&club, "test");
    assert_eq!(text.matches("[[define_effect]]").count(), 2, "{text}");
    let back = smash::data::club_file::parse_club(Path::new("back.toml"), &text).unwrap();
    assert_eq!(back.effects, club.effects);
    let d = common::deliveries()[3];
    for g in ["A", "B"] {
        let (x, y) = (
            club.model_for_group(g).unwrap().solve(&d).unwrap(),
            back.model_for_group(g).unwrap().solve(&d).unwrap(),
        );
        // The file's numbers read back to within an ulp or two.
        assert!(
            (x.ball_velocity_m_s - y.ball_velocity_m_s).norm()
                <= 1e-12 * x.ball_velocity_m_s.norm()
        );
    }
    // Without the definitions a club file naming them would not read; with them in the file
    // it does (checked above), and the definition is the one registered.
    assert!(
        text.contains("cor = \"cor - b_per_m_s * ut_m_s\""),
        "{text}"
    );
}

// ---------------------------------------------------------------------------------------------
// Errors: one line each, naming the file, line, effect, expression and position.

fn def_error(text: &str) -> String {
    let e = parse_effect_defs(Path::new("bad.toml"), text)
        .unwrap_err()
        .to_string();
    assert!(!e.contains('\n'), "one line: {e}");
    assert!(e.starts_with("bad.toml:"), "{e}");
    e
}

const P: &str = r#"params = [{ key = "q", unit = "1", default = 0.0, lower = 0.0, upper = 1.0 }]"#;

#[test]
fn every_error_class_is_one_clear_line() {
    // Parse error: line, file column and character in the expression.
    let e = def_error(&format!(
        "[[define_effect]]\nname = \"e_parse\"\n{P}\ncor = \"cor * (q + \"\n"
    ));
    assert!(
        e.starts_with("bad.toml:4: column 19: key define_effect[0].cor: effect 'e_parse': expression \"cor * (q + \", at character 12: expected a number"),
        "{e}"
    );
    // Unknown name.
    let e = def_error(&format!(
        "[[define_effect]]\nname = \"e_unknown\"\n{P}\ncor = \"cor * qq\"\n"
    ));
    assert!(
        e.contains("unknown name 'qq'") && e.contains("at character 7") && e.contains("u1n_m_s"),
        "{e}"
    );
    // A quantity that may not read a variable.
    let e = def_error(&format!(
        "[[define_effect]]\nname = \"e_var\"\n{P}\nclub_mass_g = \"club_mass_g + q * u1n_m_s\"\n"
    ));
    assert!(
        e.contains("club_mass_g may not use 'u1n_m_s'") && e.contains(":4:"),
        "{e}"
    );
    let e = def_error(&format!(
        "[[define_effect]]\nname = \"e_loc\"\n{P}\nloft_deg = \"loft_deg + q * ut_m_s\"\n"
    ));
    assert!(e.contains("loft_deg may not use 'ut_m_s'"), "{e}");
    // The impact location and the shaft mass are every quantity's to read.
    define(&format!(
        "[[define_effect]]\nname = \"e_loc_ok\"\n{P}\nloft_deg = \"loft_deg + q * impact_y_mm * shaft_mass_g\"\n"
    ));
    // Another quantity is not a variable.
    let e = def_error(&format!(
        "[[define_effect]]\nname = \"e_other\"\n{P}\ncor = \"mu * q\"\n"
    ));
    assert!(e.contains("'mu' is another quantity"), "{e}");
    // Clash with the library.
    let e = def_error(&format!(
        "[[define_effect]]\nname = \"cor_power\"\n{P}\ncor = \"cor\"\n"
    ));
    assert!(
        e.contains("'cor_power' is the name of a library effect") && e.contains(":2:"),
        "{e}"
    );
    // Clash within a file.
    let e = def_error(&format!(
        "[[define_effect]]\nname = \"e_twice\"\n{P}\ncor = \"cor\"\n\n[[define_effect]]\nname = \"e_twice\"\n{P}\ncor = \"cor\"\n"
    ));
    assert!(
        e.contains("'e_twice' is defined twice") && e.contains(":7:"),
        "{e}"
    );
    // Clash with another file's different definition (same definition again is fine).
    let first = format!("[[define_effect]]\nname = \"e_elsewhere\"\n{P}\ncor = \"cor\"\n");
    parse_effect_defs(Path::new("one.toml"), &first).unwrap();
    parse_effect_defs(Path::new("again.toml"), &first).unwrap();
    let e = def_error(&format!(
        "[[define_effect]]\nname = \"e_elsewhere\"\n{P}\ncor = \"cor * q\"\n"
    ));
    assert!(
        e.contains("already defined differently (in one.toml)"),
        "{e}"
    );
    // Bad bounds, default, plausible range, keys.
    let bad = [
        ("lower = 1.0, upper = 0.0", "lower < upper"),
        ("lower = 0.0, upper = inf", "lower < upper"),
        (
            "lower = 0.0, upper = 1.0, plausible = [0.5, 2.0]",
            "plausible",
        ),
    ];
    for (bounds, want) in bad {
        let e = def_error(&format!(
            "[[define_effect]]\nname = \"e_bounds\"\nparams = [{{ key = \"q\", unit = \"1\", default = 0.0, {bounds} }}]\ncor = \"cor\"\n"
        ));
        assert!(e.contains(want) && e.contains("params[0]"), "{bounds}: {e}");
    }
    let e = def_error(
        "[[define_effect]]\nname = \"e_default\"\nparams = [{ key = \"q\", unit = \"1\", default = 2.0, lower = 0.0, upper = 1.0 }]\ncor = \"cor\"\n",
    );
    assert!(e.contains("default = 2 must lie within"), "{e}");
    let e = def_error(
        "[[define_effect]]\nname = \"e_key\"\nparams = [{ key = \"u1n_m_s\", unit = \"m/s\", default = 0.0, lower = 0.0, upper = 1.0 }]\ncor = \"cor\"\n",
    );
    assert!(
        e.contains("clashes with a quantity, variable or function"),
        "{e}"
    );
    // Nothing set; unknown key.
    let e = def_error(&format!("[[define_effect]]\nname = \"e_none\"\n{P}\n"));
    assert!(e.contains("sets no quantity"), "{e}");
    let e = def_error(&format!(
        "[[define_effect]]\nname = \"e_key2\"\n{P}\nspin = \"1\"\n"
    ));
    assert!(e.contains("spin"), "{e}");
}

#[test]
fn a_value_out_of_range_at_evaluation_names_effect_expression_and_shot() {
    define(
        "[[define_effect]]\nname = \"e_nan\"\nparams = []\ncor = \"cor * ln(club_speed_mph - 100)\"\n",
    );
    // Library: the solve says which effect and expression.
    let mut p = ModelParams::paper_driver();
    user("e_nan").apply(&[], &mut p);
    let m = ImpactModel::new(p).unwrap();
    let d = common::deliveries()[0]; // 80 mph: ln of a negative number
    let e = m.solve(&d).unwrap_err().to_string();
    assert!(
        e.contains(
            "user-defined effect 'e_nan': cor = \"cor * ln(club_speed_mph - 100)\" gave no number (an undefined operation: ln or sqrt of a negative"
        ),
        "{e}"
    );
    // The kernel marks such points invalid (NaN there is the documented "invalid" marker).
    let g = face_map(&m, &d, &[0.0], &[0.0, 0.01]);
    assert!(g.valid.iter().all(|v| !v));
}

/// User-defined values are bounded as the library's laws are (`cor` in (0, 1], `et` in
/// [−1, 1]), each term's value checked as it is made, and the kernel's lanes decide exactly as
/// the scalar solve: a COR that rises past 1 toward the toe and falls to 0 toward the heel, a
/// tangential restitution past ±1 high and low on the face, and a COR pushed past 1 by one
/// effect and brought back by the next (refused: the first value is already not physical).
#[test]
fn user_values_outside_the_laws_limits_are_refused_alike_by_solve_and_kernel() {
    define(
        "[[define_effect]]\nname = \"cor_edge\"\nparams = []\ncor = \"cor + impact_z_mm / 20\"\n\
         [[define_effect]]\nname = \"et_edge\"\nparams = []\net = \"impact_y_mm / 10\"\n\
         [[define_effect]]\nname = \"cor_up\"\nparams = []\ncor = \"cor + 0.5\"\n\
         [[define_effect]]\nname = \"cor_down\"\nparams = []\ncor = \"cor - 0.5\"\n",
    );
    let ys: Vec<f64> = (0..9).map(|i| (-20.0 + 5.0 * i as f64) * 1e-3).collect();
    let zs: Vec<f64> = (0..17).map(|i| (-40.0 + 5.0 * i as f64) * 1e-3).collect();
    for (names, want) in [
        (&["cor_edge"][..], "must be in (0, 1]"),
        (&["et_edge"][..], "must be in [-1, 1]"),
        (&["cor_up", "cor_down"][..], "cor = \"cor + 0.5\" gave 1.33"),
    ] {
        let mut p = ModelParams::paper_driver();
        for n in names {
            user(n).apply(&[], &mut p);
        }
        let model = ImpactModel::new(p).unwrap();
        let (mut valid, mut refused) = (0, 0);
        for d0 in common::deliveries() {
            let grid = face_map(&model, &d0, &ys, &zs);
            for (iy, &y) in ys.iter().enumerate() {
                for (iz, &z) in zs.iter().enumerate() {
                    let d = Delivery {
                        impact_y_m: y,
                        impact_z_m: z,
                        ..d0
                    };
                    let solved = model.solve(&d);
                    assert_eq!(
                        grid.valid[iy * zs.len() + iz],
                        solved.is_ok(),
                        "{names:?} at ({y}, {z})"
                    );
                    match solved {
                        Ok(_) => valid += 1,
                        Err(e) if e.to_string().contains(want) => refused += 1,
                        Err(_) => {}
                    }
                }
            }
        }
        assert!(refused > 50, "{names:?}: only {refused} points refused");
        if names.len() == 1 {
            assert!(valid > 50, "{names:?}: only {valid} points valid");
        } else {
            assert_eq!(valid, 0, "{names:?}");
        }
    }
}

#[test]
fn evaluation_allocates_nothing() {
    define(EVERY_QUANTITY);
    let mut p = ModelParams::paper_driver();
    user("sink_all").apply(&[0.5, 0.5], &mut p);
    user("sink_mu").apply(&[0.3], &mut p);
    let m = ImpactModel::new(p).unwrap();
    let ds = common::deliveries();
    let before = allocations();
    let mut sum = 0.0;
    for d in &ds {
        sum += m.solve(d).unwrap().ball_velocity_m_s.x;
    }
    assert_eq!(
        allocations(),
        before,
        "the scalar solve with user effects allocated"
    );
    assert!(sum.is_finite());
    let k = smash::sweep::FaceMapKernel::new(&m, &ds[3]);
    let zs = [0.0, 0.004, 0.008, 0.012, -0.004, -0.008, -0.012, 0.016];
    let mut out = smash::sweep::LaunchGrid::with_len(zs.len());
    let before = allocations();
    k.eval_row(0.002, &zs, out.all_out());
    assert_eq!(
        allocations(),
        before,
        "the kernel's row evaluation allocated"
    );
    // The counter counts (a test that cannot fail is no test).
    let v = vec![1u8; 3];
    assert_eq!(allocations(), before + 1);
    drop(v);
    assert!(out.valid.iter().all(|v| *v));
}

#[test]
fn shaft_mass_reaches_the_scalar_solve_the_kernel_and_a_fit() {
    define(
        r#"
[[define_effect]]
name = "shaft_share"
doc = "a share of the shaft's mass takes part in the impact"
params = [{ key = "k", unit = "1", default = 0.0, lower = 0.0, upper = 0.2 }]
club_mass_g = "club_mass_g + k * shaft_mass_g"
"#,
    );
    let share = user("shaft_share");
    let mut p = ModelParams::paper_driver();
    share.apply(&[0.05], &mut p);
    let m = ImpactModel::new(p).unwrap();
    let d0 = common::deliveries()[4];
    let at = |g: Option<f64>| Delivery {
        shaft_mass_g: g,
        ..d0
    };
    let speed = |g: Option<f64>| m.solve(&at(g)).unwrap().ball_velocity_m_s.norm();
    // A heavier shaft adds mass; an unknown one is the documented default.
    assert!(speed(Some(80.0)) > speed(Some(50.0)));
    let default = smash::physics::user_terms::DEFAULT_SHAFT_MASS_G;
    assert_eq!(speed(None).to_bits(), speed(Some(default)).to_bits());
    // The kernel reads it too.
    for g in [Some(50.0), Some(80.0), None] {
        let grid = face_map(&m, &at(g), &[d0.impact_y_m], &[d0.impact_z_m]);
        let want = m.solve(&at(g)).unwrap().launch().ball_speed_m_s;
        assert!(
            (grid.ball_speed_m_s[0] - want).abs() <= 1e-12 * want,
            "{g:?}"
        );
    }
    // A fit reads each shot's shaft mass: the share is recovered from three shafts' shots.
    let truth = common::truth(vec![Effect::new(share, &[0.04], None).unwrap()]);
    let shots = common::shots(&truth, &common::Experiment::default());
    let cal = calibrate(
        &common::paper_club(),
        &shots,
        &parse_effect_list("shaft_share").unwrap(),
        &CalibrateOptions::default(),
        None,
    )
    .unwrap();
    let (k, se) = (cal.params[0].value, cal.params[0].stderr.unwrap());
    assert!((k - 0.04).abs() < 3.0 * se && se < 0.005, "k = {k} ± {se}");
}

/// Which measured inputs of a synthetic world are noisy.
#[derive(Debug, Clone, Copy, PartialEq)]
enum InputNoise {
    /// Launch only: what the fit's error model assumes.
    LaunchOnly,
    /// Launch and the measured impact location only.
    ImpactLocation,
    /// Launch and every delivery variable, synth's defaults (as the example world).
    Default,
}

/// Standardised errors `(q̂ − q)/SE` of `cor_power` fitted to the `cor_power_world` example
/// made with each seed of `seeds` and the input noise `noise`.
fn cor_power_z_scores(
    seeds: std::ops::RangeInclusive<u64>,
    noise: InputNoise,
    correct_location: bool,
) -> Vec<f64> {
    use smash::model::DeliveryVar;
    let base = smash::synth::read_config(&repo("configs/synth/cor_power_world.toml")).unwrap();
    let q = base.hidden[0].values()[0];
    seeds
        .map(|seed| {
            let mut cfg = base.clone();
            cfg.seed = seed;
            for v in DeliveryVar::ALL {
                let keep = match noise {
                    InputNoise::LaunchOnly => false,
                    InputNoise::ImpactLocation => {
                        matches!(v, DeliveryVar::ImpactY | DeliveryVar::ImpactZ)
                    }
                    InputNoise::Default => true,
                };
                if !keep {
                    cfg.delivery_noise[v.index()] = 0.0;
                }
            }
            let run = smash::synth::generate(&cfg, &common::paper_club()).unwrap();
            let shots: Vec<_> = run.shots.iter().map(|s| s.to_shot()).collect();
            let sigma = |v: DeliveryVar| cfg.delivery_noise[v.index()] * 1e-3;
            let options = CalibrateOptions {
                impact_noise: correct_location.then(|| smash::measurement::ImpactNoise {
                    sigma_y_m: sigma(DeliveryVar::ImpactY),
                    sigma_z_m: sigma(DeliveryVar::ImpactZ),
                }),
                ..CalibrateOptions::default()
            };
            let cal = calibrate(
                &common::paper_club(),
                &shots,
                &parse_effect_list("cor_power").unwrap(),
                &options,
                None,
            )
            .unwrap();
            let p = &cal.params[0];
            let se = p.stderr.expect("identifiable");
            let z = (p.value - q) / se;
            eprintln!(
                "seed {seed:2} ({noise:?}, corrected {correct_location}): q = {:.5} ± {se:.5}, z = {z:+.2}, χ²/dof = {:.3}",
                p.value, cal.reduced_chi2
            );
            z
        })
        .collect()
}

/// Fractions of `z` within 1 and 2 of zero, and the mean.
fn coverage(z: &[f64]) -> (f64, f64, f64) {
    let n = z.len() as f64;
    let within = |k: f64| z.iter().filter(|z| z.abs() < k).count() as f64 / n;
    (within(1.0), within(2.0), z.iter().sum::<f64>() / n)
}

/// Does a fit's 1-SE / 2-SE interval cover the truth as often as it claims (68 % / 95 %)? Over
/// the 20 seeds 1..=20 (every one, none chosen; 600 shots each, as the example world):
///
/// - with noise where the fit's error model puts it (on the launch), it does;
/// - with synth's default noise on the measured delivery too, `q` comes out biased upward by
///   about 1.4 standard errors (errors in the input variables: the model is evaluated at the
///   measured delivery). Most of it is the impact location's noise, which pushes the modelled
///   strikes off-centre where the ball is slower, a deficit the fit makes up with a larger `q`
///   (the world's normal speeds lie below the law's 48.77 m/s reference, where a larger `q`
///   raises the COR). Correcting for it (`--impact-noise-mm`, regression calibration) restores
///   the coverage of a world with noisy locations only, and halves the bias of the default
///   world; the rest comes from the club speed's noise, which the fit does not model
///   (`docs/user-effects.md`, "How far to trust a fitted value").
///
/// Each bound is a 3-sigma binomial or normal band for 20 seeds.
#[test]
fn cor_power_calibration_coverage_over_twenty_seeds() {
    let nominal = |name: &str, z: &[f64]| {
        let (c1, c2, mean) = coverage(z);
        eprintln!("{name}: 1-SE {c1:.2}, 2-SE {c2:.2}, mean z {mean:+.2}");
        assert!(c1 >= 0.4 && c2 >= 0.8, "{name}: coverage {c1} / {c2}");
        assert!(mean.abs() < 0.7, "{name}: mean z {mean}");
    };
    nominal(
        "launch noise only",
        &cor_power_z_scores(1..=20, InputNoise::LaunchOnly, false),
    );
    nominal(
        "noisy impact locations, corrected",
        &cor_power_z_scores(1..=20, InputNoise::ImpactLocation, true),
    );
    let (c1, c2, biased) = coverage(&cor_power_z_scores(1..=20, InputNoise::Default, false));
    eprintln!("default delivery noise: 1-SE {c1:.2}, 2-SE {c2:.2}, mean z {biased:+.2}");
    assert!(biased > 0.7 && biased < 2.5, "mean z {biased}");
    let (c1, c2, corrected) = coverage(&cor_power_z_scores(1..=20, InputNoise::Default, true));
    eprintln!("default delivery noise, locations corrected: 1-SE {c1:.2}, 2-SE {c2:.2}, mean z {corrected:+.2}");
    assert!(
        c2 >= 0.8 && corrected < biased - 0.4,
        "mean z {corrected} vs {biased}"
    );
}

#[test]
fn compare_hints_at_a_hidden_user_effect_from_its_measured_signature() {
    load_examples();
    define(
        r#"
[[define_effect]]
name = "face_turn"
doc = "the face turns by d at impact"
params = [{ key = "d_deg", unit = "deg", default = 0.0, lower = -3.0, upper = 3.0, plausible = [-1.0, 1.0] }]
face_deg = "face_deg + d_deg"
"#,
    );
    let oblique = user("cor_oblique");
    let effects: Vec<&'static UserEffect> = ["cor_oblique", "face_turn", "cor_power2"]
        .iter()
        .map(|n| user(n).user().unwrap())
        .collect();
    let world = |b: f64| {
        common::shots(
            &common::truth(vec![Effect::new(oblique, &[b], None).unwrap()]),
            &common::Experiment::default(),
        )
    };
    // The model of `club` against a world with cor_oblique at b = 0.003: the hints of each
    // ball-speed finding.
    let speed_hints = |club: &smash::club::ClubSpec| -> Vec<Vec<String>> {
        let shots = world(0.003);
        let models = club
            .models_for_groups(shots.iter().map(|s| s.group.as_str()))
            .unwrap();
        let predicted: Vec<_> = shots
            .iter()
            .map(|s| models[&s.group].solve(&s.delivery).unwrap().launch())
            .collect();
        let hints = smash::compare::UserHints::measure(club, &shots, &effects);
        let report = smash::compare::compare_with_hints(
            &shots,
            &predicted,
            &smash::compare::CompareOptions::default(),
            &hints,
        )
        .unwrap();
        report
            .findings
            .iter()
            .filter(|f| f.component == "ball_speed_mph")
            .map(|f| f.hints.clone())
            .collect()
    };
    let named = |h: &[Vec<String>], name: &str| {
        h.iter()
            .flatten()
            .any(|t| t.starts_with(&format!("{name} (user-defined")))
    };
    // The nominal club: ball speed too high, falling with the tangential speed. cor_oblique
    // can lower it (and so can cor_power2); turning the face cannot.
    let h = speed_hints(&common::paper_club());
    assert!(!h.is_empty(), "no ball-speed finding");
    assert!(named(&h, "cor_oblique"), "{h:?}");
    assert!(!named(&h, "face_turn"), "{h:?}");
    // A club that already overdoes it (b = 0.006): ball speed too low, which a larger b
    // (its only way from the default 0) cannot fix.
    let over = common::paper_club()
        .with_effects(vec![Effect::new(oblique, &[0.006], None).unwrap()])
        .unwrap();
    let h = speed_hints(&over);
    assert!(!h.is_empty(), "no ball-speed finding");
    assert!(!named(&h, "cor_oblique"), "{h:?}");
}

// ---------------------------------------------------------------------------------------------
// Offered or world-only: a synth world's hidden definitions are no candidates.

#[test]
fn a_synth_worlds_hidden_definition_is_never_offered_until_an_effects_file_defines_it() {
    let path = repo("configs/synth/twisted_face_world.toml");
    let cfg = smash::synth::read_config(&path).unwrap();
    // The world hides `face_twist`, nameable once its file is read...
    assert!(cfg.hidden.iter().any(|h| h.kind().name() == "face_twist"));
    assert!(EffectId::from_name("face_twist").is_some());
    // ...but a diagnosis or a comparison run after it in the same process is not offered it.
    let labels = |groups: &[String]| -> Vec<String> {
        smash::diagnose::default_candidates(groups)
            .iter()
            .map(|c| c.label())
            .collect()
    };
    let groups = vec!["A".to_owned(), "B".to_owned()];
    assert!(!labels(&groups).iter().any(|l| l == "face_twist"));
    assert!(!smash::effects::user::offered()
        .iter()
        .any(|u| u.name == "face_twist"));
    // A club carrying it, written and read back (the check before a club file is written),
    // does not offer it either.
    let twist = EffectId::from_name("face_twist").unwrap();
    let values: Vec<f64> = twist.params().iter().map(|p| p.default).collect();
    let club = common::paper_club()
        .with_effects(vec![Effect::new(twist, &values, None).unwrap()])
        .unwrap();
    smash::data::club_file::club_toml_checked(&club, "test", Path::new("twisted.toml")).unwrap();
    assert!(!labels(&groups).iter().any(|l| l == "face_twist"));
    // The same definition read from an effects file is offered from then on.
    let text = std::fs::read_to_string(&path).unwrap();
    let start = text.find("[[define_effect]]").unwrap();
    let end = text[start..]
        .find("[[hidden]]")
        .map_or(text.len(), |e| start + e);
    let defs = parse_effect_defs(Path::new("twist_effects.toml"), &text[start..end])
        .expect("the world's definition as an effects file");
    assert_eq!(defs.len(), 1);
    assert!(labels(&groups).iter().any(|l| l == "face_twist"));
}
