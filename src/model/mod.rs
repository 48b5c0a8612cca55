//! The domain below the file formats: a [`Shot`] and the [`DeliveryVar`]iables, in SI or file
//! units as each says. No I/O: [`crate::data`] reads and writes files of these types.

pub mod delivery;
pub mod shot;

pub use delivery::{default_launch_noise, delivery_from_file_units, DeliveryVar, N_DELIVERY};
pub use shot::Shot;
