//! The domain below the file formats: a [`Shot`] and the [`DeliveryVar`]iables, in SI or file
//! units as each says. No I/O: [`crate::data`] reads and writes files of these types.

pub mod component;
pub mod convention;
/// The delivery variables live beside [`crate::physics::Delivery`], whose file-unit view they are
/// (user-defined effects in `physics` read them too); re-exported here for the domain's users.
pub use crate::physics::delivery_vars as delivery;
pub mod shot;

pub use component::PerComponent;
pub use delivery::{
    default_launch_noise, delivery_from_file_units, delivery_to_file_units, DeliveryVar, N_DELIVERY,
};
pub use shot::Shot;
