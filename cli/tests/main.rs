//! The command line's integration tests, one module per subject, compiled into one test binary
//! (`cargo test -p smash-cli --test cli [FILTER]`): 51 binaries, each linking the library and
//! its own copy of `cli_support`, took several minutes of CI's build; one takes a fraction.
//! Every test here runs the `smash` binary as a child process or calls the library without
//! registering anything in it, so the tests share no state.

mod cli_support;
/// The library tests' helpers (deterministic synthetic experiments), shared.
#[path = "../../tests/common/mod.rs"]
mod common;

mod bad_rows;
mod carry_units;
mod cli_fit;
mod cli_flight;
mod cli_flight_calibrate;
mod cli_flight_diagnose;
mod cli_flight_measure;
mod cli_io;
mod cli_predict;
mod cli_user_effects;
mod cli_yards;
mod club_match;
mod cmd;
mod compare;
mod conventions;
mod cor_range;
mod csv_errors;
mod diagnose_assumed;
mod diagnose_honest;
mod diagnose_strata;
mod diagnose_worlds;
mod docs_links;
mod docs_run;
mod fuzz;
mod golden;
mod hostile_import3;
mod hostile_input;
mod hostile_more;
mod hostile_round15;
mod hostile_round2;
mod hostile_round3;
mod hostile_round4;
mod hostile_round5;
mod hostile_round6;
mod import;
mod import_corpus;
mod import_fsx_play;
mod import_hostile;
mod import_mutations;
mod import_real;
mod import_unseen;
mod import_unseen3;
mod infer_club;
mod json_schema;
mod library_forms;
mod model_comparison;
mod output_folders;
mod output_plan;
mod project_defaults;
mod report;
mod rival_families;
mod signals;
mod study;
mod study_memory;
mod study_report;
mod text_width;
mod validation;
mod whatif;
mod world_seeds;
