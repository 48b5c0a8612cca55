//! Shared test helpers.

pub mod fifteen;
