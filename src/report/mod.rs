//! Output rendering: builds bytes and strings (SVG pictures, CSV matrices, text tables, JSON);
//! never writes files. Writing is done in one place, [`crate::data::write_atomic`].

pub mod calibrate;
pub mod charts;
pub mod compare;
pub mod delivery_noise;
pub mod diagnose;
pub mod effects;
pub mod flight;
pub mod heatmap;
pub mod html;
mod json;
pub mod likelihood;
pub mod predict;
pub mod render;
pub mod strata;
pub mod tables;
pub mod text;
pub mod to_scale;
pub mod views;
pub use crate::wrap;

pub use heatmap::{heatmap_svg, matrix_csv, Heatmap, Scale};
pub use tables::{error_table_text, error_tables_side_by_side, fmt_value, TextTable};

/// An impact-location noise in mm as the reports print it: to 1e-6 mm, so that 1.8 mm shows as
/// 1.8 after the metre round trip.
pub fn location_mm(m: f64) -> f64 {
    (m * 1e9).round() / 1e6
}
