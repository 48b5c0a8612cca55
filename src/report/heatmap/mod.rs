//! Heatmaps over the clubface: SVG pictures and CSV matrices.
//!
//! A [`Heatmap`] is a row-major grid of values at cell centres `xs` (columns, e.g. heel–toe
//! position `z`, mm) × `ys` (rows, e.g. vertical position `y`, mm). Invalid cells (off the face,
//! no data) are NaN in memory, grey in the picture and empty in the CSV: no NaN reaches a file.

mod draw;
mod small;

use self::draw::{draw_svg, draw_svg_on_edges};
pub use self::small::{
    colour_bar_svg, scale_colour, shared_limits, small_map_svg, SmallMap, SMALL_WIDTH_PX,
};
use crate::data::number::{push_cell, push_f64};

/// How values map to colours.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scale {
    /// Perceptually uniform sequential (viridis) from min to max.
    Sequential,
    /// Blue–white–red, symmetric about zero (residuals, sensitivities, changes).
    Diverging,
}

/// A grid of values to draw or export.
#[derive(Debug, Clone, Copy)]
pub struct Heatmap<'a> {
    /// Title line.
    pub title: &'a str,
    /// Horizontal axis label with unit, e.g. `impact z (toward toe), mm`.
    pub x_label: &'a str,
    /// Vertical axis label with unit, e.g. `impact y (up), mm`.
    pub y_label: &'a str,
    /// Colour-bar label with unit, e.g. `ball speed, mph`.
    pub value_label: &'a str,
    /// Column centres, strictly ascending.
    pub xs: &'a [f64],
    /// Row centres, strictly ascending.
    pub ys: &'a [f64],
    /// `ys.len() × xs.len()` values, row-major (row `i` is `ys[i]`); NaN marks an invalid cell.
    pub values: &'a [f64],
    /// A marker (e.g. the face centre) at `(x, y)`, drawn when inside the plotted range.
    pub marker: Option<(f64, f64)>,
    /// Colour scale.
    pub scale: Scale,
}

impl Heatmap<'_> {
    fn check(&self) {
        assert_eq!(
            self.values.len(),
            self.xs.len() * self.ys.len(),
            "heatmap values must be ys × xs"
        );
        assert!(
            !self.xs.is_empty() && !self.ys.is_empty(),
            "heatmap needs at least one row and column"
        );
    }

    /// Finite min and max of the values, if any value is finite.
    pub fn range(&self) -> Option<(f64, f64)> {
        let mut it = self.values.iter().copied().filter(|v| v.is_finite());
        let first = it.next()?;
        Some(it.fold((first, first), |(lo, hi), v| (lo.min(v), hi.max(v))))
    }
}

/// CSV matrix: the first row is `y \ x` then the column centres; each following row is a row
/// centre then its values. Rows are written top (largest y) to bottom, as on the face seen from
/// the front. Invalid cells are empty.
pub fn matrix_csv(map: &Heatmap<'_>) -> Vec<u8> {
    map.check();
    let mut s = matrix_csv_header(map.xs);
    let nx = map.xs.len();
    for (i, y) in map.ys.iter().enumerate().rev() {
        matrix_csv_row(&mut s, *y, &map.values[i * nx..(i + 1) * nx]);
    }
    s
}

/// The first line of [`matrix_csv`]: `y\x` and the column centres.
pub fn matrix_csv_header(xs: &[f64]) -> Vec<u8> {
    let mut s = b"y\\x".to_vec();
    for x in xs {
        s.push(b',');
        push_f64(&mut s, *x);
    }
    s.push(b'\n');
    s
}

/// One row of [`matrix_csv`]: the row centre `y`, then the row's values (invalid: empty).
pub fn matrix_csv_row(out: &mut Vec<u8>, y: f64, values: &[f64]) {
    push_f64(out, y);
    for v in values {
        out.push(b',');
        push_cell(out, *v);
    }
    out.push(b'\n');
}

// Viridis, 9 stops.
const VIRIDIS: [(f64, f64, f64); 9] = [
    (68.0, 1.0, 84.0),
    (71.0, 44.0, 122.0),
    (59.0, 81.0, 139.0),
    (44.0, 113.0, 142.0),
    (33.0, 144.0, 141.0),
    (39.0, 173.0, 129.0),
    (92.0, 200.0, 99.0),
    (170.0, 220.0, 50.0),
    (253.0, 231.0, 37.0),
];
// Blue–white–red (ColorBrewer RdBu reversed), 7 stops.
const DIVERGING: [(f64, f64, f64); 7] = [
    (33.0, 102.0, 172.0),
    (103.0, 169.0, 207.0),
    (209.0, 229.0, 240.0),
    (247.0, 247.0, 247.0),
    (253.0, 219.0, 199.0),
    (239.0, 138.0, 98.0),
    (178.0, 24.0, 43.0),
];

fn ramp(stops: &[(f64, f64, f64)], t: f64) -> String {
    let t = t.clamp(0.0, 1.0) * (stops.len() - 1) as f64;
    let i = (t.floor() as usize).min(stops.len() - 2);
    let f = t - i as f64;
    let (a, b) = (stops[i], stops[i + 1]);
    let c = |x: f64, y: f64| (x + (y - x) * f).round() as u8;
    format!("#{:02x}{:02x}{:02x}", c(a.0, b.0), c(a.1, b.1), c(a.2, b.2))
}

/// Colour-scale limits: (low, high) of the finite values, symmetric about 0 when diverging,
/// widened when flat.
fn limits(map: &Heatmap<'_>) -> (f64, f64) {
    let (lo, hi) = map.range().unwrap_or((0.0, 1.0));
    let (lo, hi) = match map.scale {
        Scale::Sequential => (lo, hi),
        Scale::Diverging => {
            let m = lo.abs().max(hi.abs());
            (-m, m)
        }
    };
    if hi > lo {
        (lo, hi)
    } else {
        let pad = if lo == 0.0 { 1.0 } else { lo.abs() * 1e-3 };
        (lo - pad, hi + pad)
    }
}

fn colour(map: &Heatmap<'_>, v: f64, lo: f64, hi: f64) -> String {
    let t = (v - lo) / (hi - lo);
    match map.scale {
        Scale::Sequential => ramp(&VIRIDIS, t),
        Scale::Diverging => ramp(&DIVERGING, t),
    }
}

/// "Nice" tick positions covering [lo, hi].
pub fn nice_ticks(lo: f64, hi: f64, target: usize) -> Vec<f64> {
    if !(hi > lo) || !lo.is_finite() || !hi.is_finite() {
        return vec![lo];
    }
    let raw = (hi - lo) / target.max(1) as f64;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 2.5, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * mag);
    let first = (lo / step).ceil() * step;
    let mut ticks = Vec::new();
    let mut k = 0;
    loop {
        let t = first + k as f64 * step;
        if t > hi + step * 1e-9 {
            break;
        }
        // Snap tiny round-off to zero so labels read "0", not "-1.7e-16".
        ticks.push(if t.abs() < step * 1e-9 { 0.0 } else { t });
        k += 1;
    }
    ticks
}

fn label(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    if (1e-3..1e5).contains(&a) {
        let s = format!("{v:.4}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    } else {
        format!("{v:.2e}")
    }
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Cell edges from centres: midpoints, extended by half a spacing at the ends.
fn edges(c: &[f64]) -> Vec<f64> {
    if c.len() == 1 {
        return vec![c[0] - 0.5, c[0] + 0.5];
    }
    let mut e = Vec::with_capacity(c.len() + 1);
    e.push(c[0] - (c[1] - c[0]) / 2.0);
    for w in c.windows(2) {
        e.push((w[0] + w[1]) / 2.0);
    }
    let n = c.len();
    e.push(c[n - 1] + (c[n - 1] - c[n - 2]) / 2.0);
    e
}

/// Most cells drawn along one axis; finer maps are drawn block-averaged (the CSV keeps every
/// cell), which keeps a 401 × 401 map's picture a few MB instead of tens.
pub const MAX_SVG_CELLS_PER_AXIS: usize = 160;

/// Block means of `c` in runs of `f`.
fn block_centres(c: &[f64], f: usize) -> Vec<f64> {
    c.chunks(f)
        .map(|b| b.iter().sum::<f64>() / b.len() as f64)
        .collect()
}

/// Rows and columns per drawn block for a map of `ny × nx` cells: 1 × 1 up to
/// [`MAX_SVG_CELLS_PER_AXIS`] cells per axis.
pub fn svg_block(ny: usize, nx: usize) -> (usize, usize) {
    (
        ny.div_ceil(MAX_SVG_CELLS_PER_AXIS).max(1),
        nx.div_ceil(MAX_SVG_CELLS_PER_AXIS).max(1),
    )
}

/// Sums and counts of the finite values of a map's [`svg_block`] blocks, filled a band of rows
/// at a time, bottom row first (so a map need never be held whole). Within a block the values
/// are added row by row, left to right, as [`heatmap_svg`] adds them.
#[derive(Debug, Clone)]
pub struct BlockMeans {
    next_row: usize,
    fy: usize,
    fx: usize,
    nx: usize,
    bx: usize,
    sum: Vec<f64>,
    count: Vec<usize>,
}

impl BlockMeans {
    /// Accumulators for a map of `ny × nx` cells.
    pub fn new(ny: usize, nx: usize) -> Self {
        let (fy, fx) = svg_block(ny, nx);
        let (by, bx) = (ny.div_ceil(fy), nx.div_ceil(fx));
        Self {
            next_row: 0,
            fy,
            fx,
            nx,
            bx,
            sum: vec![0.0; by * bx],
            count: vec![0; by * bx],
        }
    }

    /// Add the next rows (`values` row-major, whole rows, following those added before).
    pub fn add_rows(&mut self, values: &[f64]) {
        let first = self.next_row;
        self.next_row += values.len() / self.nx;
        for (k, row) in values.chunks_exact(self.nx).enumerate() {
            let b = (first + k) / self.fy;
            for (bj, cells) in row.chunks(self.fx).enumerate() {
                let (mut s, mut n) = (self.sum[b * self.bx + bj], self.count[b * self.bx + bj]);
                for v in cells {
                    if v.is_finite() {
                        s += v;
                        n += 1;
                    }
                }
                self.sum[b * self.bx + bj] = s;
                self.count[b * self.bx + bj] = n;
            }
        }
    }

    /// The same sums in blocks of whole blocks, at most `max_cells` per axis (sums and counts
    /// add, so the means are those of the map's cells in the larger blocks).
    pub fn coarsened(&self, max_cells: usize) -> BlockMeans {
        let by = self.sum.len() / self.bx.max(1);
        let (gy, gx) = (
            by.div_ceil(max_cells.max(1)).max(1),
            self.bx.div_ceil(max_cells.max(1)).max(1),
        );
        let (cy, cx) = (by.div_ceil(gy), self.bx.div_ceil(gx));
        let mut out = BlockMeans {
            next_row: self.next_row,
            fy: self.fy * gy,
            fx: self.fx * gx,
            nx: self.nx,
            bx: cx,
            sum: vec![0.0; cy * cx],
            count: vec![0; cy * cx],
        };
        for b in 0..by {
            for bj in 0..self.bx {
                let (k, c) = (b * self.bx + bj, (b / gy) * cx + bj / gx);
                out.sum[c] += self.sum[k];
                out.count[c] += self.count[k];
            }
        }
        out
    }

    /// The blocks as a map: their centres along `xs` and `ys` (the map's cell centres) and
    /// their means, row-major (NaN where a block has no finite value).
    pub fn cells(&self, xs: &[f64], ys: &[f64]) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let values = self
            .sum
            .iter()
            .zip(&self.count)
            .map(|(s, &n)| if n > 0 { s / n as f64 } else { f64::NAN })
            .collect();
        (
            block_centres(xs, self.fx),
            block_centres(ys, self.fy),
            values,
        )
    }

    /// The SVG picture of `map` (whose `values` are ignored; its blocks were added here).
    pub fn svg(&self, map: &Heatmap<'_>) -> String {
        let values: Vec<f64> = self
            .sum
            .iter()
            .zip(&self.count)
            .map(|(s, &n)| if n > 0 { s / n as f64 } else { f64::NAN })
            .collect();
        blocks_svg(map, self.fy, self.fx, &values)
    }
}

/// The picture of `map` drawn from its `fy × fx` block means `values`.
fn blocks_svg(map: &Heatmap<'_>, fy: usize, fx: usize, values: &[f64]) -> String {
    if fx == 1 && fy == 1 {
        return draw_svg(&Heatmap { values, ..*map });
    }
    let xs = block_centres(map.xs, fx);
    let ys = block_centres(map.ys, fy);
    let title = format!("{} (drawn as {fy}×{fx}-cell block means)", map.title);
    draw_svg(&Heatmap {
        title: &title,
        xs: &xs,
        ys: &ys,
        values,
        ..*map
    })
}

/// SVG picture of a coarse map of bins with edges `x_edges` and `y_edges` (one more than the
/// columns and rows; bins of unequal width, e.g. quantile bins, drawn as they are): as
/// [`heatmap_svg`], without block means.
pub fn binned_heatmap_svg(map: &Heatmap<'_>, x_edges: &[f64], y_edges: &[f64]) -> String {
    map.check();
    draw_svg_on_edges(map, x_edges, y_edges)
}

/// SVG picture of the map: cells, axes with ticks, a colour bar with the value label and unit,
/// the marker, and the title. Invalid cells are light grey. Maps finer than
/// [`MAX_SVG_CELLS_PER_AXIS`] are drawn as block means of their valid cells.
pub fn heatmap_svg(map: &Heatmap<'_>) -> String {
    map.check();
    let mut blocks = BlockMeans::new(map.ys.len(), map.xs.len());
    blocks.add_rows(map.values);
    blocks.svg(map)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample<'a>(xs: &'a [f64], ys: &'a [f64], v: &'a [f64]) -> Heatmap<'a> {
        Heatmap {
            title: "t",
            x_label: "z, mm",
            y_label: "y, mm",
            value_label: "ball speed, mph",
            xs,
            ys,
            values: v,
            marker: Some((0.0, 0.0)),
            scale: Scale::Sequential,
        }
    }

    #[test]
    fn csv_matrix_has_top_row_first_and_blank_invalid_cells() {
        let (xs, ys) = ([-1.0, 0.0, 1.0], [-2.0, 2.0]);
        let v = [1.0, 2.0, 3.0, 4.0, f64::NAN, 6.0];
        let csv = String::from_utf8(matrix_csv(&sample(&xs, &ys, &v))).unwrap();
        assert_eq!(csv, "y\\x,-1,0,1\n2,4,,6\n-2,1,2,3\n");
    }

    #[test]
    fn svg_has_cells_colour_bar_marker_and_no_nan() {
        let (xs, ys) = ([-1.0, 0.0, 1.0], [-2.0, 2.0]);
        let v = [1.0, 2.0, 3.0, 4.0, f64::NAN, 6.0];
        let svg = heatmap_svg(&sample(&xs, &ys, &v));
        assert!(svg.starts_with("<svg"));
        assert!(svg.contains("ball speed, mph"));
        assert!(svg.contains("<circle"));
        assert!(svg.contains("#e0e0e0"));
        assert!(!svg.to_lowercase().contains("nan"));
        assert!(!svg.contains("inf"));
    }

    #[test]
    fn ticks_are_round_and_cover_the_range() {
        assert_eq!(
            nice_ticks(-20.0, 20.0, 8),
            vec![-20.0, -15.0, -10.0, -5.0, 0.0, 5.0, 10.0, 15.0, 20.0]
        );
        let t = nice_ticks(0.013, 0.091, 5);
        assert!(t.first().unwrap() >= &0.013 && t.last().unwrap() <= &0.091);
    }

    #[test]
    fn fine_maps_are_drawn_block_averaged() {
        let n = 401;
        let xs: Vec<f64> = (0..n).map(|i| i as f64).collect();
        let v: Vec<f64> = (0..n * n)
            .map(|k| if k % n < 3 { f64::NAN } else { 1.0 })
            .collect();
        let svg = heatmap_svg(&sample(&xs, &xs, &v));
        let cells = svg.matches("<rect").count();
        assert!(cells < 150 * 150, "{cells} rects");
        assert!(svg.contains("block means"));
        assert!(!svg.to_lowercase().contains("nan"));
    }

    #[test]
    fn coarsened_blocks_are_the_means_of_their_cells() {
        let (ny, nx) = (7, 5);
        let xs: Vec<f64> = (0..nx).map(|i| i as f64).collect();
        let ys: Vec<f64> = (0..ny).map(|i| 10.0 * i as f64).collect();
        let v: Vec<f64> = (0..ny * nx)
            .map(|k| if k == 3 { f64::NAN } else { k as f64 })
            .collect();
        let mut b = BlockMeans::new(ny, nx);
        b.add_rows(&v);
        let (cx, cy, means) = b.coarsened(3).cells(&xs, &ys);
        assert_eq!((cx.len(), cy.len()), (3, 3));
        assert_eq!(cx, vec![0.5, 2.5, 4.0]);
        assert_eq!(cy, vec![10.0, 40.0, 60.0]);
        // The first block: rows 0–2, columns 0–1 (cells 0, 1, 5, 6, 10, 11).
        assert_eq!(means[0], 33.0 / 6.0);
        // The block holding the NaN cell: cells 2, 3 (NaN), 7, 8, 12, 13.
        assert_eq!(means[1], 42.0 / 5.0);
        // The last row of blocks is row 6 alone, the last column column 4 alone.
        assert_eq!(means[8], 34.0);
        // Coarsening to at least the map's size changes nothing.
        let same = b.coarsened(100).cells(&xs, &ys).2;
        assert_eq!(same.len(), v.len());
        for (a, e) in same.iter().zip(&v) {
            assert!(a == e || (a.is_nan() && e.is_nan()), "{a} against {e}");
        }
    }

    #[test]
    fn diverging_scale_is_symmetric() {
        let (xs, ys) = ([0.0, 1.0], [0.0]);
        let v = [-1.0, 3.0];
        let m = Heatmap {
            scale: Scale::Diverging,
            ..sample(&xs, &ys, &v)
        };
        assert_eq!(limits(&m), (-3.0, 3.0));
    }
}
