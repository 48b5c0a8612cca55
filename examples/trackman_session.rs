//! Write a synthetic shots file (`smash synth`) as a TrackMan export in its real 61-column
//! layout and TrackMan's conventions: the file of the guided real-format example
//! (configs/README.md, tests/data/README.md) and of the real-format diagnose bench's world
//! (`configs/synth/trackman_real_scale_world.toml`, with `--radar-face`).
//!
//! `cargo run --example trackman_session -- WORLD.csv HEADER.csv CLUB.toml OUT.csv [--radar-face]`
//!
//! - `HEADER.csv`: a TrackMan export whose header and units rows are copied (the layout of
//!   `cli/tests/fixtures/import/trackman_normalized.csv`);
//! - what is written, and `--radar-face` (a face angle derived from the launch as some radar
//!   units do): `benches/support/trackman.rs`.

use std::path::Path;

#[path = "../benches/support/trackman.rs"]
mod trackman;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let radar_face = args.get(4).map(String::as_str) == Some("--radar-face");
    assert!(
        args.len() == 4 || (args.len() == 5 && radar_face),
        "usage: WORLD.csv HEADER.csv CLUB.toml OUT.csv [--radar-face]"
    );
    let club = smash::data::club_file::read_club(Path::new(&args[2])).expect("club");
    let face =
        smash::physics::FaceGeometry::new(club.nominal.bulge_m, club.nominal.roll_m).expect("face");
    let layout = std::fs::read_to_string(&args[1]).expect("header file");
    let world = std::fs::read(&args[0]).expect("world");
    let out = trackman::trackman_export(&world, &layout, &face, radar_face);
    std::fs::write(&args[3], out).expect("write");
}
