//! How a row or a set of points is cut into fixed-size chunks of [`LANES`] points, so that every
//! point goes through the same code whatever its position (the tail is padded), and how a chunk
//! reaches the kernel's monomorphised point code ([`FaceMapKernel::dispatch`]).

use super::grid::fill_invalid;
use super::{Chunk, FaceMapKernel, Row, RowOut, LANES};
use crate::lanes::{V, W};

/// A row or a set of points, run by [`FaceMapKernel::dispatch`].
pub(super) trait Job {
    fn run<const FRICTION: bool, const POWER: bool, const USER: bool>(
        &self,
        k: &FaceMapKernel,
        out: RowOut<'_>,
    );
    /// Number of points.
    fn len(&self) -> usize;
    /// Point `i`: `(y, z)`, m.
    fn at(&self, i: usize) -> (f64, f64);
}

/// One grid row: the heights are fixed in `row`.
pub(super) struct RowJob<'a> {
    pub(super) row: &'a Row,
    pub(super) zs: &'a [f64],
}

impl Job for RowJob<'_> {
    #[inline(always)]
    fn run<const FRICTION: bool, const POWER: bool, const USER: bool>(
        &self,
        k: &FaceMapKernel,
        out: RowOut<'_>,
    ) {
        k.row_impl::<FRICTION, POWER, USER>(self.row, self.zs, out)
    }
    fn len(&self) -> usize {
        self.zs.len()
    }
    fn at(&self, i: usize) -> (f64, f64) {
        (self.row.y.0[0], self.zs[i])
    }
}

/// Arbitrary points.
pub(super) struct PointsJob<'a> {
    pub(super) ys: &'a [f64],
    pub(super) zs: &'a [f64],
}

impl Job for PointsJob<'_> {
    #[inline(always)]
    fn run<const FRICTION: bool, const POWER: bool, const USER: bool>(
        &self,
        k: &FaceMapKernel,
        out: RowOut<'_>,
    ) {
        k.points_impl::<FRICTION, POWER, USER>(self.ys, self.zs, out)
    }
    fn len(&self) -> usize {
        self.zs.len()
    }
    fn at(&self, i: usize) -> (f64, f64) {
        (self.ys[i], self.zs[i])
    }
}

/// What [`for_chunks`] runs on each chunk (a trait rather than a closure so that it is inlined
/// into the `target_feature` functions and compiled with their instruction set).
trait ChunkFn {
    fn call(&self, a: &[f64; LANES], b: &[f64; LANES], out: Chunk<'_>);
}

/// Chunks of a row: `b` holds the heel–toe locations (`a` is unused).
struct RowChunks<'a, const FRICTION: bool, const POWER: bool, const USER: bool> {
    k: &'a FaceMapKernel,
    row: &'a Row,
}

impl<const FRICTION: bool, const POWER: bool, const USER: bool> ChunkFn
    for RowChunks<'_, FRICTION, POWER, USER>
{
    #[inline(always)]
    fn call(&self, _: &[f64; LANES], zs: &[f64; LANES], out: Chunk<'_>) {
        self.k.row_chunk::<FRICTION, POWER, USER>(self.row, zs, out)
    }
}

/// Chunks of arbitrary points: `a` holds the heights, `b` the heel–toe locations.
struct PointChunks<'a, const FRICTION: bool, const POWER: bool, const USER: bool> {
    k: &'a FaceMapKernel,
}

impl<const FRICTION: bool, const POWER: bool, const USER: bool> ChunkFn
    for PointChunks<'_, FRICTION, POWER, USER>
{
    #[inline(always)]
    fn call(&self, ys: &[f64; LANES], zs: &[f64; LANES], out: Chunk<'_>) {
        self.k.points_chunk::<FRICTION, POWER, USER>(ys, zs, out)
    }
}

/// Run `f` over the chunks of `(a, b)`, the tail padded to a full chunk (with the last point
/// repeated), so every point goes through the same code whatever its position. One call site
/// of `f`: the point code is inlined once per instance, not once for the full chunks and again
/// for the tail (inputs and outputs go through a chunk's buffers, a copy per point that costs
/// little beside an impact).
#[inline(always)]
fn for_chunks(a: &[f64], b: &[f64], out: RowOut<'_>, f: &impl ChunkFn) {
    let n = b.len();
    let mut i = 0;
    while i < n {
        let m = LANES.min(n - i);
        let (mut pa, mut pb) = ([a[i + m - 1]; LANES], [b[i + m - 1]; LANES]);
        pa[..m].copy_from_slice(&a[i..i + m]);
        pb[..m].copy_from_slice(&b[i..i + m]);
        let mut o = [[0.0; LANES]; 5];
        let mut v = [false; LANES];
        let [o0, o1, o2, o3, o4] = &mut o;
        f.call(
            &pa,
            &pb,
            Chunk {
                speed: o0,
                launch: o1,
                azimuth: o2,
                backspin: o3,
                sidespin: o4,
                valid: &mut v,
            },
        );
        let r = i..i + m;
        out.ball_speed_m_s[r.clone()].copy_from_slice(&o[0][..m]);
        out.launch_angle_rad[r.clone()].copy_from_slice(&o[1][..m]);
        out.azimuth_rad[r.clone()].copy_from_slice(&o[2][..m]);
        out.backspin_rad_s[r.clone()].copy_from_slice(&o[3][..m]);
        out.sidespin_rad_s[r.clone()].copy_from_slice(&o[4][..m]);
        out.valid[r].copy_from_slice(&v[..m]);
        i += m;
    }
}

impl FaceMapKernel {
    /// One chunk of a row.
    #[inline(always)]
    fn row_chunk<const FRICTION: bool, const POWER: bool, const USER: bool>(
        &self,
        row: &Row,
        zs: &[f64; LANES],
        mut out: Chunk<'_>,
    ) {
        for k in 0..LANES / W {
            let z = V(zs[k * W..(k + 1) * W].try_into().unwrap());
            let o = self.point::<FRICTION, POWER, USER>(row, z);
            out.store(k, &o);
        }
    }

    /// One chunk of arbitrary points.
    #[inline(always)]
    fn points_chunk<const FRICTION: bool, const POWER: bool, const USER: bool>(
        &self,
        ys: &[f64; LANES],
        zs: &[f64; LANES],
        mut out: Chunk<'_>,
    ) {
        for k in 0..LANES / W {
            let y = V(ys[k * W..(k + 1) * W].try_into().unwrap());
            let z = V(zs[k * W..(k + 1) * W].try_into().unwrap());
            let row = self.row(y);
            let o = self.point::<FRICTION, POWER, USER>(&row, z);
            out.store(k, &o);
        }
    }

    #[inline(always)]
    fn row_impl<const FRICTION: bool, const POWER: bool, const USER: bool>(
        &self,
        row: &Row,
        zs: &[f64],
        out: RowOut<'_>,
    ) {
        if !row.ok.get(0) {
            fill_invalid(out);
            return;
        }
        for_chunks(
            zs,
            zs,
            out,
            &RowChunks::<FRICTION, POWER, USER> { k: self, row },
        );
    }

    #[inline(always)]
    fn points_impl<const FRICTION: bool, const POWER: bool, const USER: bool>(
        &self,
        ys: &[f64],
        zs: &[f64],
        out: RowOut<'_>,
    ) {
        for_chunks(
            ys,
            zs,
            out,
            &PointChunks::<FRICTION, POWER, USER> { k: self },
        );
    }
}
