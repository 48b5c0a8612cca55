//! Shots files as `smash synth` writes them: the paper world (`configs/synth/paper_world.toml`,
//! 600 shots) or the same world with more golfers, generated, written as CSV and read back with
//! the reader the CLI uses, so the benches fit exactly what a user's command fits.

use std::path::Path;

use smash::data::club_file::read_club;
use smash::data::shots::{read_shots, Shot};
use smash::synth::files::synth_shots_csv;
use smash::synth::{generate, read_config};
use smash::ClubSpec;

/// The paper's driver, read from `configs/clubs/paper_driver.toml` (the club of the README's
/// commands).
pub fn paper_club() -> ClubSpec {
    read_club(&Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/clubs/paper_driver.toml"))
        .expect("paper club reads")
}

/// The paper world with `golfers` golfers per shaft (20: the shipped 600-shot world), as read
/// back from the CSV `smash synth` writes.
pub fn paper_world(golfers: usize) -> Vec<Shot> {
    let cfg_path = Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/synth/paper_world.toml");
    let mut cfg = read_config(&cfg_path).expect("paper world reads");
    cfg.golfers = golfers;
    shots_of(&cfg)
}

/// The world of the synth config at `path`, as read back from the CSV `smash synth` writes.
#[allow(dead_code)] // not every bench that includes this file uses it
pub fn world(path: &Path) -> Vec<Shot> {
    shots_of(&read_config(path).expect("world reads"))
}

fn shots_of(cfg: &smash::synth::SynthConfig) -> Vec<Shot> {
    let club = read_club(&cfg.club).expect("base club reads");
    let run = generate(cfg, &club).expect("world generates");
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("shots.csv");
    std::fs::write(&path, synth_shots_csv(&run)).expect("shots written");
    read_shots(&path).expect("shots read").shots
}
