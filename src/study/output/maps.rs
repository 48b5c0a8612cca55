//! The per-map files of a study: matrices (`<stem>.csv`, top row first) and their pictures
//! (`<stem>.svg`, drawn from block means), streamed a band of rows at a time or written from
//! the matrix lines the long table's pass kept.

use std::fs::File;
use std::io::Write as _;
use std::ops::Range;
use std::path::{Path, PathBuf};

use rayon::prelude::*;

use crate::report::heatmap::{matrix_csv_header, BlockMeans, Heatmap, Scale};

use super::super::sweep::Prepared;
use super::long::HeldMatrices;
use super::{band_rows, create, io_err, pipeline, push_matrix_row, put, X_LABEL, Y_LABEL};

/// The block means of the pictures of a map set, from an ascending pass over the rows.
pub(super) fn block_means(p: &Prepared, n_maps: usize, fill: &MapFill<'_>) -> Vec<BlockMeans> {
    let (ny, nz) = (p.ys_mm.len(), p.zs_mm.len());
    let per = band_rows(nz);
    let mut blocks: Vec<BlockMeans> = (0..n_maps).map(|_| BlockMeans::new(ny, nz)).collect();
    let make = |b: usize, values: &mut Vec<Vec<f64>>| {
        values.resize_with(n_maps, Vec::new);
        fill(b * per..((b + 1) * per).min(ny), values);
    };
    let mut consume = |_: usize, values: &mut Vec<Vec<f64>>| -> std::io::Result<()> {
        for (b, v) in blocks.iter_mut().zip(values) {
            b.add_rows(v);
        }
        Ok(())
    };
    pipeline(
        ny.div_ceil(per),
        [Vec::new(), Vec::new()],
        &make,
        &mut consume,
    )
    .expect("no I/O in this pass");
    blocks
}

/// Values of each map of a set on a band of rows: `fill(rows, out)`, row-major.
pub(super) type MapFill<'a> = dyn Fn(Range<usize>, &mut [Vec<f64>]) + Sync + 'a;

/// One map of a set written by [`write_maps`].
pub(super) struct MapFile {
    /// Path without extension, relative to the output folder.
    pub stem: String,
    /// Picture title.
    pub title: String,
    /// Colour-bar label.
    pub value_label: String,
    /// Colour scale.
    pub scale: Scale,
}

/// A band of a map set: per map its values (row-major) and its matrix lines (top row first).
#[derive(Default)]
struct MapBand {
    values: Vec<Vec<f64>>,
    lines: Vec<Vec<Vec<u8>>>,
}

/// Open the matrix files of `maps` (`<stem>.csv`) and write their header.
fn matrix_files(root: &Path, p: &Prepared, maps: &[MapFile]) -> std::io::Result<Vec<File>> {
    let header = matrix_csv_header(&p.zs_mm);
    maps.iter()
        .map(|m| {
            let rel = PathBuf::from(format!("{}.csv", m.stem));
            let mut f = create(root, &rel)?;
            f.write_all(&header).map_err(|e| io_err(&rel, e))?;
            Ok(f)
        })
        .collect()
}

/// The matrices (`<stem>.csv`, top row first) of maps over the study grid; `fill(rows, out)`
/// gives each map's values on `rows` (row-major). Returns the number of files written.
pub(super) fn write_maps(
    root: &Path,
    p: &Prepared,
    maps: &[MapFile],
    fill: &MapFill<'_>,
) -> std::io::Result<usize> {
    let (ny, nz) = (p.ys_mm.len(), p.zs_mm.len());
    let per = band_rows(nz);
    let bands = ny.div_ceil(per);
    let mut files = matrix_files(root, p, maps)?;
    // Bands from the top of the face down.
    let band_range = |b: usize| {
        let k = bands - 1 - b;
        k * per..((k + 1) * per).min(ny)
    };
    let make = |b: usize, band: &mut MapBand| {
        let rows = band_range(b);
        band.values.resize_with(maps.len(), Vec::new);
        fill(rows.clone(), &mut band.values);
        band.lines.resize_with(maps.len(), Vec::new);
        for (vals, lines) in band.values.iter().zip(band.lines.iter_mut()) {
            lines.resize_with(rows.len(), Vec::new);
            lines.par_iter_mut().enumerate().for_each(|(k, out)| {
                // Line k of the band is row `rows.end - 1 - k`.
                let r = rows.len() - 1 - k;
                out.clear();
                push_matrix_row(out, p.ys_mm[rows.start + r], &vals[r * nz..(r + 1) * nz]);
            });
        }
    };
    let mut consume = |_: usize, band: &mut MapBand| -> std::io::Result<()> {
        for (i, f) in files.iter_mut().enumerate() {
            for l in &band.lines[i] {
                f.write_all(l)?;
            }
        }
        Ok(())
    };
    pipeline(
        bands,
        [MapBand::default(), MapBand::default()],
        &make,
        &mut consume,
    )?;
    Ok(maps.len())
}

/// The matrices of `maps` from the lines [`long_pass`] kept (bands and rows reversed: top row
/// first), the files written in parallel. Returns the number of files written.
pub(super) fn write_held_maps(
    root: &Path,
    p: &Prepared,
    maps: &[MapFile],
    held: &HeldMatrices,
) -> std::io::Result<usize> {
    let files = matrix_files(root, p, maps)?;
    files
        .into_par_iter()
        .enumerate()
        .try_for_each(|(o, mut f)| -> std::io::Result<()> {
            let mut lines = held
                .iter()
                .rev()
                .flat_map(|band| band.iter().rev().map(|row| &row[o][..]));
            // A few hundred lines a system call, straight from where they were formatted.
            loop {
                let batch: Vec<std::io::IoSlice<'_>> = lines
                    .by_ref()
                    .take(256)
                    .map(std::io::IoSlice::new)
                    .collect();
                if batch.is_empty() {
                    return Ok(());
                }
                write_all_slices(&mut f, &batch)?;
            }
        })
        .map_err(|e| io_err(Path::new("maps"), e))?;
    Ok(maps.len())
}

/// Write every byte of `slices` to `f`, in order, with vectored writes.
fn write_all_slices(f: &mut File, slices: &[std::io::IoSlice<'_>]) -> std::io::Result<()> {
    let (mut i, mut skip) = (0, 0);
    while i < slices.len() {
        let mut head: Vec<std::io::IoSlice<'_>> = Vec::with_capacity(slices.len() - i);
        head.push(std::io::IoSlice::new(&slices[i][skip..]));
        head.extend_from_slice(&slices[i + 1..]);
        let mut n = match f.write_vectored(&head) {
            Ok(0) => return Err(std::io::ErrorKind::WriteZero.into()),
            Ok(n) => n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(e),
        };
        // Skip what was written: whole slices, then part of the next.
        while i < slices.len() && n >= slices[i].len() - skip {
            n -= slices[i].len() - skip;
            i += 1;
            skip = 0;
        }
        skip += n;
    }
    Ok(())
}

/// The pictures (`<stem>.svg`) of `maps`, drawn from their block means. Returns the number of
/// files written.
pub(super) fn write_svgs(
    root: &Path,
    p: &Prepared,
    maps: &[MapFile],
    blocks: &[BlockMeans],
) -> std::io::Result<usize> {
    maps.par_iter().zip(blocks).try_for_each(|(m, b)| {
        let map = Heatmap {
            title: &m.title,
            x_label: X_LABEL,
            y_label: Y_LABEL,
            value_label: &m.value_label,
            xs: &p.zs_mm,
            ys: &p.ys_mm,
            values: &[],
            marker: Some((0.0, 0.0)),
            scale: m.scale,
        };
        put(
            root,
            Path::new(&format!("{}.svg", m.stem)),
            b.svg(&map).as_bytes(),
        )
    })?;
    Ok(maps.len())
}
