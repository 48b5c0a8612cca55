//! Pure statistics: summaries and Student-t tests, Pearson correlations, robust scale,
//! straight-line regression, the Table-2 error statistics, and deterministic grouped k-fold
//! assignment. No I/O; every function takes plain slices; no randomness.

pub mod correlation;
pub mod error_table;
pub mod folds;
pub mod regression;
pub mod robust;
pub mod summary;
pub mod tdist;

pub use correlation::{pearson, Correlation};
pub use error_table::{launch_error_table, ErrorTable, GroupErrors, MeanStd};
pub use folds::{grouped_folds, item_folds, FoldKeys, KeyKind};
pub use regression::{linear_regression, t_statistic, LineFit};
pub use robust::{median, rms, robust_scale, MAD_TO_SIGMA};
pub use summary::{mean, std_dev, Summary};
pub use tdist::{student_t_cdf, student_t_two_sided_p};
