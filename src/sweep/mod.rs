//! Sweeps over the face: many impacts of one model and one swing, evaluated fast.
//!
//! [`kernel`] maps launch conditions over a grid (or a list) of impact locations, one row per
//! rayon task, into a structure-of-arrays [`kernel::LaunchGrid`]. Studies (`crate::study`) are
//! written only against this API.

pub mod kernel;

pub use kernel::{face_map, face_map_into, FaceMapKernel, LaunchGrid, RowOut};
