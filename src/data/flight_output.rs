//! The flight command's output file: written to a temporary file beside it, which replaces it
//! only when every row has flown (so a failed run leaves the output as it was).

use std::path::{Path, PathBuf};

use crate::data::{safe_write, DataError};

/// A temporary file beside the output that replaces it on [`commit`](Self::commit) and is
/// removed otherwise.
pub(crate) struct Temporary {
    /// The open temporary.
    pub(crate) file: std::fs::File,
    tmp: PathBuf,
    out: PathBuf,
    done: bool,
}

impl Temporary {
    /// Create the temporary beside `out` (refusing an output that must not be replaced).
    pub(crate) fn create(out: &Path) -> Result<Self, DataError> {
        let parent = match out.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_owned(),
            _ => PathBuf::from("."),
        };
        let name = out
            .file_name()
            .ok_or_else(|| DataError::file(out, "not a file path"))?
            .to_string_lossy()
            .into_owned();
        std::fs::create_dir_all(&parent).map_err(|e| {
            DataError::file(
                out,
                format!("cannot create folder {}: {e}", parent.display()),
            )
        })?;
        safe_write::check_output(out, false)?;
        safe_write::clean_stale_temporaries(out);
        let tmp = parent.join(format!(".{name}.{}.tmp", std::process::id()));
        crate::data::output_plan::register_temporary(&tmp);
        let file = std::fs::File::create(&tmp)
            .map_err(|e| DataError::file(out, format!("cannot write: {e}")))?;
        Ok(Self {
            file,
            tmp,
            out: out.to_owned(),
            done: false,
        })
    }

    /// Replace the output by the temporary.
    pub(crate) fn commit(mut self) -> Result<(), DataError> {
        let r = self
            .file
            .sync_all()
            .and_then(|()| std::fs::rename(&self.tmp, &self.out));
        r.map_err(|e| DataError::file(&self.out, format!("cannot write: {e}")))?;
        crate::data::output_plan::forget_temporary(&self.tmp);
        self.done = true;
        Ok(())
    }
}

impl Drop for Temporary {
    fn drop(&mut self) {
        if !self.done {
            let _ = std::fs::remove_file(&self.tmp);
            crate::data::output_plan::forget_temporary(&self.tmp);
        }
    }
}
