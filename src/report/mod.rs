//! Text reports: tables for the terminal, built as strings (the CLI prints them).

pub mod tables;

pub use tables::{error_table_text, error_tables_side_by_side, fmt_value, TextTable};
