//! Whole-output snapshots of the command line: every case `tests/cmd/NAME.toml` runs `smash` with
//! its arguments (in `tests/cmd/fixtures/`, or a copy of it when the command writes files) and
//! compares the exit code, the whole stdout (`NAME.stdout`), the whole stderr (`NAME.stderr`)
//! and every file in `NAME.out/` byte for byte. `[..]` in a snapshot matches anything on that
//! line: used only for run times.
//!
//! After an intended change of output: `TRYCMD=overwrite cargo test -p smash-cli --test cli cmd::`,
//! then review the diff of `tests/cmd/` like code.

#[test]
fn cli_snapshots() {
    trycmd::TestCases::new()
        .register_bin("smash", std::path::Path::new(env!("CARGO_BIN_EXE_smash")))
        .case("tests/cmd/*.toml");
}
