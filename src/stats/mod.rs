//! Pure statistics for comparing a model with measurements: summaries, Student-t tests and
//! Pearson correlations. No I/O; every function takes plain slices.

pub mod correlation;
pub mod summary;
pub mod tdist;

pub use correlation::{pearson, Correlation};
pub use summary::{mean, std_dev, Summary};
pub use tdist::{student_t_cdf, student_t_two_sided_p};
