//! Output rendering: builds bytes (SVG pictures, CSV matrices, text tables); never writes files.
//! Writing is done in one place, [`crate::data::write_atomic`].

pub mod compare;
pub mod heatmap;

pub use heatmap::{heatmap_svg, matrix_csv, Heatmap, Scale};
