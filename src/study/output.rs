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
//! computed and formatted a second time, top row first, for the matrices.
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

use std::sync::Arc;

use parquet::basic::Compression;
use parquet::data_type::{BoolType, DoubleType, Int32Type};
use parquet::file::properties::WriterProperties;
use parquet::file::writer::SerializedFileWriter;
use parquet::schema::parser::parse_message_type;
use rayon::prelude::*;

use crate::data::club_file::club_toml;
use crate::data::fmt_f64;
use crate::data::number::{push_cell, push_f64};
use crate::report::heatmap::{matrix_csv_header, matrix_csv_row, BlockMeans, Heatmap, Scale};
use crate::sweep::kernel::LaunchGrid;
use crate::units::{mm, mph};

use super::design::DesignVar;
use super::metrics::{metric_names, metric_unit, Output};
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

const X_LABEL: &str = "impact z (toward toe), mm";
const Y_LABEL: &str = "impact y (up the face), mm";

fn id_width(n: usize) -> usize {
    (n.saturating_sub(1)).to_string().len().max(3)
}

/// How the long table is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
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

fn io_err(path: &Path, e: std::io::Error) -> std::io::Error {
    std::io::Error::new(e.kind(), format!("{}: {e}", path.display()))
}

/// Write `bytes` to `root/rel` (creating folders).
fn put(root: &Path, rel: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let mut f = create(root, rel)?;
    f.write_all(bytes).map_err(|e| io_err(rel, e))
}

fn create(root: &Path, rel: &Path) -> std::io::Result<File> {
    let path = root.join(rel);
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent).map_err(|e| io_err(rel, e))?;
    }
    File::create(&path).map_err(|e| io_err(rel, e))
}

/// Rows per band for a grid of `nz` columns (at least one row: an axis has at most 100,000
/// points, so a band stays a few tens of MB).
fn band_rows(nz: usize) -> usize {
    (BAND_POINTS / nz.max(1)).max(1)
}

/// Produce `bands` items with `make` into two alternating buffers and hand each, in order, to
/// `consume`: the next band is made while the previous one is consumed (which may take parts
/// of it, e.g. text to keep).
fn pipeline<T: Send + Sync>(
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
) -> std::io::Result<usize> {
    let s = &p.study;
    let mut n_files = 0;
    put(root, Path::new("study.toml"), resolved_toml(s).as_bytes())?;
    n_files += 1;
    let axes: Vec<DesignVar> = s.design.axes.iter().map(|(v, _)| *v).collect();
    let names = metric_names(s.distribution.is_some());

    // variants.csv
    let mut t = String::from("variant_id");
    for v in &axes {
        let _ = write!(t, ",{}", v.key());
    }
    for n in &names {
        let _ = write!(t, ",{n}");
    }
    t.push('\n');
    for (i, (d, m)) in p.variants.iter().zip(metrics).enumerate() {
        let _ = write!(t, "{i}");
        for v in &axes {
            let _ = write!(t, ",{}", cell(d.get(*v)));
        }
        for x in m {
            let _ = write!(t, ",{}", cell(*x));
        }
        t.push('\n');
    }
    put(root, Path::new("variants.csv"), t.as_bytes())?;
    n_files += 1;

    // maps_long.csv and the per-variant maps, one variant at a time: its long-table rows
    // (ascending, which also sums the pictures' block means), then its matrices (top row first).
    let long_rel = Path::new(match format {
        TableFormat::Csv => "maps_long.csv",
        TableFormat::Parquet => "maps_long.parquet",
    });
    let long_file = create(root, long_rel)?;
    let mut long = match format {
        TableFormat::Csv => {
            let mut f = long_file;
            let mut head = String::from("variant_id");
            for v in &axes {
                let _ = write!(head, ",{}", v.key());
            }
            head.push_str(",y_mm,z_mm,valid");
            for o in &s.outputs {
                let _ = write!(head, ",{}", o.column());
            }
            head.push('\n');
            f.write_all(head.as_bytes())
                .map_err(|e| io_err(long_rel, e))?;
            LongWriter::Csv(f)
        }
        TableFormat::Parquet => LongWriter::Parquet(
            parquet_long_writer(long_file, &axes, &s.outputs).map_err(|e| io_err(long_rel, e))?,
        ),
    };
    n_files += 1;
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
    let club_speed = mph(s.swing.club_speed_mph);
    let w = id_width(p.variants.len());
    let ys_m: Vec<f64> = p.ys_mm.iter().map(|v| mm(*v)).collect();
    let zs_m: Vec<f64> = p.zs_mm.iter().map(|v| mm(*v)).collect();
    let spare_lines = std::sync::Mutex::new(Vec::new());
    let read_error: std::sync::Mutex<Option<std::io::Error>> = std::sync::Mutex::new(None);
    let check_read = || match read_error.lock().unwrap_or_else(|e| e.into_inner()).take() {
        Some(e) => Err(e),
        None => Ok(()),
    };
    for (i, d) in p.variants.iter().enumerate() {
        let mut prefix = i.to_string();
        for v in &axes {
            let _ = write!(prefix, ",{}", cell(d.get(*v)));
        }
        prefix.push(',');
        let fill = |rows: Range<usize>, valid: &mut Vec<bool>, out: &mut [Vec<f64>]| {
            let mut g = LaunchGrid::default();
            let n = rows.len() * p.zs_mm.len();
            if let Err(e) = grids.grid_rows(i, rows, &mut g) {
                // Reported once the band is written (the whole output folder is discarded).
                *read_error.lock().unwrap_or_else(|e| e.into_inner()) = Some(e);
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
        };
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
        let design: Vec<f64> = axes.iter().map(|v| d.get(*v)).collect();
        let pass = long_pass(
            &mut long,
            p,
            &LongRows {
                variant: i,
                prefix: prefix.as_bytes(),
                zs: &zs_text,
                design: &design,
                n_outputs: s.outputs.len(),
            },
            &fill,
            (held_matrix_bytes, &spare_lines),
        )
        .map_err(|e| io_err(long_rel, e))?;
        n_files += match pass.held {
            Some(held) => {
                let n = write_held_maps(root, p, &maps, &held)?;
                // The next variant formats into these lines' memory.
                spare_lines
                    .lock()
                    .unwrap_or_else(|e| e.into_inner())
                    .extend(held.into_iter().flatten());
                n
            }
            None => {
                let fill_values = |rows: Range<usize>, out: &mut [Vec<f64>]| {
                    fill(rows, &mut Vec::new(), out);
                };
                write_maps(root, p, &maps, &fill_values)?
            }
        };
        check_read()?;
        n_files += write_svgs(root, p, &maps, &pass.blocks)?;
    }
    if let LongWriter::Parquet(w) = long {
        w.close()
            .map_err(|e| io_err(long_rel, std::io::Error::other(e)))?;
    }

    if !sens.is_empty() {
        let mut t = sensitivity_table(sens, &names);
        put(root, Path::new("sensitivity.csv"), t.as_bytes())?;
        t.clear();
        n_files += 1;
        for x in sens {
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
            let blocks = block_means(p, maps.len(), &fill);
            n_files += write_maps(root, p, &maps, &fill)?;
            n_files += write_svgs(root, p, &maps, &blocks)?;
        }
    }
    if let Some(o) = opt {
        for (rel, bytes) in optimise_files(p, o, &names) {
            put(root, &rel, &bytes)?;
            n_files += 1;
        }
    }
    Ok(n_files)
}

/// Values of a band of rows for [`long_pass`]: validity and each output (row-major).
type LongFill<'a> = dyn Fn(Range<usize>, &mut Vec<bool>, &mut [Vec<f64>]) + Sync + 'a;

/// Most bytes of matrix text [`long_pass`] keeps to write the matrices from (top row first)
/// after the long table's ascending pass, instead of computing and formatting every value a
/// second time: a few variants of an 801 × 801 grid. Larger grids take the second pass.
pub const HELD_MATRIX_BYTES: usize = 192 << 20;

/// Bytes a matrix cell takes, about (17 significant digits, sign, point, comma).
const MATRIX_CELL_BYTES: usize = 20;

/// What one variant's rows of the long table are made of.
struct LongRows<'a> {
    variant: usize,
    /// `id,variables,` (CSV).
    prefix: &'a [u8],
    /// `,z,` per column (CSV).
    zs: &'a [Vec<u8>],
    /// The design variables (Parquet).
    design: &'a [f64],
    n_outputs: usize,
}

/// A band of rows of the long pass: values, and per grid row its long-table line (CSV) and its
/// matrix line per output (`y,v,v,…\n`, as [`matrix_csv_row`] writes it).
#[derive(Default)]
struct LongBand {
    valid: Vec<bool>,
    values: Vec<Vec<f64>>,
    long: Vec<Vec<u8>>,
    mats: Vec<Vec<Vec<u8>>>,
}

/// The matrix lines of one variant kept by [`long_pass`]: per band (ascending), per grid row,
/// per output.
type HeldMatrices = Vec<Vec<Vec<Vec<u8>>>>;

/// What [`long_pass`] leaves: the block means of each output's picture, and the matrix lines
/// when they were kept.
struct LongPass {
    blocks: Vec<BlockMeans>,
    held: Option<HeldMatrices>,
}

/// One variant's rows of the long table (ascending rows) into `long`. Every value is formatted
/// once: the matrix line of each output is written first and the long-table line is assembled
/// from its cells. The matrix lines are kept for [`write_held_maps`] while they fit in
/// `budget` bytes ([`HELD_MATRIX_BYTES`]); new lines reuse the memory of `spare` ones.
fn long_pass(
    long: &mut LongWriter,
    p: &Prepared,
    v: &LongRows<'_>,
    fill: &LongFill<'_>,
    (budget, spare): (usize, &std::sync::Mutex<Vec<Vec<Vec<u8>>>>),
) -> std::io::Result<LongPass> {
    use std::sync::atomic::{AtomicBool, Ordering};
    let (ny, nz) = (p.ys_mm.len(), p.zs_mm.len());
    let n_outputs = v.n_outputs;
    let per = band_rows(nz);
    let bands = ny.div_ceil(per);
    let csv = matches!(long, LongWriter::Csv(_));
    let estimate = ny
        .saturating_mul(nz)
        .saturating_mul(n_outputs)
        .saturating_mul(MATRIX_CELL_BYTES);
    let holding = AtomicBool::new(estimate <= budget);
    let mut held: HeldMatrices = Vec::new();
    let mut held_bytes = 0usize;
    let mut blocks: Vec<BlockMeans> = (0..n_outputs).map(|_| BlockMeans::new(ny, nz)).collect();
    let long_cap = v.prefix.len() + 48 + n_outputs * 26;
    let make = |b: usize, band: &mut LongBand| {
        let rows = b * per..((b + 1) * per).min(ny);
        band.values.resize_with(n_outputs, Vec::new);
        fill(rows.clone(), &mut band.valid, &mut band.values);
        let hold = holding.load(Ordering::Relaxed);
        if !(csv || hold) {
            return;
        }
        {
            let mut spare = spare.lock().unwrap_or_else(|e| e.into_inner());
            band.mats
                .resize_with(rows.len(), || spare.pop().unwrap_or_default());
        }
        band.long
            .resize_with(if csv { rows.len() } else { 0 }, Vec::new);
        let (valid, values) = (&band.valid, &band.values);
        let format_row = |r: usize,
                          mats: &mut Vec<Vec<u8>>,
                          long: Option<&mut Vec<u8>>,
                          spans: &mut Vec<u32>| {
            let mut y = Vec::new();
            push_f64(&mut y, p.ys_mm[rows.start + r]);
            mats.resize_with(n_outputs, Vec::new);
            // Cell k of output o spans spans[2(o·nz + k)]..spans[2(o·nz + k) + 1] of its line.
            spans.clear();
            for (o, line) in mats.iter_mut().enumerate() {
                let vals = &values[o][r * nz..(r + 1) * nz];
                line.clear();
                line.reserve(y.len() + 2 + nz * (MATRIX_CELL_BYTES + 4));
                line.extend_from_slice(&y);
                for x in vals {
                    line.push(b',');
                    spans.push(line.len() as u32);
                    push_cell(line, *x);
                    spans.push(line.len() as u32);
                }
                line.push(b'\n');
            }
            if let Some(out) = long {
                out.clear();
                out.reserve(nz * (long_cap + y.len()));
                for (iz, z) in v.zs.iter().enumerate() {
                    out.extend_from_slice(v.prefix);
                    out.extend_from_slice(&y);
                    out.extend_from_slice(z);
                    out.push(if valid[r * nz + iz] { b'1' } else { b'0' });
                    for (o, line) in mats.iter().enumerate() {
                        let k = 2 * (o * nz + iz);
                        out.push(b',');
                        out.extend_from_slice(&line[spans[k] as usize..spans[k + 1] as usize]);
                    }
                    out.push(b'\n');
                }
            }
        };
        if csv {
            band.mats
                .par_iter_mut()
                .zip(band.long.par_iter_mut())
                .enumerate()
                .for_each_init(Vec::new, |spans, (r, (m, l))| {
                    format_row(r, m, Some(l), spans)
                });
        } else {
            band.mats
                .par_iter_mut()
                .enumerate()
                .for_each_init(Vec::new, |spans, (r, m)| format_row(r, m, None, spans));
        }
    };
    let pq = |e: parquet::errors::ParquetError| std::io::Error::other(e);
    let mut consume = |b: usize, band: &mut LongBand| -> std::io::Result<()> {
        let rows = b * per..((b + 1) * per).min(ny);
        match long {
            LongWriter::Csv(f) => {
                for l in &band.long {
                    f.write_all(l)?;
                }
            }
            LongWriter::Parquet(w) => {
                write_parquet_band(w, p, v, rows, &band.valid, &band.values).map_err(pq)?
            }
        }
        for (b, x) in blocks.iter_mut().zip(&band.values) {
            b.add_rows(x);
        }
        if holding.load(Ordering::Relaxed) {
            held_bytes += band.mats.iter().flatten().map(Vec::capacity).sum::<usize>();
            if held_bytes > budget + budget / 2 {
                // Longer numbers than estimated: give the memory back, take the second pass.
                holding.store(false, Ordering::Relaxed);
                held = Vec::new();
            } else {
                held.push(std::mem::take(&mut band.mats));
            }
        }
        Ok(())
    };
    pipeline(
        bands,
        [LongBand::default(), LongBand::default()],
        &make,
        &mut consume,
    )?;
    Ok(LongPass {
        blocks,
        held: holding.into_inner().then_some(held),
    })
}

/// The long table's file.
enum LongWriter {
    Csv(File),
    Parquet(SerializedFileWriter<File>),
}

/// A Parquet writer for the long table: `variant_id` (INT32), the design variables, `y_mm`,
/// `z_mm` (DOUBLE), `valid` (BOOLEAN), then the outputs (DOUBLE, null where invalid).
fn parquet_long_writer(
    f: File,
    axes: &[DesignVar],
    outputs: &[Output],
) -> std::io::Result<SerializedFileWriter<File>> {
    let mut schema = String::from("message maps_long {\n  REQUIRED INT32 variant_id;\n");
    for v in axes {
        let _ = writeln!(schema, "  REQUIRED DOUBLE {};", v.key());
    }
    schema
        .push_str("  REQUIRED DOUBLE y_mm;\n  REQUIRED DOUBLE z_mm;\n  REQUIRED BOOLEAN valid;\n");
    for o in outputs {
        let _ = writeln!(schema, "  OPTIONAL DOUBLE {};", o.column());
    }
    schema.push('}');
    let schema = parse_message_type(&schema).map_err(std::io::Error::other)?;
    let props = WriterProperties::builder()
        .set_compression(Compression::SNAPPY)
        .set_dictionary_enabled(false)
        .build();
    SerializedFileWriter::new(f, Arc::new(schema), Arc::new(props)).map_err(std::io::Error::other)
}

/// One band of the long table (rows `rows` of variant `v`) as a Parquet row group.
fn write_parquet_band(
    w: &mut SerializedFileWriter<File>,
    p: &Prepared,
    v: &LongRows<'_>,
    rows: Range<usize>,
    valid: &[bool],
    values: &[Vec<f64>],
) -> Result<(), parquet::errors::ParquetError> {
    let nz = p.zs_mm.len();
    let design = v.design;
    let n = valid.len();
    let ys: Vec<f64> = rows
        .flat_map(|r| std::iter::repeat_n(p.ys_mm[r], nz))
        .collect();
    let zs: Vec<f64> = p.zs_mm.iter().copied().cycle().take(n).collect();
    let mut rg = w.next_row_group()?;
    let mut column = 0;
    while let Some(mut col) = rg.next_column()? {
        let c = column;
        column += 1;
        if c == 0 {
            let ids = vec![v.variant as i32; n];
            col.typed::<Int32Type>().write_batch(&ids, None, None)?;
        } else if c <= design.len() {
            let x = vec![design[c - 1]; n];
            col.typed::<DoubleType>().write_batch(&x, None, None)?;
        } else if c == design.len() + 1 {
            col.typed::<DoubleType>().write_batch(&ys, None, None)?;
        } else if c == design.len() + 2 {
            col.typed::<DoubleType>().write_batch(&zs, None, None)?;
        } else if c == design.len() + 3 {
            col.typed::<BoolType>().write_batch(valid, None, None)?;
        } else {
            let x = &values[c - design.len() - 4];
            let present: Vec<f64> = x.iter().copied().filter(|x| x.is_finite()).collect();
            let def: Vec<i16> = x.iter().map(|x| i16::from(x.is_finite())).collect();
            col.typed::<DoubleType>()
                .write_batch(&present, Some(&def), None)?;
        }
        col.close()?;
    }
    rg.close()?;
    Ok(())
}

/// The block means of the pictures of a map set, from an ascending pass over the rows.
fn block_means(p: &Prepared, n_maps: usize, fill: &MapFill<'_>) -> Vec<BlockMeans> {
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
type MapFill<'a> = dyn Fn(Range<usize>, &mut [Vec<f64>]) + Sync + 'a;

/// One map of a set written by [`write_maps`].
struct MapFile {
    stem: String,
    title: String,
    value_label: String,
    scale: Scale,
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
fn write_maps(
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
                matrix_csv_row(out, p.ys_mm[rows.start + r], &vals[r * nz..(r + 1) * nz]);
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
fn write_held_maps(
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
fn write_svgs(
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

fn sensitivity_table(sens: &[Sensitivity], names: &[String]) -> String {
    let mut t = String::from(
        "metric,variable,derivative,unit,step,reference_change,change_per_reference,rank\n",
    );
    for (mi, name) in names.iter().enumerate() {
        let mut rows: Vec<(&Sensitivity, f64)> = sens
            .iter()
            .map(|x| (x, x.metrics[mi] * x.var.reference_change()))
            .collect();
        // Largest |change| first; NaN last; ties keep variable order.
        rows.sort_by(|a, b| {
            let (x, y) = (a.1.abs(), b.1.abs());
            match (x.is_nan(), y.is_nan()) {
                (true, true) => std::cmp::Ordering::Equal,
                (true, false) => std::cmp::Ordering::Greater,
                (false, true) => std::cmp::Ordering::Less,
                _ => y.total_cmp(&x),
            }
        });
        for (rank, (x, change)) in rows.iter().enumerate() {
            let _ = writeln!(
                t,
                "{name},{},{},{} per {},{},{},{},{}",
                x.var.key(),
                cell(x.metrics[mi]),
                metric_unit(name),
                x.var.unit(),
                cell(x.step),
                cell(x.var.reference_change()),
                cell(*change),
                rank + 1
            );
        }
    }
    t
}

fn optimise_files(p: &Prepared, o: &OptimiseResult, names: &[String]) -> Files {
    let s = &p.study;
    let spec = s.optimise.as_ref().expect("optimise result without spec");
    let mut files = Files::new();
    let mut t = String::from("iteration,objective");
    for (v, _, _) in &spec.bounds {
        let _ = write!(t, ",{}", v.key());
    }
    t.push('\n');
    for pt in &o.path {
        let _ = write!(t, "{},{}", pt.iteration, cell(pt.objective));
        for (v, _, _) in &spec.bounds {
            let _ = write!(t, ",{}", cell(pt.design.get(*v)));
        }
        t.push('\n');
    }
    files.push(("optimise/path.csv".into(), t.into_bytes()));

    let base = s.club.nominal.clone();
    let best = o
        .best
        .apply(&s.club.nominal, s.design.discretionary_mass.as_ref())
        .expect("the optimum was evaluated");
    let mut t = String::from("quantity,unit,base,optimum,change\n");
    let mut row = |q: &str, unit: &str, a: f64, b: f64| {
        let _ = writeln!(t, "{q},{unit},{},{},{}", cell(a), cell(b), cell(b - a));
    };
    row("objective", "", o.base_objective, o.best_objective);
    for (v, _, _) in &spec.bounds {
        row(v.key(), v.unit(), v.neutral(), o.best.get(*v));
    }
    row(
        "club_mass_g",
        "g",
        base.club_mass_kg * 1e3,
        best.club_mass_kg * 1e3,
    );
    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
        row(
            &format!("com_{axis}_mm"),
            "mm",
            base.club_com_m[k] * 1e3,
            best.club_com_m[k] * 1e3,
        );
    }
    for (k, axis) in ["xx", "yy", "zz"].iter().enumerate() {
        row(
            &format!("i{axis}_gcm2"),
            "gcm2",
            base.club_inertia_kgm2[(k, k)] * 1e7,
            best.club_inertia_kgm2[(k, k)] * 1e7,
        );
    }
    for (i, n) in names.iter().enumerate() {
        row(n, &metric_unit(n), o.base_metrics[i], o.best_metrics[i]);
    }
    files.push(("optimise/result.csv".into(), t.into_bytes()));

    let mut club = s.club.clone();
    club.nominal = best;
    club.name = format!("{} (optimised by study {})", s.club.name, s.name);
    let comment = format!(
        "Optimum of study '{}': {}\nobjective {} -> {} ({} iterations' path in path.csv)",
        s.name,
        o.best.describe(),
        cell(o.base_objective),
        cell(o.best_objective),
        o.path.len()
    );
    files.push((
        "optimise/optimum_club.toml".into(),
        club_toml(&club, &comment).into_bytes(),
    ));
    files
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

    fn write(p: &Prepared, dir: &Path, budget: usize) {
        let metrics = p.all_metrics();
        write_study_holding(
            dir,
            p,
            &p.kernels(),
            (&metrics, &[], None),
            TableFormat::Csv,
            budget,
        )
        .unwrap();
    }

    /// `Display` of a cell, empty when not finite: how every number was written before the
    /// fast formatter.
    fn display(v: f64) -> String {
        if v.is_finite() {
            format!("{v}")
        } else {
            String::new()
        }
    }

    #[test]
    fn streamed_outputs_equal_an_in_memory_display_writer_byte_for_byte() {
        let p = prepared();
        let (ny, nz) = (p.ys_mm.len(), p.zs_mm.len());
        assert!(ny > band_rows(nz), "the grid must span several bands");
        let dir = std::env::temp_dir().join(format!("smash-output-test-{}", std::process::id()));
        let (held, twice) = (dir.join("held"), dir.join("twice"));
        write(&p, &held, HELD_MATRIX_BYTES);
        // No memory for the matrix lines: the matrices take the second (top-down) pass.
        write(&p, &twice, 0);
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
                        long += &format!(",{}", display(o.file_value(&r.grid, k, club_speed)));
                    }
                    long.push('\n');
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
                            display(o.file_value(&r.grid, iy * nz + iz, club_speed))
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
