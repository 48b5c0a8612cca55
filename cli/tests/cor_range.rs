//! A library COR law inside its parameters' ranges can leave (0, 1] at some deliveries
//! (`cor_power` at a slow club speed, `cor_radial` far from the face centre): such an impact is
//! no collision, and every path refuses it as the scalar solve does (found by a hostile tester,
//! 29 Nov 2026: a smash factor of 8.18 at 10 mph, a COR of −0.5 at 36 mm off centre, printed
//! without a word).

use crate::cli_support;

use cli_support::{repo, s, smash, unwrapped as stderr, write};

/// The paper driver with one more `[[effect]]` table.
fn club_with(dir: &std::path::Path, effect: &str) -> std::path::PathBuf {
    let base = std::fs::read_to_string(repo("configs/clubs/paper_driver.toml")).unwrap();
    write(dir, "club.toml", &format!("{base}\n[[effect]]\n{effect}\n"))
}

#[test]
fn a_cor_law_outside_zero_to_one_is_refused_not_printed() {
    let dir = tempfile::tempdir().unwrap();
    let club = club_with(dir.path(), "name = \"cor_power\"\nq = 1.0");
    let o = smash(&[
        "predict",
        "--club",
        s(&club),
        "--speed",
        "10",
        "--loft",
        "12",
    ]);
    let e = stderr(&o);
    assert!(
        !o.status.success(),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    assert!(
        e.contains("the club's restitution law gives a COR of")
            && e.contains("outside (0, 1]")
            && !e.contains("panicked"),
        "{e}"
    );
    // At a driver's speed the same law is a collision.
    let o = smash(&[
        "predict",
        "--club",
        s(&club),
        "--speed",
        "100",
        "--loft",
        "12",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn a_face_map_marks_cells_whose_cor_leaves_the_range_invalid() {
    let dir = tempfile::tempdir().unwrap();
    let club = club_with(dir.path(), "name = \"cor_radial\"\nc_per_mm2 = 0.001");
    let study = write(
        dir.path(),
        "map.toml",
        &format!(
            "[study]\nname = \"m\"\nclub = \"{}\"\n\n[delivery]\nclub_speed_mph = 100.0\n\
             dynamic_loft_deg = 12.0\n\n[grid]\ny_mm = {{ from = 0.0, to = 0.0, step = 1.0 }}\n\
             z_mm = {{ from = -40.0, to = 40.0, step = 10.0 }}\n",
            s(&club)
        ),
    );
    let out = dir.path().join("out");
    let o = smash(&["run", s(&study), "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let map = std::fs::read_to_string(out.join("maps_long.csv")).unwrap();
    // COR ≈ 0.83 − 0.001·z² on the centre line: above 0 to ±20 mm, below it from ±30 mm.
    let mut r = csv::Reader::from_reader(map.as_bytes());
    let h = r.headers().unwrap().clone();
    let col = |name: &str| h.iter().position(|c| c == name).unwrap();
    let (z, valid, smash_factor) = (col("z_mm"), col("valid"), col("smash_factor"));
    let mut seen = 0;
    for rec in r.records() {
        let rec = rec.unwrap();
        let z: f64 = rec[z].parse().unwrap();
        let inside = z.abs() <= 20.0;
        assert_eq!(&rec[valid], if inside { "1" } else { "0" }, "{map}");
        assert_eq!(rec[smash_factor].is_empty(), !inside, "{map}");
        seen += 1;
    }
    assert_eq!(seen, 9, "{map}");
}
