use super::*;

#[test]
fn written_club_reads_back_with_its_effects() {
    let path = Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/configs/clubs/paper_driver.toml"
    ));
    let club = read_club(path).unwrap();
    let effects = vec![
        Effect::new(EffectKind::AddedMass, &[2.54], Some("A".into())).unwrap(),
        Effect::new(EffectKind::BallOffset, &[0.48, -0.07], None).unwrap(),
    ];
    let club = club.with_effects(effects).unwrap();
    let text = club_toml(&club, "calibrated\nby a test");
    assert!(text.starts_with("# calibrated\n# by a test\n"));
    let back = parse_club(Path::new("back.toml"), &text).unwrap();
    assert_eq!(back.name, club.name);
    assert_eq!(back.effects, club.effects);
    let (a, b) = (&back.nominal, &club.nominal);
    assert!((a.club_mass_kg - b.club_mass_kg).abs() < 1e-15);
    assert!((a.club_inertia_kgm2 - b.club_inertia_kgm2).amax() < 1e-18);
    assert!((a.club_com_m - b.club_com_m).amax() < 1e-15);
    assert_eq!(a.cor, b.cor);
}

#[test]
fn integer_values_are_accepted_where_numbers_are_expected() {
    let path = Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/configs/clubs/paper_driver.toml"
    ));
    let text = std::fs::read_to_string(path)
        .unwrap()
        .replace("mass_g = 204.0", "mass_g = 204");
    match parse_club(Path::new("int.toml"), &text) {
        Ok(c) => assert!((c.nominal.club_mass_kg - 0.204).abs() < 1e-15),
        Err(e) => panic!("an integer mass should be accepted: {e}"),
    }
}

#[test]
fn a_ball_inertia_beyond_a_thin_shell_is_refused_at_its_key() {
    let path = Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/configs/clubs/paper_driver.toml"
    ));
    let text = std::fs::read_to_string(path).unwrap();
    // 45.9 g, 21.3 mm: a shell holds (2/3)·45.9·2.13² = 138.8 g·cm²; a solid ball 83.3.
    let read = |v: &str| {
        let t = text.replace("inertia_gcm2 = 83.63", &format!("inertia_gcm2 = {v}"));
        parse_club(Path::new("ball.toml"), &t)
    };
    let e = read("5000").unwrap_err().to_string();
    assert!(
        e.contains("ball.inertia_gcm2")
            && e.contains("5000 g·cm² is more than a ball of 45.9 g and radius 21.3 mm")
            && e.contains("at most 138.8 g·cm²"),
        "{e}"
    );
    assert!(read("138.8").is_ok());
    assert!(read("138.9").is_err());
}
