//! The real-format fixture of the diagnose bench: `configs/synth/trackman_real_scale_world.toml`
//! (2,200 drives in 22 sessions, structure everywhere) generated as `smash synth` does, written
//! as a TrackMan export ([`super::trackman`], with the radar's derived face angle, as
//! `cargo run --example trackman_session -- … --radar-face` writes it), converted with the
//! `trackman` preset as `smash import --format trackman --impact-offset-positive toe` does, read
//! back with the CLI's reader and brought to the model's convention as `smash diagnose` does.
//! What `smash diagnose` is then given: the shots and the session (date) fold keys.
//!
//! [`shaft_season`] is the same for `configs/synth/trackman_shaft_season_world.toml` (three
//! shafts of 50, 80 and 120 g, the added mass in proportion to the shaft's: 2,244 drives), with
//! each shot's `shaft_mass_g` joined to the export's club name, as a fitter who weighed the
//! shafts would (`docs/performance-history.md`, "A shaft-fitting season").

use std::path::Path;

use smash::data::club_file::read_club;
use smash::data::import::{import, load_mapping, ImportOptions, OffsetSide};
use smash::data::sessions::fold_keys;
use smash::data::shots::{read_shots, Shot};
use smash::stats::FoldKeys;
use smash::synth::files::synth_shots_csv;
use smash::synth::{generate, read_config};
use smash::ClubSpec;

use super::trackman::trackman_export;

/// The shots of the real-format season in the model's convention with `club`'s face, and the
/// fold keys (sessions) for `folds` folds.
pub fn real_format_season(club: &ClubSpec, folds: usize) -> (Vec<Shot>, Option<FoldKeys>) {
    season(
        "configs/synth/trackman_real_scale_world.toml",
        club,
        folds,
        false,
    )
}

/// The shaft-fitting season ([`real_format_season`] of the three-shaft world, the shaft masses
/// joined by club).
pub fn shaft_season(club: &ClubSpec, folds: usize) -> (Vec<Shot>, Option<FoldKeys>) {
    season(
        "configs/synth/trackman_shaft_season_world.toml",
        club,
        folds,
        true,
    )
}

fn season(
    world: &str,
    club: &ClubSpec,
    folds: usize,
    join_shafts: bool,
) -> (Vec<Shot>, Option<FoldKeys>) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let cfg = read_config(&root.join(world)).expect("real-scale world reads");
    let base = read_club(&cfg.club).expect("base club reads");
    let run = generate(&cfg, &base).expect("world generates");
    let layout =
        std::fs::read_to_string(root.join("cli/tests/fixtures/import/trackman_normalized.csv"))
            .expect("TrackMan layout reads");
    let face =
        smash::physics::FaceGeometry::new(club.nominal.bulge_m, club.nominal.roll_m).expect("face");
    let export = trackman_export(&synth_shots_csv(&run), &layout, &face, true);
    let dir = tempfile::tempdir().expect("temp dir");
    let export_path = dir.path().join("trackman.csv");
    let opts = ImportOptions {
        impact_offset_positive: Some(OffsetSide::Toe),
        ..ImportOptions::default()
    };
    let mapping = load_mapping("trackman").expect("trackman preset");
    let imported =
        import(&export_path, export.as_bytes(), &mapping, &opts).expect("export imports");
    let shots_path = dir.path().join("shots.csv");
    let csv = if join_shafts {
        with_shaft_masses(&imported.csv, &run.shots).into_bytes()
    } else {
        imported.csv
    };
    std::fs::write(&shots_path, &csv).expect("shots written");
    let mut table = read_shots(&shots_path).expect("shots read");
    let (shots, _) = smash::conventions::to_model(club, &table.shots, &table.conventions)
        .expect("shots on the face");
    table.shots = shots;
    table.conventions = vec![Default::default(); table.shots.len()];
    let keys = fold_keys(&table, folds).expect("session keys");
    (table.shots, keys)
}

/// `shots_csv` (the import's output) with a `shaft_mass_g` column taken by group (the export's
/// club name) from the world's shots.
fn with_shaft_masses(shots_csv: &[u8], world: &[smash::synth::SynthShot]) -> String {
    let mass: std::collections::HashMap<&str, f64> = world
        .iter()
        .map(|s| (s.group.as_str(), s.shaft_mass_g))
        .collect();
    let mut reader = csv::Reader::from_reader(shots_csv);
    let header = reader.headers().expect("header").clone();
    let group = header
        .iter()
        .position(|h| h == "group")
        .expect("a group column");
    let mut out = csv::Writer::from_writer(Vec::new());
    let mut head: Vec<&str> = header.iter().collect();
    head.push("shaft_mass_g");
    out.write_record(&head).expect("header written");
    for row in reader.records() {
        let row = row.expect("row reads");
        let m = mass[row.get(group).expect("group")];
        let mut fields: Vec<String> = row.iter().map(str::to_owned).collect();
        fields.push(m.to_string());
        out.write_record(&fields).expect("row written");
    }
    String::from_utf8(out.into_inner().expect("flushed")).expect("UTF-8")
}
