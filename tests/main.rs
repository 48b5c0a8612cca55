//! The library's integration tests, one module per subject, compiled into one test binary
//! (`cargo test -p smash --test library [FILTER]`). Three stay binaries of their own
//! (`Cargo.toml`): `user_effects` counts allocations with its own global allocator;
//! `lane_path` reads process-wide counts that other tests' fits would add to; `lane_user_bits`
//! (like the other two) registers user-defined effects, which in a shared process would become
//! default candidates of the other tests' diagnoses.

mod common;

mod calibrate;
mod cancel;
mod club_heads;
mod contact_world;
mod diagnose;
mod diagnose_fdr;
mod face_map_golden;
mod face_map_kernel;
mod fifteen_equations;
mod fit_batched;
mod flight;
mod flight_air;
mod flight_real;
mod flight_step;
mod infer_club;
mod large_n_fdr;
mod lib_map;
mod location_noise;
mod new_effects;
mod properties;
mod synth;
