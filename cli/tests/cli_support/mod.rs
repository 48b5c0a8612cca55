//! What the command-line tests share: the binary, the repository's files and a measured shots
//! file, and the check that a file was left as it was. Each test binary uses a part of it.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Writes `text` to `dir/name` and returns the path.
pub fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// The `smash` binary under test.
pub const SMASH: &str = env!("CARGO_BIN_EXE_smash");

/// The documentation files `docs_run.rs` runs, in the order it runs them: README.md,
/// configs/README.md, CONTRIBUTING.md, then docs/*.md alphabetically.
pub fn doc_files(root: &Path) -> Vec<PathBuf> {
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root.join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "md"))
        .collect();
    docs.sort();
    let mut files = vec![
        root.join("README.md"),
        root.join("configs/README.md"),
        root.join("CONTRIBUTING.md"),
    ];
    files.extend(docs);
    files
}

/// A path in the repository.
pub fn repo(rel: &str) -> PathBuf {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/..")).join(rel)
}

/// Run `smash` with `args` (and no project file: a `smash.toml` above the checkout must not
/// change what the tests see).
pub fn smash(args: &[&str]) -> Output {
    Command::new(SMASH)
        .args(args)
        .env("SMASH_CONFIG", "none")
        .output()
        .unwrap()
}

/// Run `smash` with `args` from the repository's root (relative paths are the repository's),
/// without a project file.
pub fn smash_in_repo(args: &[&str]) -> Output {
    Command::new(SMASH)
        .args(args)
        .env("SMASH_CONFIG", "none")
        .current_dir(repo(""))
        .output()
        .unwrap()
}

/// A command's stderr as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// `stderr(o)` with the notes' continuation lines joined back to their notes
/// (`smash_cli::text::print_note` wraps a long note at the report width, its continuation lines
/// indented two spaces): a test looks for a note's text whole, wherever the wrap fell.
pub fn unwrapped(o: &Output) -> String {
    stderr(o).replace("\n  ", " ")
}

/// A path as an argument.
pub fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// The paper's driver, as an argument.
pub fn club() -> String {
    s(&repo("configs/clubs/paper_driver.toml")).to_owned()
}

/// A shots file with measured launch: the golden deliveries with their reference launch as the
/// measurement.
pub fn measured_shots(dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(repo("tests/data/golden/nominal.csv")).unwrap();
    let path = dir.join("shots.csv");
    std::fs::write(&path, text.replacen("pred_", "", 5)).unwrap();
    path
}

/// `path` still holds `text`.
pub fn assert_kept(path: &Path, text: &str) {
    assert_eq!(
        std::fs::read_to_string(path).unwrap(),
        text,
        "{} was changed",
        path.display()
    );
}

/// `smash synth --config configs/synth/WORLD.toml --out DIR/WORLD_SEED.csv --seed SEED`: the
/// shots file, after checking the command succeeded.
pub fn synth_world(dir: &Path, world: &str, seed: u32) -> PathBuf {
    synth_config(dir, &repo(&format!("configs/synth/{world}.toml")), seed)
}

/// `smash synth --config CONFIG --out DIR/NAME_SEED.csv --seed SEED` (`NAME` the config's file
/// stem): the shots file, after checking the command succeeded.
pub fn synth_config(dir: &Path, config: &Path, seed: u32) -> PathBuf {
    let name = config.file_stem().unwrap().to_string_lossy();
    let shots = dir.join(format!("{name}_{seed}.csv"));
    let seed_arg = seed.to_string();
    let o = smash(&[
        "synth",
        "--config",
        s(config),
        "--out",
        s(&shots),
        "--seed",
        &seed_arg,
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    shots
}

/// `smash diagnose --club configs/clubs/paper_driver.toml --shots SHOTS --json ARGS`: the JSON,
/// after checking the command succeeded.
pub fn diagnose_json(shots: &Path, args: &[&str]) -> serde_json::Value {
    let club = repo("configs/clubs/paper_driver.toml");
    let mut argv = vec![
        "diagnose",
        "--club",
        s(&club),
        "--shots",
        s(shots),
        "--json",
    ];
    argv.extend_from_slice(args);
    let o = smash(&argv);
    assert!(o.status.success(), "{}", stderr(&o));
    serde_json::from_slice(&o.stdout).unwrap()
}

/// The rows of a CSV file written by the CLI, as header → cell maps.
pub fn csv_rows(path: &Path) -> Vec<std::collections::HashMap<String, String>> {
    let mut r = csv::Reader::from_path(path).unwrap();
    let head: Vec<String> = r.headers().unwrap().iter().map(str::to_owned).collect();
    r.records()
        .map(|rec| {
            head.iter()
                .cloned()
                .zip(rec.unwrap().iter().map(str::to_owned))
                .collect()
        })
        .collect()
}
