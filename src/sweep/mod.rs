//! Design-study sweeps: launch conditions over impact-location grids and model variants.
//!
//! [`kernel`] holds the fast inner loop: a [`FaceMapKernel`] precomputes everything about one
//! (model, delivery) pair that does not depend on where the ball meets the face, then evaluates
//! rows or arbitrary point sets of impact locations into structure-of-arrays [`LaunchGrid`]s.
//! [`face_map`] and [`face_map_into`] run a whole grid, rows in parallel, deterministically.
//! [`fastmath`] has the branch-free `atan2` the kernel vectorises.

pub mod fastmath;
pub mod kernel;

pub use kernel::{
    face_map, face_map_into, simd_level, FaceMapKernel, LaunchGrid, RowOut, SimdLevel, LANES,
};
