//! The engine reproduces every reference file in `tests/data/golden/` to 1e-6 (relative or
//! absolute, whichever is looser), through the `smash predict` command on the real files, and
//! finds the friction file's slipping shots where the README says they are. The reference values
//! come from an independent implementation (`tests/data/golden/generate.py`, see its README).

use std::path::{Path, PathBuf};
use std::process::Command;

const CASES: [&str; 11] = [
    "nominal",
    "added_mass",
    "ball_offset",
    "tangential_restitution",
    "friction",
    "cor_speed",
    "cor_radial",
    "loft_bias",
    "face_bias",
    "com_offset",
    "inertia_scale",
];
const COMPONENTS: [&str; 5] = [
    "ball_speed_mph",
    "launch_angle_deg",
    "azimuth_deg",
    "backspin_rpm",
    "sidespin_rpm",
];

fn golden_dir() -> PathBuf {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/..")).join("tests/data/golden")
}

fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let mut r = csv::Reader::from_path(path).unwrap();
    let h = r.headers().unwrap().iter().map(str::to_owned).collect();
    let rows = r
        .records()
        .map(|x| x.unwrap().iter().map(str::to_owned).collect())
        .collect();
    (h, rows)
}

fn column(h: &[String], rows: &[Vec<String>], name: &str) -> Vec<f64> {
    let i = h
        .iter()
        .position(|c| c == name)
        .unwrap_or_else(|| panic!("no column {name}"));
    rows.iter().map(|r| r[i].parse().unwrap()).collect()
}

fn predict(case: &str, out: &Path) {
    let club = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .join(format!("tests/data/golden_clubs/{case}.toml"));
    let shots = golden_dir().join(format!("{case}.csv"));
    let status = Command::new(env!("CARGO_BIN_EXE_smash"))
        .args(["predict", "--club"])
        .arg(&club)
        .arg("--shots")
        .arg(&shots)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    assert!(
        status.status.success(),
        "{case}: {}",
        String::from_utf8_lossy(&status.stderr)
    );
}

#[test]
fn smash_predict_reproduces_every_golden_file() {
    let tmp = tempfile::tempdir().unwrap();
    for case in CASES {
        let out = tmp.path().join(format!("{case}.csv"));
        predict(case, &out);
        let (gh, grows) = read_csv(&golden_dir().join(format!("{case}.csv")));
        let (ph, prows) = read_csv(&out);
        assert_eq!(grows.len(), prows.len(), "{case}: row count");
        assert!(grows.len() >= 10, "{case}: too few golden rows");
        let gid = gh.iter().position(|c| c == "shot_id").unwrap();
        let pid = ph.iter().position(|c| c == "shot_id").unwrap();
        for (g, p) in grows.iter().zip(&prows) {
            assert_eq!(g[gid], p[pid], "{case}: shot order");
        }
        for comp in COMPONENTS {
            let want = column(&gh, &grows, &format!("pred_{comp}"));
            let got = column(&ph, &prows, &format!("pred_{comp}"));
            for (k, (w, g)) in want.iter().zip(&got).enumerate() {
                let tol = 1e-6 * w.abs().max(1.0);
                assert!(
                    (w - g).abs() <= tol,
                    "{case} row {k} {comp}: golden {w}, engine {g}"
                );
            }
        }
        // Exactly one set of prediction columns: the golden pred_* inputs are replaced.
        assert_eq!(
            ph.iter()
                .filter(|c| c.as_str() == "pred_ball_speed_mph")
                .count(),
            1
        );
    }
}

#[test]
fn friction_golden_slips_only_on_some_shots_and_matches_nominal_elsewhere() {
    let (h, rows) = read_csv(&golden_dir().join("friction.csv"));
    let (nh, nrows) = read_csv(&golden_dir().join("nominal.csv"));
    let fr = column(&h, &rows, "pred_backspin_rpm");
    let nom = column(&nh, &nrows, "pred_backspin_rpm");
    let loft = column(&h, &rows, "dynamic_loft_deg");
    let differ: Vec<usize> = (0..fr.len())
        .filter(|&i| (fr[i] - nom[i]).abs() > 1e-6)
        .collect();
    assert!(
        !differ.is_empty() && differ.len() < fr.len(),
        "friction must slip on some shots only"
    );
    // Slip happens on the more lofted deliveries.
    let mean = |ix: &mut dyn Iterator<Item = usize>| {
        let v: Vec<f64> = ix.map(|i| loft[i]).collect();
        v.iter().sum::<f64>() / v.len() as f64
    };
    let slip_loft = mean(&mut differ.iter().copied());
    let stick_loft = mean(&mut (0..fr.len()).filter(|i| !differ.contains(i)));
    assert!(
        slip_loft > stick_loft,
        "slipping shots should be more lofted"
    );
}
