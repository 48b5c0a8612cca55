//! `import`: a launch-monitor export converted to a shots file.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::inputs::ShotsFormat;
use super::Notes;
use crate::data::import::Imported;
use crate::data::shots::ShotTable;

/// Settings of `import`: how the export is read (its `format` unset: `auto`, the layout
/// recognised from the header or the JSON keys).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct ImportSettings {
    /// How the export is read.
    #[serde(flatten)]
    pub shots: ShotsFormat,
}

/// A converted export: the shots file's bytes and, read back, the shots with a complete
/// delivery (none when no row has one).
pub struct Converted {
    /// The conversion (its `csv` is the shots file).
    pub imported: Imported,
    /// The shots file read back.
    pub table: Option<ShotTable>,
}

/// Convert the export at `path` (the import's notes to `notes`).
pub fn run(
    settings: &ImportSettings,
    path: &Path,
    notes: &mut dyn Notes,
) -> anyhow::Result<Converted> {
    let format = settings.shots.format.as_deref().unwrap_or("auto");
    if format == "shots" {
        anyhow::bail!(
            "--format shots: `shots` is the shots-file format itself, so there is nothing to \
             convert; give the export's format: auto (the default: recognised from the header), \
             a preset (trackman, foresight, …: smash import --help lists them) or a mapping \
             file NAME.toml"
        );
    }
    let imported = settings.shots.import(path, format, notes)?;
    // Shots without a complete delivery or with estimated values are written all the same
    // (flight uses their launch); the rest must read back.
    let table = imported.checked_read_back(path, settings.shots.strict)?;
    Ok(Converted { imported, table })
}
