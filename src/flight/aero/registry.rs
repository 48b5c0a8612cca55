//! The built-in coefficient models by name: the one list a new model is added to
//! (`aero_models!` below), and what is made from it.

use std::path::Path;

use super::{CoefficientModel, Coefficients, TableModel};

/// An aerodynamic model name that is not one ([`AeroModel::from_name`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AeroNameError {
    /// Neither a built-in model nor `table:PATH`.
    #[error("unknown aerodynamic model '{name}' (allowed: {}, table:PATH)", MODEL_NAMES.join(", "))]
    Unknown {
        /// The name given.
        name: String,
    },
    /// A table that cannot be read.
    #[error(transparent)]
    Table(#[from] super::table::TableError),
}

/// Something done with whichever coefficient model an [`AeroModel`] holds, with the model's
/// concrete type (so an integrator is compiled once per model, with no dispatch in its loop).
pub trait ModelVisitor {
    /// What the visit gives.
    type Output;
    /// Do it with `model`.
    fn visit<C: CoefficientModel>(self, model: &C) -> Self::Output;
}

/// Declares the built-in models: one line per model, `Type => "name",`, the default first.
/// `Type` is a unit struct implementing [`CoefficientModel`] (its own file, or this one); the
/// macro makes the [`AeroModel`] variant of the same name, [`MODEL_NAMES`], the lookup by name,
/// the name and the dispatch, so adding a model is its file and its line.
macro_rules! aero_models {
    ($first:ident => $first_name:literal, $($model:ident => $name:literal,)*) => {
        /// A coefficient model chosen by name (what files and the command line select).
        #[derive(Debug, Clone, PartialEq, Default)]
        pub enum AeroModel {
            #[doc = concat!("[`", stringify!($first), "`](super::", stringify!($first), ") (the default).")]
            #[default]
            $first,
            $(
                #[doc = concat!("[`", stringify!($model), "`](super::", stringify!($model), ").")]
                $model,
            )*
            /// A user's [`TableModel`].
            Table(std::sync::Arc<TableModel>),
        }

        /// Names of the built-in models, the default first.
        pub const MODEL_NAMES: [&str; [$first_name, $($name),*].len()] = [$first_name, $($name),*];

        impl AeroModel {
            /// A built-in model by name, or `table:PATH` (a CSV file, see [`TableModel`]).
            pub fn from_name(name: &str) -> Result<Self, AeroNameError> {
                match name {
                    $first_name => Ok(Self::$first),
                    $($name => Ok(Self::$model),)*
                    _ => match name.strip_prefix("table:") {
                        Some(p) => Ok(Self::Table(std::sync::Arc::new(TableModel::from_path(
                            Path::new(p),
                        )?))),
                        None => Err(AeroNameError::Unknown {
                            name: name.to_owned(),
                        }),
                    },
                }
            }

            /// The name as selected (tables: `table:` and a description).
            pub fn name(&self) -> String {
                match self {
                    Self::$first => $first_name.into(),
                    $(Self::$model => $name.into(),)*
                    Self::Table(t) => t.describe(),
                }
            }

            /// Visit the model with its concrete type.
            pub fn visit<V: ModelVisitor>(&self, v: V) -> V::Output {
                match self {
                    Self::$first => v.visit(&super::$first),
                    $(Self::$model => v.visit(&super::$model),)*
                    Self::Table(t) => v.visit(t.as_ref()),
                }
            }
        }
    };
}

// The built-in models: one line each, the default first.
aero_models! {
    Fmm2022 => "fmm2022",
    Fmm2022Tour => "fmm2022-tour",
    Fmm2022Re => "fmm2022-re",
    NathanLyu => "nathan-lyu",
}

impl AeroModel {
    /// [`CoefficientModel::reynolds_at_reference_air`] of the model: the built-in models
    /// take it, a table does not.
    pub fn reynolds_at_reference_air(&self) -> bool {
        !matches!(self, Self::Table(_))
    }

    /// Coefficients (dispatching on the model; the integrator dispatches once per batch).
    pub fn coefficients(&self, s: f64, re: f64) -> Coefficients {
        struct At(f64, f64);
        impl ModelVisitor for At {
            type Output = Coefficients;
            fn visit<C: CoefficientModel>(self, m: &C) -> Coefficients {
                m.coefficients(self.0, self.1)
            }
        }
        self.visit(At(s, re))
    }
}
