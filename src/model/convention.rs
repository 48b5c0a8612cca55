//! Where and how a launch monitor defines one shot's delivery: the point of the head its loft
//! and face angle, and its speed and path, refer to, and whether its face angle was measured.
//! The values and their names in files; the conversion to the model's own convention is in
//! the `conventions` module at the crate's root.

/// Where the dynamic loft and the face angle are defined.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash, PartialOrd, Ord)]
pub enum FacePoint {
    /// The orientation of the face frame at the face centre (the model's own).
    #[default]
    FaceCentre,
    /// The direction of the face normal at the centre-point of contact (TrackMan).
    ContactPoint,
}

/// Which point of the head the club speed, attack angle and path describe.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash, PartialOrd, Ord)]
pub enum VelocityPoint {
    /// The clubhead's centre of mass (the model's own).
    #[default]
    Com,
    /// The head's geometric centre (TrackMan), taken to be the centre of mass.
    GeometricCentre,
    /// The centre of the face (camera monitors).
    FaceCentre,
}

/// How the face angle was obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash, PartialOrd, Ord)]
pub enum FaceAngleSource {
    /// Measured (the model's assumption).
    #[default]
    Measured,
    /// Computed by the monitor from the launch direction and the club path.
    Launch,
}

/// The convention of one shot's delivery ([`Default`]: the model's own).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash, PartialOrd, Ord)]
pub struct DeliveryConvention {
    /// Where loft and face angle are defined.
    pub face_at: FacePoint,
    /// Which point speed, attack angle and path describe.
    pub velocity_at: VelocityPoint,
    /// How the face angle was obtained.
    pub face_angle_from: FaceAngleSource,
}

/// Shots-file column of [`DeliveryConvention::face_at`].
pub const FACE_AT_COLUMN: &str = "face_at";
/// Shots-file column of [`DeliveryConvention::velocity_at`].
pub const VELOCITY_AT_COLUMN: &str = "velocity_at";
/// Shots-file column of [`DeliveryConvention::face_angle_from`].
pub const FACE_ANGLE_FROM_COLUMN: &str = "face_angle_from";

impl FacePoint {
    /// Every value, with its name in files.
    pub const ALL: [(Self, &'static str); 2] = [
        (Self::FaceCentre, "face_centre"),
        (Self::ContactPoint, "contact_point"),
    ];
}

impl VelocityPoint {
    /// Every value, with its name in files.
    pub const ALL: [(Self, &'static str); 3] = [
        (Self::Com, "com"),
        (Self::GeometricCentre, "geometric_centre"),
        (Self::FaceCentre, "face_centre"),
    ];
}

impl FaceAngleSource {
    /// Every value, with its name in files.
    pub const ALL: [(Self, &'static str); 2] = [
        (Self::Measured, "measured"),
        (Self::Launch, "derived_from_launch"),
    ];
}

/// The value named `name` in `all`.
pub fn parse_name<T: Copy>(all: &[(T, &'static str)], name: &str) -> Option<T> {
    all.iter().find(|(_, n)| *n == name).map(|(v, _)| *v)
}

/// The name of `v` in `all`.
pub fn name_of<T: Copy + PartialEq>(all: &[(T, &'static str)], v: T) -> &'static str {
    all.iter().find(|(x, _)| *x == v).map_or("?", |(_, n)| *n)
}

/// The names in `all`, for messages.
pub fn names<T>(all: &[(T, &'static str)]) -> String {
    all.iter().map(|(_, n)| *n).collect::<Vec<_>>().join(", ")
}
