//! The number type the laws and user-defined expressions are evaluated on: `f64` (one shot) or
//! a vector of lanes, with the same operations on both. Defined with the lane types
//! ([`crate::lanes::Real`]) and used here under its physics name.

pub use crate::lanes::Real;
