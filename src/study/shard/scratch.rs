//! The scratch file of a merge: every variant's grid rows in binary, written as the shards are
//! read and served a band at a time to the outputs ([`DiskGrids`]).

use std::io::Write as _;
use std::path::{Path, PathBuf};

use crate::data::DataError;
use crate::sweep::kernel::LaunchGrid;

use super::super::sweep::{GridSource, Prepared};

/// The face maps of a merged study, read back from the shards into a binary scratch file (one
/// fixed-size record per variant and grid row: the five launch components in SI units as
/// little-endian `f64`, then the validity bytes) and served a band at a time to
/// [`super::output::write_study`]: the merge's memory does not grow with the study. The scratch
/// file is removed when this is dropped.
pub struct DiskGrids {
    file: std::sync::Mutex<std::fs::File>,
    path: PathBuf,
    ny: usize,
    nz: usize,
}

impl DiskGrids {
    /// Bytes of one grid row's record.
    fn record(nz: usize) -> usize {
        nz * (5 * 8 + 1)
    }
}

impl Drop for DiskGrids {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

impl GridSource for DiskGrids {
    fn grid_rows(
        &self,
        variant: usize,
        rows: std::ops::Range<usize>,
        out: &mut LaunchGrid,
    ) -> std::io::Result<()> {
        use std::io::{Read, Seek, SeekFrom};
        let (nz, rec) = (self.nz, Self::record(self.nz));
        let mut bytes = vec![0u8; rows.len() * rec];
        {
            let mut f = self.file.lock().unwrap_or_else(|e| e.into_inner());
            f.seek(SeekFrom::Start(
                ((variant * self.ny + rows.start) * rec) as u64,
            ))
            .and_then(|_| f.read_exact(&mut bytes))
            .map_err(|e| {
                std::io::Error::new(
                    e.kind(),
                    format!("{}: cannot read back: {e}", self.path.display()),
                )
            })?;
        }
        *out = LaunchGrid::with_len(0);
        for r in bytes.chunks_exact(rec) {
            let comp = |k: usize| {
                r[k * 8 * nz..(k + 1) * 8 * nz]
                    .chunks_exact(8)
                    .map(|b| f64::from_le_bytes(b.try_into().expect("8 bytes")))
            };
            out.ball_speed_m_s.extend(comp(0));
            out.launch_angle_rad.extend(comp(1));
            out.azimuth_rad.extend(comp(2));
            out.backspin_rad_s.extend(comp(3));
            out.sidespin_rad_s.extend(comp(4));
            out.valid.extend(r[40 * nz..].iter().map(|&b| b == 1));
        }
        Ok(())
    }
}

/// The scratch file of [`DiskGrids`] being written: sized for every grid row, each row written
/// at its place.
pub(super) struct ScratchWriter {
    file: std::io::BufWriter<std::fs::File>,
    path: PathBuf,
    guard: ScratchGuard,
    record: Vec<u8>,
    at_byte: u64,
    ny: usize,
    nz: usize,
}

impl ScratchWriter {
    pub(super) fn create(path: &Path, p: &Prepared) -> Result<Self, DataError> {
        let (nv, ny, nz) = (p.variants.len(), p.ys_mm.len(), p.zs_mm.len());
        let err = |e: std::io::Error| DataError::file(path, format!("cannot write: {e}"));
        let file = std::fs::OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(true)
            .open(path)
            .map_err(err)?;
        let guard = ScratchGuard(Some(path.to_path_buf()));
        let rec = DiskGrids::record(nz);
        file.set_len((nv * ny * rec) as u64).map_err(err)?;
        Ok(Self {
            file: std::io::BufWriter::with_capacity(1 << 20, file),
            path: path.to_path_buf(),
            guard,
            record: Vec::with_capacity(rec),
            at_byte: 0,
            ny,
            nz,
        })
    }

    fn err(&self, e: std::io::Error) -> DataError {
        DataError::file(&self.path, format!("cannot write: {e}"))
    }

    /// Grid row `row` of variant `variant`.
    pub(super) fn put_row(
        &mut self,
        variant: usize,
        row: usize,
        g: &LaunchGrid,
    ) -> Result<(), DataError> {
        use std::io::{Seek, SeekFrom};
        self.record.clear();
        for c in [
            &g.ball_speed_m_s,
            &g.launch_angle_rad,
            &g.azimuth_rad,
            &g.backspin_rad_s,
            &g.sidespin_rad_s,
        ] {
            for v in c {
                self.record.extend_from_slice(&v.to_le_bytes());
            }
        }
        self.record.extend(g.valid.iter().map(|&b| u8::from(b)));
        let rec = DiskGrids::record(self.nz) as u64;
        let pos = (variant * self.ny + row) as u64 * rec;
        // Rows arrive in order within a shard: seek only when they jump.
        if self.at_byte != pos {
            let r = self.file.seek(SeekFrom::Start(pos));
            r.map_err(|e| self.err(e))?;
        }
        let r = self.file.write_all(&self.record);
        r.map_err(|e| self.err(e))?;
        self.at_byte = pos + rec;
        Ok(())
    }

    /// The written scratch file, to read back from.
    pub(super) fn finish(mut self) -> Result<DiskGrids, DataError> {
        let path = self.guard.take();
        let file = self.file.into_inner().map_err(|e| {
            let _ = std::fs::remove_file(&path);
            DataError::file(&path, format!("cannot write: {}", e.error()))
        })?;
        Ok(DiskGrids {
            file: std::sync::Mutex::new(file),
            path,
            ny: self.ny,
            nz: self.nz,
        })
    }
}

/// Removes a scratch file when dropped, unless taken.
struct ScratchGuard(Option<PathBuf>);

impl ScratchGuard {
    fn take(&mut self) -> PathBuf {
        self.0.take().expect("taken once")
    }
}

impl Drop for ScratchGuard {
    fn drop(&mut self) {
        if let Some(p) = &self.0 {
            let _ = std::fs::remove_file(p);
        }
    }
}
