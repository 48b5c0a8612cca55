//! Study outputs: CSV tables, CSV matrices and SVG heatmaps, written into a folder the CLI
//! provides (a temporary one it swaps in as a unit: [`crate::data::write_folder_atomic_with`]).
//! No NaN reaches a file: values that cannot be computed are empty cells.
//!
//! The face maps are streamed: a band of grid rows is computed (or read back, for a merge), its
//! numbers formatted in parallel and written, while the next band is computed. Memory is a few
//! bands whatever the grid (see [`BAND_POINTS`]); the pictures are drawn from block means
//! accumulated band by band. The long table is written in ascending rows and the matrices top
//! row first. Each number is formatted once, into its matrix line, and the long table's line is
//! assembled from those cells; a variant's matrix lines are kept until its long-table rows are
//! written while they fit in [`HELD_MATRIX_BYTES`] (an 801 × 801 grid's do). Larger grids are
//! computed and formatted a second time, top row first, for the matrices. Map values are
//! written to ten significant digits ([`cells`]); coordinates, design values and the small
//! tables keep every digit of their shortest round-trip form.
//!
//! The files are not synced to the disk one by one (`fsync` would hold a large study to the
//! disk's sustained write rate, a few hundred MB/s here, instead of the page cache's): the folder
//! swap still makes a failed or interrupted run leave the previous outputs as they were.
//!
//! | file | content |
//! |---|---|
//! | `study.toml` | the resolved study (every default filled in) |
//! | `variants.csv` | one row per variant: id, design variables, summary metrics |
//! | `maps_long.csv` | one row per variant × grid point: id, variables, `y_mm`, `z_mm`, `valid`, outputs |
//! | `maps/v<id>_<output>.csv` / `.svg` | matrix (rows top to bottom) and heatmap per variant and output |
//! | `sensitivity.csv` | d metric / d variable at the base design, ranked within each metric |
//! | `sensitivity/d_<output>__d_<variable>.csv` / `.svg` | sensitivity maps |
//! | `optimise/path.csv` | best objective and design per optimiser iteration |
//! | `optimise/result.csv` | base vs optimum: objective, design variables, mass properties, metrics |
//! | `optimise/optimum_club.toml` | the optimum as a club file |

use std::fmt::Write as _;
use std::fs::File;
use std::io::Write as _;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use rayon::prelude::*;

use crate::data::fmt_f64;
use crate::data::number::push_cell;
use crate::report::heatmap::{BlockMeans, Scale};
use crate::sweep::kernel::LaunchGrid;
use crate::units::{mm, mph};

mod cells;
mod long;
mod maps;
mod tables;

pub use cells::{push_map_cell, push_matrix_row, MAP_DIGITS};
pub use long::HELD_MATRIX_BYTES;

use long::{LongRows, LongWriter, SpareLines};
use maps::MapFile;

use super::design::DesignVar;
use super::metrics::{metric_names, Output};
use super::optimise::OptimiseResult;
use super::sensitivity::Sensitivity;
use super::spec::resolved_toml;
use super::sweep::{GridSource, Prepared};

/// Files to write: path relative to the output folder, bytes.
pub type Files = Vec<(PathBuf, Vec<u8>)>;

/// A CSV cell: shortest round-trip form, empty for NaN.
pub fn cell(v: f64) -> String {
    if v.is_finite() {
        fmt_f64(v)
    } else {
        String::new()
    }
}

pub(super) const X_LABEL: &str = "impact z (toward toe), mm";
pub(super) const Y_LABEL: &str = "impact y (up the face), mm";

fn id_width(n: usize) -> usize {
    (n.saturating_sub(1)).to_string().len().max(3)
}

/// How the long table is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum TableFormat {
    /// `maps_long.csv`: text, for small studies and any tool.
    #[default]
    Csv,
    /// `maps_long.parquet`: columnar, typed and compressed (Snappy); invalid cells are nulls.
    /// Several times smaller and faster to write and to read (pandas, polars, Arrow) than CSV.
    Parquet,
}

/// Grid points per streamed band (about 64 k: a few MB of values and text per band).
pub const BAND_POINTS: usize = 1 << 16;

pub(super) fn io_err(path: &Path, e: std::io::Error) -> std::io::Error {
    std::io::Error::new(e.kind(), format!("{}: {e}", path.display()))
}

/// Write `bytes` to `root/rel` (creating folders).
pub(super) fn put(root: &Path, rel: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let mut f = create(root, rel)?;
    f.write_all(bytes).map_err(|e| io_err(rel, e))
}

pub(super) fn create(root: &Path, rel: &Path) -> std::io::Result<File> {
    let path = root.join(rel);
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent).map_err(|e| io_err(rel, e))?;
    }
    File::create(&path).map_err(|e| io_err(rel, e))
}

/// Rows per band for a grid of `nz` columns (at least one row: an axis has at most 100,000
/// points, so a band stays a few tens of MB).
pub(super) fn band_rows(nz: usize) -> usize {
    (BAND_POINTS / nz.max(1)).max(1)
}

/// Produce `bands` items with `make` into two alternating buffers and hand each, in order, to
/// `consume`: the next band is made while the previous one is consumed (which may take parts
/// of it, e.g. text to keep).
pub(super) fn pipeline<T: Send + Sync>(
    bands: usize,
    bufs: [T; 2],
    make: &(dyn Fn(usize, &mut T) + Sync),
    consume: &mut (dyn FnMut(usize, &mut T) -> std::io::Result<()> + Send),
) -> std::io::Result<()> {
    if bands == 0 {
        return Ok(());
    }
    let [mut cur, mut next] = bufs;
    make(0, &mut cur);
    for b in 0..bands {
        let (done, ()) = rayon::join(
            || consume(b, &mut cur),
            || {
                if b + 1 < bands {
                    make(b + 1, &mut next)
                }
            },
        );
        done?;
        std::mem::swap(&mut cur, &mut next);
    }
    Ok(())
}

/// Every output file of a complete (unsharded or merged) run, written under `root`, with the
/// face maps from `grids` and each variant's summary metrics in `metrics`. Returns the number
/// of files written.
pub fn write_study(
    root: &Path,
    p: &Prepared,
    grids: &dyn GridSource,
    metrics: &[Vec<f64>],
    sens: &[Sensitivity],
    opt: Option<&OptimiseResult>,
    format: TableFormat,
) -> std::io::Result<usize> {
    Ok(write_study_maps(root, p, grids, (metrics, sens, opt), format)?.0)
}

/// Most blocks per axis of the face maps [`write_study_maps`] keeps for a report: a small
/// multiple is drawn 200 px wide, so finer blocks would not show.
pub const REPORT_MAP_CELLS: usize = 40;

/// [`write_study`], also returning every variant's face maps (per variant, one per study
/// output) as block means of at most [`REPORT_MAP_CELLS`] per axis: the maps of the report,
/// summed as the maps are written (they are never held whole).
pub fn write_study_maps(
    root: &Path,
    p: &Prepared,
    grids: &dyn GridSource,
    (metrics, sens, opt): (&[Vec<f64>], &[Sensitivity], Option<&OptimiseResult>),
    format: TableFormat,
) -> std::io::Result<(usize, Vec<Vec<BlockMeans>>)> {
    write_study_holding(
        root,
        p,
        grids,
        (metrics, sens, opt),
        format,
        HELD_MATRIX_BYTES,
    )
}

/// [`write_study`], keeping at most `held_matrix_bytes` of matrix text per variant.
fn write_study_holding(
    root: &Path,
    p: &Prepared,
    grids: &dyn GridSource,
    (metrics, sens, opt): (&[Vec<f64>], &[Sensitivity], Option<&OptimiseResult>),
    format: TableFormat,
    held_matrix_bytes: usize,
) -> std::io::Result<(usize, Vec<Vec<BlockMeans>>)> {
    let s = &p.study;
    put(root, Path::new("study.toml"), resolved_toml(s).as_bytes())?;
    let axes: Vec<DesignVar> = s.design.axes.iter().map(|(v, _)| *v).collect();
    let names = metric_names(s.distribution.is_some());
    let variants = tables::variants_table(p, &axes, &names, metrics);
    put(root, Path::new("variants.csv"), variants.as_bytes())?;
    let (n_maps, face_maps) = write_face_maps(root, p, grids, &axes, format, held_matrix_bytes)?;
    let mut n_files = 2 + n_maps;
    if !sens.is_empty() {
        let t = tables::sensitivity_table(sens, &names);
        put(root, Path::new("sensitivity.csv"), t.as_bytes())?;
        n_files += 1;
        for x in sens {
            n_files += write_sensitivity_maps(root, p, x)?;
        }
    }
    if let Some(o) = opt {
        for (rel, bytes) in tables::optimise_files(p, o, &names) {
            put(root, &rel, &bytes)?;
            n_files += 1;
        }
    }
    Ok((n_files, face_maps))
}

/// The long table and every variant's maps (matrices and pictures), one variant at a time: its
/// long-table rows (ascending, which also sums the pictures' block means), then its matrices
/// (top row first). Returns the number of files written and the maps' coarse block means.
fn write_face_maps(
    root: &Path,
    p: &Prepared,
    grids: &dyn GridSource,
    axes: &[DesignVar],
    format: TableFormat,
    held_matrix_bytes: usize,
) -> std::io::Result<(usize, Vec<Vec<BlockMeans>>)> {
    let s = &p.study;
    let long_rel = Path::new(match format {
        TableFormat::Csv => "maps_long.csv",
        TableFormat::Parquet => "maps_long.parquet",
    });
    let mut long = long::open_long(
        create(root, long_rel)?,
        axes,
        &s.outputs,
        format == TableFormat::Csv,
    )
    .map_err(|e| io_err(long_rel, e))?;
    // `,z,` of every column, formatted once.
    let zs_text: Vec<Vec<u8>> = p
        .zs_mm
        .iter()
        .map(|z| {
            let mut b = vec![b','];
            push_cell(&mut b, *z);
            b.push(b',');
            b
        })
        .collect();
    let w = VariantWriter {
        root,
        p,
        grids,
        axes,
        zs_text: &zs_text,
        held_matrix_bytes,
        spare_lines: Mutex::new(Vec::new()),
        read_error: Mutex::new(None),
    };
    let mut n_files = 1;
    let mut face_maps = Vec::with_capacity(p.variants.len());
    for i in 0..p.variants.len() {
        let (n, blocks) = w.write(i, &mut long, long_rel)?;
        n_files += n;
        face_maps.push(blocks);
    }
    if let LongWriter::Parquet(w) = long {
        w.close()
            .map_err(|e| io_err(long_rel, std::io::Error::other(e)))?;
    }
    Ok((n_files, face_maps))
}

/// What every variant's maps are written with.
struct VariantWriter<'a> {
    root: &'a Path,
    p: &'a Prepared,
    grids: &'a dyn GridSource,
    axes: &'a [DesignVar],
    /// `,z,` per column.
    zs_text: &'a [Vec<u8>],
    held_matrix_bytes: usize,
    /// Matrix lines of the previous variant, whose memory the next one formats into.
    spare_lines: SpareLines,
    /// The first error reading the grid back (a merge's scratch file).
    read_error: Mutex<Option<std::io::Error>>,
}

impl VariantWriter<'_> {
    /// Variant `i`'s long-table rows into `long` and its maps; the number of map files and the
    /// maps' block means, coarsened to [`REPORT_MAP_CELLS`].
    fn write(
        &self,
        i: usize,
        long: &mut LongWriter,
        long_rel: &Path,
    ) -> std::io::Result<(usize, Vec<BlockMeans>)> {
        let (p, s) = (self.p, &self.p.study);
        let d = &p.variants[i];
        let mut prefix = i.to_string();
        for v in self.axes {
            let _ = write!(prefix, ",{}", cell(d.get(*v)));
        }
        prefix.push(',');
        let fill = |rows: Range<usize>, valid: &mut Vec<bool>, out: &mut [Vec<f64>]| {
            self.fill(i, rows, valid, out)
        };
        let w = id_width(p.variants.len());
        let maps: Vec<MapFile> = s
            .outputs
            .iter()
            .map(|o| MapFile {
                stem: format!("maps/v{i:0w$}_{}", o.column()),
                title: format!("{}: variant {i} ({}): {}", s.name, d.describe(), o.label()),
                value_label: format!("{}, {}", o.label().to_lowercase(), o.unit()),
                scale: if o.signed() {
                    Scale::Diverging
                } else {
                    Scale::Sequential
                },
            })
            .collect();
        let design: Vec<f64> = self.axes.iter().map(|v| d.get(*v)).collect();
        let rows = LongRows {
            variant: i,
            prefix: prefix.as_bytes(),
            zs: self.zs_text,
            design: &design,
            n_outputs: s.outputs.len(),
        };
        let budget = (self.held_matrix_bytes, &self.spare_lines);
        let pass =
            long::long_pass(long, p, &rows, &fill, budget).map_err(|e| io_err(long_rel, e))?;
        let mut n = match pass.held {
            Some(held) => {
                let n = maps::write_held_maps(self.root, p, &maps, &held)?;
                // The next variant formats into these lines' memory.
                self.spare_lines
                    .lock()
                    .unwrap_or_else(|e| e.into_inner())
                    .extend(held.into_iter().flatten());
                n
            }
            None => {
                let fill_values = |rows: Range<usize>, out: &mut [Vec<f64>]| {
                    fill(rows, &mut Vec::new(), out);
                };
                maps::write_maps(self.root, p, &maps, &fill_values)?
            }
        };
        if let Some(e) = self
            .read_error
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .take()
        {
            return Err(e);
        }
        n += maps::write_svgs(self.root, p, &maps, &pass.blocks)?;
        let coarse = pass
            .blocks
            .iter()
            .map(|b| b.coarsened(REPORT_MAP_CELLS))
            .collect();
        Ok((n, coarse))
    }

    /// Validity and each output's values of variant `i` on `rows` (row-major).
    fn fill(&self, i: usize, rows: Range<usize>, valid: &mut Vec<bool>, out: &mut [Vec<f64>]) {
        let s = &self.p.study;
        let club_speed = mph(s.swing.club_speed_mph);
        let mut g = LaunchGrid::default();
        let n = rows.len() * self.p.zs_mm.len();
        if let Err(e) = self.grids.grid_rows(i, rows, &mut g) {
            // Reported once the band is written (the whole output folder is discarded).
            *self.read_error.lock().unwrap_or_else(|e| e.into_inner()) = Some(e);
            g = LaunchGrid::with_len(n);
        }
        for (o, dst) in s.outputs.iter().zip(out.iter_mut()) {
            dst.clear();
            dst.par_extend(
                (0..g.len())
                    .into_par_iter()
                    .map(|k| o.file_value(&g, k, club_speed)),
            );
        }
        std::mem::swap(valid, &mut g.valid);
    }
}

/// The maps of sensitivity `x` (one per study output): matrices and pictures. Returns the
/// number of files written.
fn write_sensitivity_maps(root: &Path, p: &Prepared, x: &Sensitivity) -> std::io::Result<usize> {
    let s = &p.study;
    let club_speed = mph(s.swing.club_speed_mph);
    let ys_m: Vec<f64> = p.ys_mm.iter().map(|v| mm(*v)).collect();
    let zs_m: Vec<f64> = p.zs_mm.iter().map(|v| mm(*v)).collect();
    let outputs: Vec<Output> = Output::ALL
        .iter()
        .copied()
        .filter(|o| s.outputs.contains(o))
        .collect();
    let maps: Vec<MapFile> = outputs
        .iter()
        .map(|o| MapFile {
            stem: format!("sensitivity/d_{}__d_{}", o.column(), x.var.key()),
            title: format!(
                "{}: d({}) / d({}) at the base design (step {})",
                s.name,
                o.label().to_lowercase(),
                x.var.key(),
                x.step
            ),
            value_label: format!(
                "{} per {}, {}/{}",
                o.label().to_lowercase(),
                x.var.key(),
                o.unit(),
                x.var.unit()
            ),
            scale: Scale::Diverging,
        })
        .collect();
    let fill = |rows: Range<usize>, out: &mut [Vec<f64>]| {
        x.map_rows(&ys_m[rows], &zs_m, club_speed, &outputs, out);
    };
    let blocks = maps::block_means(p, maps.len(), &fill);
    Ok(maps::write_maps(root, p, &maps, &fill)? + maps::write_svgs(root, p, &maps, &blocks)?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::spec::parse_study;
    use std::collections::BTreeMap;

    fn tree(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
        let mut out = BTreeMap::new();
        let mut stack = vec![dir.to_path_buf()];
        while let Some(d) = stack.pop() {
            for e in std::fs::read_dir(&d).unwrap() {
                let path = e.unwrap().path();
                if path.is_dir() {
                    stack.push(path);
                } else {
                    let rel = path.strip_prefix(dir).unwrap().to_path_buf();
                    out.insert(rel, std::fs::read(&path).unwrap());
                }
            }
        }
        out
    }

    /// Two variants on a 150 × 701 grid (two bands a variant) reaching off the face.
    fn prepared() -> Prepared {
        let club = Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/clubs/paper_driver.toml");
        let text = format!(
            "[study]\nname = \"t\"\nclub = \"{}\"\n\n[delivery]\nclub_speed_mph = 100.0\n\
             dynamic_loft_deg = 12.0\n\n[grid]\ny_mm = {{ from = -330.0, to = 25.0, count = 150 }}\n\
             z_mm = {{ from = -40.0, to = 40.0, count = 701 }}\n\n[design]\n\
             com_dx_mm = [-5.0, 5.0]\n",
            club.display().to_string().replace('\\', "/")
        );
        Prepared::new(parse_study(Path::new("t.toml"), &text).unwrap()).unwrap()
    }

    fn write(p: &Prepared, dir: &Path, budget: usize) -> Vec<Vec<BlockMeans>> {
        let metrics = p.all_metrics();
        write_study_holding(
            dir,
            p,
            &p.kernels(),
            (&metrics, &[], None),
            TableFormat::Csv,
            budget,
        )
        .unwrap()
        .1
    }

    /// A map value as the standard library rounds it to ten significant digits, empty when
    /// not finite.
    fn value(v: f64) -> String {
        if v.is_finite() {
            let r: f64 = format!("{v:.9e}").parse().unwrap();
            format!("{r}")
        } else {
            String::new()
        }
    }

    #[test]
    fn streamed_outputs_equal_an_in_memory_format_writer_byte_for_byte() {
        let p = prepared();
        let (ny, nz) = (p.ys_mm.len(), p.zs_mm.len());
        assert!(ny > band_rows(nz), "the grid must span several bands");
        let dir = std::env::temp_dir().join(format!("smash-output-test-{}", std::process::id()));
        let (held, twice) = (dir.join("held"), dir.join("twice"));
        let blocks = write(&p, &held, HELD_MATRIX_BYTES);
        // No memory for the matrix lines: the matrices take the second (top-down) pass.
        let blocks_twice = write(&p, &twice, 0);
        let (a, b) = (tree(&held), tree(&twice));
        assert_eq!(a.keys().collect::<Vec<_>>(), b.keys().collect::<Vec<_>>());
        for (k, v) in &a {
            assert!(v == &b[k], "{} differs between the two passes", k.display());
        }

        // The whole study held in memory and written with format!, the obvious way.
        let results = p.assemble(p.compute(0..p.work_len(), &|| ())).unwrap();
        let s = &p.study;
        let club_speed = mph(s.swing.club_speed_mph);
        let mut long = String::from("variant_id,com_dx_mm,y_mm,z_mm,valid");
        for o in &s.outputs {
            long += &format!(",{}", o.column());
        }
        long.push('\n');
        let mut invalid = 0;
        for (i, (d, r)) in p.variants.iter().zip(&results).enumerate() {
            let (var, _) = &s.design.axes[0];
            assert_eq!(var.key(), "com_dx_mm");
            let dx = d.get(*var);
            for (iy, y) in p.ys_mm.iter().enumerate() {
                for (iz, z) in p.zs_mm.iter().enumerate() {
                    let k = iy * nz + iz;
                    invalid += usize::from(!r.grid.valid[k]);
                    long += &format!("{i},{dx},{y},{z},{}", u8::from(r.grid.valid[k]));
                    for o in &s.outputs {
                        long += &format!(",{}", value(o.file_value(&r.grid, k, club_speed)));
                    }
                    long.push('\n');
                }
            }
            // The report's maps: the block means of the whole map, coarsened.
            for (k, o) in s.outputs.iter().enumerate() {
                let whole: Vec<f64> = (0..ny * nz)
                    .map(|c| o.file_value(&r.grid, c, club_speed))
                    .collect();
                let mut b = BlockMeans::new(ny, nz);
                b.add_rows(&whole);
                let want = b.coarsened(REPORT_MAP_CELLS).cells(&p.zs_mm, &p.ys_mm);
                for got in [&blocks[i][k], &blocks_twice[i][k]] {
                    let got = got.cells(&p.zs_mm, &p.ys_mm);
                    assert_eq!((&got.0, &got.1), (&want.0, &want.1));
                    assert!(got.0.len() <= REPORT_MAP_CELLS && got.1.len() <= REPORT_MAP_CELLS);
                    for (a, e) in got.2.iter().zip(&want.2) {
                        assert!(a == e || (a.is_nan() && e.is_nan()), "{a} against {e}");
                    }
                }
            }
            for o in &s.outputs {
                let mut m = String::from("y\\x");
                for z in &p.zs_mm {
                    m += &format!(",{z}");
                }
                m.push('\n');
                for (iy, y) in p.ys_mm.iter().enumerate().rev() {
                    m += &format!("{y}");
                    for iz in 0..nz {
                        m += &format!(
                            ",{}",
                            value(o.file_value(&r.grid, iy * nz + iz, club_speed))
                        );
                    }
                    m.push('\n');
                }
                let rel = PathBuf::from(format!("maps/v{i:03}_{}.csv", o.column()));
                assert!(a[&rel] == m.as_bytes(), "{} differs", rel.display());
            }
        }
        assert!(invalid > 0, "rows below -305 mm lie off the face");
        assert!(
            a[Path::new("maps_long.csv")] == long.as_bytes(),
            "maps_long.csv differs"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
