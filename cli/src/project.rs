//! The options every command reads in layers, each over the one before (the layering of
//! typos' `config.rs`): the built-in defaults, then a project file, then the flags given.
//!
//! The project file is `smash.toml` in the current directory or the nearest directory above
//! it (or the file `SMASH_CONFIG` names; `SMASH_CONFIG=none`: no file). Its `[defaults]` table
//! states what is true of the user's whole setup, so that it need not be repeated on every
//! command line: the launch monitor's export format, which way its heel–toe offset points,
//! the instruments' noise class or file, the impact-location noise and the user-defined
//! effects. A flag given on the command line wins over the file; a key the file leaves out
//! keeps the built-in default. Every value taken from the file is named on stderr, so a run
//! never depends on it silently. Paths in the file (`noise`, `effect_defs`, a mapping file
//! named by `format`) are relative to the file's directory, wherever the command runs.
//!
//! ```toml
//! [defaults]
//! format = "trackman"
//! impact_offset_positive = "toe"
//! instrument = "radar"
//! impact_noise_mm = [3.0, 2.5]
//! effect_defs = "effects/my_effects.toml"
//! ```

use std::path::{Path, PathBuf};

use serde::Deserialize;

use smash::data::toml_check::parse_toml;

/// The file name looked for.
pub const FILE_NAME: &str = "smash.toml";

/// What a project file may hold.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct ProjectFile {
    #[serde(default)]
    defaults: Defaults,
}

/// The `[defaults]` table: each key the value of the flag of the same name (`-` for `_`),
/// checked as the flag is when the file is read, whatever the command.
#[derive(Debug, Default, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Defaults {
    /// `--format`.
    pub format: Option<String>,
    /// `--impact-offset-positive` (`toe` or `heel`).
    pub impact_offset_positive: Option<smash::data::import::OffsetSide>,
    /// `--instrument`.
    pub instrument: Option<String>,
    /// `--noise`.
    pub noise: Option<PathBuf>,
    /// `--impact-noise-mm`, `[vertical, heel-toe]`.
    pub impact_noise_mm: Option<[f64; 2]>,
    /// `--effect-defs`.
    pub effect_defs: Option<PathBuf>,
    /// `instrument`, parsed.
    #[serde(skip)]
    instrument_class: Option<smash::diagnose::noise_floor::InstrumentClass>,
    /// `impact_noise_mm`, checked.
    #[serde(skip)]
    impact_noise: Option<smash::measurement::ImpactNoise>,
    /// The project file these defaults were read from.
    #[serde(skip)]
    file: Option<PathBuf>,
}

/// What a project file holds, for the message that lists the allowed keys.
const LAYOUT: &str = "a smash.toml holds a [defaults] table with format, \
    impact_offset_positive, instrument, noise, impact_noise_mm and effect_defs";

/// The project file that applies in `dir`: `SMASH_CONFIG`'s file (none for `none`), else the
/// nearest `smash.toml` at or above `dir`.
pub fn find(dir: &Path) -> Option<PathBuf> {
    match std::env::var_os("SMASH_CONFIG") {
        Some(v) if v == "none" => None,
        Some(v) => Some(PathBuf::from(v)),
        None => dir
            .ancestors()
            .map(|d| d.join(FILE_NAME))
            .find(|p| p.is_file()),
    }
}

/// The defaults of the project file at `path`, its paths made relative to where the command
/// runs (they are written relative to the file).
pub fn read(path: &Path) -> anyhow::Result<Defaults> {
    // An input like any other: no output of the command may be written over it.
    smash::data::safe_write::note_input_named(path, "the project file");
    let text = std::fs::read_to_string(path).map_err(|e| {
        smash::data::DataError::file(path, format!("cannot read the project file: {e}"))
    })?;
    let file: ProjectFile = parse_toml(path, &text, LAYOUT)?;
    let mut d = file.defaults;
    d.file = Some(path.to_owned());
    let bad = |key: &str, msg: String| -> anyhow::Error {
        smash::data::DataError::at(path, None, Some(format!("key defaults.{key}")), msg).into()
    };
    if let Some(name) = &d.instrument {
        d.instrument_class =
            Some(crate::likelihood::parse_instrument(name).map_err(|e| bad("instrument", e))?);
    }
    if let Some([y, z]) = d.impact_noise_mm {
        d.impact_noise =
            Some(crate::impact_noise_from_mm(y, z).map_err(|e| bad("impact_noise_mm", e.0))?);
    }
    // Every path the file names is relative to the file's folder, not to where the command
    // runs: `noise`, `effect_defs`, and `format` when it names a mapping file, not a preset.
    let base = path.parent().unwrap_or(Path::new(""));
    for p in [&mut d.noise, &mut d.effect_defs].into_iter().flatten() {
        if p.is_relative() {
            *p = base.join(&*p);
        }
    }
    if let Some(f) = &mut d.format {
        if !is_named_format(f) && Path::new(f.as_str()).is_relative() {
            *f = base.join(f.as_str()).to_string_lossy().into_owned();
        }
    }
    Ok(d)
}

/// Whether `format` names a format rather than a mapping file: `shots`, `auto`, a preset or
/// one of its aliases (what [`smash::data::import::load_mapping`] looks up before a path).
fn is_named_format(format: &str) -> bool {
    use smash::data::import::{PRESETS, PRESET_ALIASES};
    let key = format.to_ascii_lowercase();
    key == "shots"
        || key == "auto"
        || PRESETS.iter().any(|(n, _)| *n == key)
        || PRESET_ALIASES.iter().any(|(a, _)| *a == key)
}

/// The options of one command that a project file may set, borrowed from its parsed flags.
#[derive(Default)]
pub struct Layered<'a> {
    /// `--effect-defs`.
    pub effect_defs: Option<&'a mut crate::EffectDefsArgs>,
    /// `--format`, `--impact-offset-positive`.
    pub shots_format: Option<&'a mut crate::ShotsFormatArgs>,
    /// `--impact-noise-mm`, and whether a flag said the locations are exact.
    pub measurement: Option<(&'a mut crate::MeasurementArgs, bool)>,
    /// `--instrument` and `--noise`.
    pub noise: Option<(
        &'a mut Option<smash::diagnose::noise_floor::InstrumentClass>,
        &'a mut Option<PathBuf>,
    )>,
}

impl Defaults {
    /// Set in `opts` what its flags left unset and this file states; what was taken, one
    /// `KEY = VALUE` each.
    pub fn apply(&self, opts: Layered<'_>) -> Vec<String> {
        let mut taken = Vec::new();
        if let (Some(e), Some(p)) = (opts.effect_defs, &self.effect_defs) {
            if e.effect_defs.is_none() {
                e.effect_defs = Some(p.clone());
                taken.push(format!("effect_defs = {}", p.display()));
            }
        }
        if let Some(f) = opts.shots_format {
            if let (None, Some(v)) = (&f.format, &self.format) {
                f.format = Some(v.clone());
                f.format_from.clone_from(&self.file);
                taken.push(format!("format = {v}"));
            }
            if let (None, Some(side)) = (f.impact_offset_positive, self.impact_offset_positive) {
                let side = crate::OffsetSideArg::from(side);
                f.impact_offset_positive = Some(side);
                taken.push(format!("impact_offset_positive = {}", side.name()));
            }
        }
        if let (Some((m, exact)), Some(noise), Some([y, z])) =
            (opts.measurement, self.impact_noise, self.impact_noise_mm)
        {
            if m.impact_noise_mm.is_none() && !exact {
                m.impact_noise_mm = Some(noise);
                taken.push(format!("impact_noise_mm = [{y}, {z}]"));
            }
        }
        if let Some((instrument, noise)) = opts.noise {
            // A flag for either wins over the file's both: --noise over --instrument holds.
            if instrument.is_none() && noise.is_none() {
                if let Some(p) = &self.noise {
                    *noise = Some(p.clone());
                    taken.push(format!("noise = {}", p.display()));
                } else if let (Some(class), Some(name)) = (self.instrument_class, &self.instrument)
                {
                    *instrument = Some(class);
                    taken.push(format!("instrument = {name}"));
                }
            }
        }
        taken
    }
}
