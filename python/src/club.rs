//! `Club`: a club file (clubhead, ball, effects) held in memory, so that a notebook can build
//! variants in a loop. Every club is made by the library's club-file reader, from a file or
//! from club-file text, so a variant is checked exactly as a file would be.

use std::path::{Path, PathBuf};

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use smash::data::club_file::{club_toml, parse_club, parse_club_as, read_club};
use smash::effects::user::Offer;
use smash::effects::EffectId;
use smash::ClubSpec;

use crate::{to_py, SmashError};

/// A club: clubhead, ball and effects, as read from a club file (TOML).
#[pyclass(frozen, module = "smash_golf._native")]
pub struct Club {
    pub(crate) spec: ClubSpec,
    /// The name of its file in messages (the path it was read from, or a label).
    pub(crate) label: PathBuf,
}

impl Club {
    fn parse(label: &Path, text: &str) -> PyResult<Self> {
        let spec = parse_club(label, text).map_err(|e| to_py(e.into()))?;
        Ok(Self {
            spec,
            label: label.to_path_buf(),
        })
    }

    /// This club's file text with `extra` appended, read back as a new club (its user-defined
    /// effects offered to model searches as they were: [`Offer::Reread`]).
    fn variant(&self, extra: &str) -> PyResult<Self> {
        let mut text = club_toml(&self.spec, "");
        text.push_str(extra);
        let spec = parse_club_as(&self.label, &text, Offer::Reread).map_err(|e| to_py(e.into()))?;
        Ok(Self {
            spec,
            label: self.label.clone(),
        })
    }
}

/// The parameters of an effect kind as dicts: key, unit, default (its neutral value), lower and
/// upper (physical bounds), plausible (the range a real driver impact shows), doc.
pub(crate) fn param_specs(py: Python<'_>, id: EffectId) -> PyResult<Bound<'_, PyList>> {
    let out = PyList::empty(py);
    for s in id.params() {
        let d = PyDict::new(py);
        d.set_item("key", s.key)?;
        d.set_item("unit", s.unit)?;
        d.set_item("default", s.default)?;
        d.set_item("lower", s.lower)?;
        d.set_item("upper", s.upper)?;
        d.set_item("plausible", (s.plausible.0, s.plausible.1))?;
        d.set_item("doc", s.doc)?;
        out.append(d)?;
    }
    Ok(out)
}

#[pymethods]
impl Club {
    /// Read a club file (TOML), exactly as `smash --club PATH` does.
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<Self> {
        let spec = read_club(&path).map_err(|e| to_py(e.into()))?;
        Ok(Self { spec, label: path })
    }

    /// A club from club-file text (`label` names it in messages).
    #[staticmethod]
    #[pyo3(signature = (text, label = "<club>"))]
    fn from_toml(text: &str, label: &str) -> PyResult<Self> {
        Self::parse(Path::new(label), text)
    }

    /// The club's name (`[club] name`).
    #[getter]
    fn name(&self) -> &str {
        &self.spec.name
    }

    /// The file it was read from, or its label.
    #[getter]
    fn label(&self) -> PathBuf {
        self.label.clone()
    }

    /// The effects, in file order: dicts with `name`, `group` (None: every group) and `params`
    /// (parameter key → value, in the unit its key names: `dm_g` in g, `dy_mm` in mm, …).
    #[getter]
    fn effects<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let out = PyList::empty(py);
        for e in &self.spec.effects {
            let d = PyDict::new(py);
            d.set_item("name", e.kind().name())?;
            d.set_item("group", e.group())?;
            let params = PyDict::new(py);
            for (s, v) in e.kind().params().iter().zip(e.values()) {
                params.set_item(s.key, v)?;
            }
            d.set_item("params", params)?;
            out.append(d)?;
        }
        Ok(out)
    }

    /// This club with one more effect: `name` (a library or registered user-defined effect),
    /// optional `group` (the shots group it applies to; None: all), and its parameters by key in
    /// their units (missing keys: an error naming them, as in a club file).
    #[pyo3(signature = (name, group = None, **params))]
    fn with_effect(
        &self,
        name: &str,
        group: Option<&str>,
        params: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let mut t = toml::Table::new();
        t.insert("name".into(), name.into());
        if let Some(g) = group {
            t.insert("group".into(), g.into());
        }
        for (k, v) in params.into_iter().flat_map(|p| p.iter()) {
            let key: String = k.extract()?;
            let value: f64 = v.extract().map_err(|_| {
                SmashError::new_err(format!(
                    "effect '{name}': parameter '{key}' must be a number"
                ))
            })?;
            t.insert(key, value.into());
        }
        let mut doc = toml::Table::new();
        doc.insert("effect".into(), toml::Value::Array(vec![t.into()]));
        let extra = toml::to_string(&doc).map_err(|e| SmashError::new_err(e.to_string()))?;
        self.variant(&format!("\n{extra}"))
    }

    /// This club without any effects (the nominal clubhead and ball).
    fn without_effects(&self) -> PyResult<Self> {
        let spec = self
            .spec
            .with_effects(Vec::new())
            .map_err(|e| SmashError::new_err(e.to_string()))?;
        Ok(Self {
            spec,
            label: self.label.clone(),
        })
    }

    /// The club-file text (TOML) of this club, with `comment` lines at the top; reads back to
    /// the same club bit for bit.
    #[pyo3(signature = (comment = ""))]
    fn to_toml(&self, comment: &str) -> String {
        club_toml(&self.spec, comment)
    }

    fn __repr__(&self) -> String {
        let effects: Vec<String> = self
            .spec
            .effects
            .iter()
            .map(|e| match e.group() {
                Some(g) => format!("{}@{g}", e.kind().name()),
                None => e.kind().name().to_owned(),
            })
            .collect();
        format!(
            "Club(name={:?}, effects=[{}])",
            self.spec.name,
            effects.join(", ")
        )
    }
}
