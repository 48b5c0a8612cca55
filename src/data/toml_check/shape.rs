//! Lists of numbers of fixed shape in TOML files (`[f64; N]`, `N` rows of `M`): serde's arrays
//! read the first `N` elements and ignore the rest, so these are read as vectors and their
//! length checked, with [`ShapeError`] saying what was expected and found.

use toml::Spanned;

/// A list of numbers of fixed shape in a TOML file (`[f64; N]`, or `N` rows of `M`): read with
/// [`exact`] / [`exact_opt`] so that a list of the wrong length is refused, not truncated (serde's
/// arrays read the first `N` elements and ignore the rest).
pub trait FixedShape: Sized {
    /// What the file holds before the length check.
    type Raw: serde::de::DeserializeOwned;
    /// The value when `raw` has this shape; otherwise what was expected and what was found.
    fn from_raw(raw: Self::Raw) -> Result<Self, ShapeError>;
}

/// A list of numbers of the wrong shape ([`FixedShape`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ShapeError {
    /// A list of the wrong length.
    #[error("expected a list of {want} numbers, got {got}")]
    Numbers {
        /// Numbers expected.
        want: usize,
        /// Numbers found.
        got: usize,
    },
    /// A table with the wrong number of rows.
    #[error("expected a list of {want} rows of {columns} numbers, got {got} rows")]
    Rows {
        /// Rows expected.
        want: usize,
        /// Numbers in each row.
        columns: usize,
        /// Rows found.
        got: usize,
    },
    /// A row of the wrong length (1-based).
    #[error("row {row}: {source}")]
    Row {
        /// The row, from 1.
        row: usize,
        /// What is wrong with it.
        source: Box<ShapeError>,
    },
}

impl<const N: usize> FixedShape for [f64; N] {
    type Raw = Vec<f64>;
    fn from_raw(raw: Vec<f64>) -> Result<Self, ShapeError> {
        let n = raw.len();
        raw.try_into()
            .map_err(|_| ShapeError::Numbers { want: N, got: n })
    }
}

impl<const M: usize, const N: usize> FixedShape for [[f64; M]; N] {
    type Raw = Vec<Vec<f64>>;
    fn from_raw(raw: Vec<Vec<f64>>) -> Result<Self, ShapeError> {
        let n = raw.len();
        if n != N {
            return Err(ShapeError::Rows {
                want: N,
                columns: M,
                got: n,
            });
        }
        let mut out = [[0.0; M]; N];
        for (i, row) in raw.into_iter().enumerate() {
            out[i] = <[f64; M]>::from_raw(row).map_err(|e| ShapeError::Row {
                row: i + 1,
                source: Box::new(e),
            })?;
        }
        Ok(out)
    }
}

/// Serde `deserialize_with` for a `Spanned` list of fixed shape (see [`FixedShape`]).
pub fn exact<'de, D, S>(d: D) -> Result<Spanned<S>, D::Error>
where
    D: serde::Deserializer<'de>,
    S: FixedShape,
{
    use serde::Deserialize;
    let raw = Spanned::<S::Raw>::deserialize(d)?;
    let span = raw.span();
    S::from_raw(raw.into_inner())
        .map(|v| Spanned::new(span, v))
        .map_err(serde::de::Error::custom)
}

/// [`exact`] for an optional key (the field also needs `#[serde(default)]`).
pub fn exact_opt<'de, D, S>(d: D) -> Result<Option<Spanned<S>>, D::Error>
where
    D: serde::Deserializer<'de>,
    S: FixedShape,
{
    exact(d).map(Some)
}
