//! The long table (`maps_long.csv` or `maps_long.parquet`): one variant's rows at a time, in
//! ascending grid rows, each number formatted once into its matrix line and the long-table line
//! assembled from those cells (see [`long_pass`]).

use std::fmt::Write as _;
use std::fs::File;
use std::io::Write as _;
use std::ops::Range;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

use parquet::basic::Compression;
use parquet::data_type::{BoolType, DoubleType, Int32Type};
use parquet::file::properties::WriterProperties;
use parquet::file::writer::SerializedFileWriter;
use parquet::schema::parser::parse_message_type;
use rayon::prelude::*;

use crate::data::number::push_f64;
use crate::report::heatmap::BlockMeans;

use super::super::design::DesignVar;
use super::super::metrics::Output;
use super::super::sweep::Prepared;
use super::{band_rows, pipeline, push_map_cell};

/// Values of a band of rows for [`long_pass`]: validity and each output (row-major).
pub(super) type LongFill<'a> = dyn Fn(Range<usize>, &mut Vec<bool>, &mut [Vec<f64>]) + Sync + 'a;

/// Most bytes of matrix text [`long_pass`] keeps to write the matrices from (top row first)
/// after the long table's ascending pass, instead of computing and formatting every value a
/// second time: several variants of an 801 × 801 grid. Larger grids take the second pass.
pub const HELD_MATRIX_BYTES: usize = 192 << 20;

/// Bytes a matrix cell takes, about (ten significant digits, sign, point, comma).
const MATRIX_CELL_BYTES: usize = 13;

/// What one variant's rows of the long table are made of.
pub(super) struct LongRows<'a> {
    /// Variant id.
    pub variant: usize,
    /// `id,variables,` (CSV).
    pub prefix: &'a [u8],
    /// `,z,` per column (CSV).
    pub zs: &'a [Vec<u8>],
    /// The design variables (Parquet).
    pub design: &'a [f64],
    /// Outputs per point.
    pub n_outputs: usize,
}

/// A band of rows of the long pass: values, and per grid row its long-table line (CSV) and its
/// matrix line per output (`y,v,v,…\n`, as [`super::push_matrix_row`] writes it).
#[derive(Default)]
struct LongBand {
    valid: Vec<bool>,
    values: Vec<Vec<f64>>,
    long: Vec<Vec<u8>>,
    mats: Vec<Vec<Vec<u8>>>,
}

/// The matrix lines of one variant kept by [`long_pass`]: per band (ascending), per grid row,
/// per output.
pub(super) type HeldMatrices = Vec<Vec<Vec<Vec<u8>>>>;

/// Spare matrix lines whose memory the next variant formats into.
pub(super) type SpareLines = Mutex<Vec<Vec<Vec<u8>>>>;

/// What [`long_pass`] leaves: the block means of each output's picture, and the matrix lines
/// when they were kept.
pub(super) struct LongPass {
    /// Per output, the block means of its picture.
    pub blocks: Vec<BlockMeans>,
    /// The matrix lines, when they fit the budget.
    pub held: Option<HeldMatrices>,
}

/// The long table's file.
pub(super) enum LongWriter {
    /// `maps_long.csv`.
    Csv(File),
    /// `maps_long.parquet`.
    Parquet(SerializedFileWriter<File>),
}

/// How one band is made: the grid, the variant's rows, where values come from, and whether the
/// long table is text (CSV lines) and the matrix lines are kept.
struct BandMaker<'a> {
    p: &'a Prepared,
    v: &'a LongRows<'a>,
    fill: &'a LongFill<'a>,
    per: usize,
    csv: bool,
    holding: &'a AtomicBool,
    spare: &'a SpareLines,
}

impl BandMaker<'_> {
    /// Rows of band `b`.
    fn rows(&self, b: usize) -> Range<usize> {
        let ny = self.p.ys_mm.len();
        b * self.per..((b + 1) * self.per).min(ny)
    }

    /// Values of band `b`, then (CSV, or while holding) every row's lines, in parallel.
    fn make(&self, b: usize, band: &mut LongBand) {
        let rows = self.rows(b);
        band.values.resize_with(self.v.n_outputs, Vec::new);
        self.fill(rows.clone(), band);
        if !(self.csv || self.holding.load(Ordering::Relaxed)) {
            return;
        }
        {
            let mut spare = self.spare.lock().unwrap_or_else(|e| e.into_inner());
            band.mats
                .resize_with(rows.len(), || spare.pop().unwrap_or_default());
        }
        let csv = self.csv;
        band.long
            .resize_with(if csv { rows.len() } else { 0 }, Vec::new);
        let (valid, values) = (&band.valid, &band.values);
        let row = |spans: &mut Vec<u32>, r: usize, mats: &mut Vec<Vec<u8>>, long| {
            self.format_row(rows.start + r, r, (valid, values), mats, long, spans)
        };
        if csv {
            band.mats
                .par_iter_mut()
                .zip(band.long.par_iter_mut())
                .enumerate()
                .for_each_init(Vec::new, |spans, (r, (m, l))| row(spans, r, m, Some(l)));
        } else {
            band.mats
                .par_iter_mut()
                .enumerate()
                .for_each_init(Vec::new, |spans, (r, m)| row(spans, r, m, None));
        }
    }

    fn fill(&self, rows: Range<usize>, band: &mut LongBand) {
        (self.fill)(rows, &mut band.valid, &mut band.values);
    }

    /// Grid row `row` (row `r` of its band): its matrix line per output into `mats`, and its
    /// long-table lines into `long` (assembled from the matrix lines' cells, whose places
    /// `spans` records).
    fn format_row(
        &self,
        row: usize,
        r: usize,
        (valid, values): (&[bool], &[Vec<f64>]),
        mats: &mut Vec<Vec<u8>>,
        long: Option<&mut Vec<u8>>,
        spans: &mut Vec<u32>,
    ) {
        let (v, nz) = (self.v, self.p.zs_mm.len());
        let mut y = Vec::new();
        push_f64(&mut y, self.p.ys_mm[row]);
        mats.resize_with(v.n_outputs, Vec::new);
        // Cell k of output o spans spans[2(o·nz + k)]..spans[2(o·nz + k) + 1] of its line.
        spans.clear();
        for (o, line) in mats.iter_mut().enumerate() {
            line.clear();
            line.reserve(y.len() + 2 + nz * (MATRIX_CELL_BYTES + 4));
            line.extend_from_slice(&y);
            for x in &values[o][r * nz..(r + 1) * nz] {
                line.push(b',');
                spans.push(line.len() as u32);
                push_map_cell(line, *x);
                spans.push(line.len() as u32);
            }
            line.push(b'\n');
        }
        let Some(out) = long else { return };
        out.clear();
        out.reserve(nz * (v.prefix.len() + 48 + v.n_outputs * (MATRIX_CELL_BYTES + 6) + y.len()));
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
}

/// One variant's rows of the long table (ascending rows) into `long`. Every value is formatted
/// once: the matrix line of each output is written first and the long-table line is assembled
/// from its cells. The matrix lines are kept for [`super::maps::write_held_maps`] while they
/// fit in `budget` bytes ([`HELD_MATRIX_BYTES`]); new lines reuse the memory of `spare` ones.
pub(super) fn long_pass(
    long: &mut LongWriter,
    p: &Prepared,
    v: &LongRows<'_>,
    fill: &LongFill<'_>,
    (budget, spare): (usize, &SpareLines),
) -> std::io::Result<LongPass> {
    let (ny, nz) = (p.ys_mm.len(), p.zs_mm.len());
    let estimate = ny
        .saturating_mul(nz)
        .saturating_mul(v.n_outputs)
        .saturating_mul(MATRIX_CELL_BYTES);
    let holding = AtomicBool::new(estimate <= budget);
    let maker = BandMaker {
        p,
        v,
        fill,
        per: band_rows(nz),
        csv: matches!(long, LongWriter::Csv(_)),
        holding: &holding,
        spare,
    };
    let mut held: HeldMatrices = Vec::new();
    let mut held_bytes = 0usize;
    let mut blocks: Vec<BlockMeans> = (0..v.n_outputs).map(|_| BlockMeans::new(ny, nz)).collect();
    let mut consume = |b: usize, band: &mut LongBand| -> std::io::Result<()> {
        match long {
            LongWriter::Csv(f) => {
                for l in &band.long {
                    f.write_all(l)?;
                }
            }
            LongWriter::Parquet(w) => {
                write_parquet_band(w, p, v, maker.rows(b), &band.valid, &band.values)
                    .map_err(std::io::Error::other)?
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
        ny.div_ceil(maker.per),
        [LongBand::default(), LongBand::default()],
        &|b, band| maker.make(b, band),
        &mut consume,
    )?;
    Ok(LongPass {
        blocks,
        held: holding.into_inner().then_some(held),
    })
}

/// The long table's file under `root`, its CSV header written: `variant_id`, the design
/// variables, `y_mm`, `z_mm`, `valid`, the outputs.
pub(super) fn open_long(
    f: File,
    axes: &[DesignVar],
    outputs: &[Output],
    csv: bool,
) -> std::io::Result<LongWriter> {
    if !csv {
        return parquet_long_writer(f, axes, outputs).map(LongWriter::Parquet);
    }
    let mut f = f;
    let mut head = String::from("variant_id");
    for v in axes {
        let _ = write!(head, ",{}", v.key());
    }
    head.push_str(",y_mm,z_mm,valid");
    for o in outputs {
        let _ = write!(head, ",{}", o.column());
    }
    head.push('\n');
    f.write_all(head.as_bytes())?;
    Ok(LongWriter::Csv(f))
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
