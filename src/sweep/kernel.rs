//! The face-map kernel: launch conditions over many impact points for one (model, delivery).
//!
//! Design studies evaluate one delivery at many impact locations, for many model variants.
//! [`FaceMapKernel::new`] precomputes everything that does not depend on the impact location
//! (face orientation with loft/face bias, clubhead velocities in the face frame `F`, inverse
//! inertia, COR and ball terms, the rotation back to `G` scaled by `1/m_b` and `1/I_b`); a row
//! of a grid (fixed height `y`) additionally fixes the torus quantities `s`, `ρ`, `n_y` and the
//! `y`-parts of `r_c`. The per-point work is then the model of [`crate::physics::impact`]
//! written as straight-line arithmetic (selects instead of branches, a vectorisable
//! [`atan2`](super::fastmath::atan2); the one branch is a rarely taken exact recheck of the
//! sign of `u1·n` near zero), evaluated over structure-of-arrays chunks of
//! [`LANES`] points that the compiler turns into packed AVX2 code (selected at run time, with a
//! portable fallback). An AVX-512 path would need `target_feature(enable = "avx512f")`, stable
//! only from Rust 1.89 (the crate's MSRV is 1.85).
//!
//! # Same results as [`ImpactModel::solve`]
//!
//! The physical laws (restitution with `cor_speed`/`cor_radial`/`cor_power`, the ball lever arm,
//! the collision matrix, the tangential law with friction slip as a blend of the two branches)
//! are not written here: the kernel evaluates the model's [`crate::physics::laws`] on lanes, the
//! same code the scalar solve runs on one shot. [`FaceMapKernel::new`] names every field of
//! [`ModelParams`], so a new one does not compile until it is handled. The torus test and `u1` use
//! exactly the operations of the generic path, and the sign of `u1·n` is taken from a fast
//! normal unless it is within 1e-13 of rounding, where `n` and `u1·n` are recomputed with the
//! generic path's operations: a point is invalid here exactly when [`ImpactModel::solve`]
//! fails for it, to the last bit (tested at the rim of the approach region). The rest is
//! rearranged for speed and agrees with `solve` + `launch()` to ~1e-15 relative
//! (property-tested at 1e-12; 1e-9 absolute for angles and spins near zero).
//!
//! # Determinism
//!
//! A point's outputs depend only on its own `(y, z)` and the kernel: every point goes through
//! the same sequence of IEEE-754 operations (`+ − × ÷ √`, no fused multiply–add; the one libm
//! call, `pow` for a `cor_power` exponent, runs lane by lane on the same function; no other libm
//! calls), whatever its lane, its chunk, the row length, the thread that runs it, or whether
//! the AVX2 or the portable path runs (the exact `u1·n` recheck is selected per lane from the
//! lane's own values). The tail of a row is padded into a full chunk. So sharded or
//! multi-threaded grids merge bit for bit (property-tested: rows vs rotated point lists vs
//! 1 and 3 threads vs the portable path).

use nalgebra::{Matrix3, Vector3};
use rayon::prelude::*;

use super::fastmath::atan2_v;
use crate::lanes::{M, V, W};
use crate::physics::laws::{Laws, TangentialLaw};
use crate::physics::{Delivery, ImpactModel, LaunchComponent, ModelParams};

/// Points per chunk: the unit the vector code works on.
pub const LANES: usize = 8;

/// Fewest grid rows a rayon task takes (a row of a few hundred points is only a few µs).
const ROWS_PER_TASK: usize = 4;

/// Launch outputs over a set of impact points, structure of arrays, SI units, row-major for
/// grids. Invalid points (off the face torus, or club not approaching the ball) have
/// `valid = false` and NaN outputs.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LaunchGrid {
    /// Ball speed, m/s.
    pub ball_speed_m_s: Vec<f64>,
    /// Launch angle, rad (+ up).
    pub launch_angle_rad: Vec<f64>,
    /// Azimuth, rad (+ right of target).
    pub azimuth_rad: Vec<f64>,
    /// Backspin, rad/s.
    pub backspin_rad_s: Vec<f64>,
    /// Sidespin, rad/s (+ slice for a right-hander).
    pub sidespin_rad_s: Vec<f64>,
    /// Whether the impact at this point is physical (on the face, club approaching the ball).
    pub valid: Vec<bool>,
}

/// Mutable output slices for one row or point set (same fields as [`LaunchGrid`], equal
/// lengths).
#[derive(Debug)]
pub struct RowOut<'a> {
    /// Ball speed, m/s.
    pub ball_speed_m_s: &'a mut [f64],
    /// Launch angle, rad.
    pub launch_angle_rad: &'a mut [f64],
    /// Azimuth, rad.
    pub azimuth_rad: &'a mut [f64],
    /// Backspin, rad/s.
    pub backspin_rad_s: &'a mut [f64],
    /// Sidespin, rad/s.
    pub sidespin_rad_s: &'a mut [f64],
    /// Validity flags.
    pub valid: &'a mut [bool],
}

impl RowOut<'_> {
    /// Number of points (the length of every slice).
    pub fn len(&self) -> usize {
        self.valid.len()
    }

    /// Whether there are no points.
    pub fn is_empty(&self) -> bool {
        self.valid.is_empty()
    }

    fn assert_len(&self, n: usize) {
        for (name, len) in [
            ("ball_speed_m_s", self.ball_speed_m_s.len()),
            ("launch_angle_rad", self.launch_angle_rad.len()),
            ("azimuth_rad", self.azimuth_rad.len()),
            ("backspin_rad_s", self.backspin_rad_s.len()),
            ("sidespin_rad_s", self.sidespin_rad_s.len()),
            ("valid", self.valid.len()),
        ] {
            assert_eq!(len, n, "RowOut.{name} has {len} entries for {n} points");
        }
    }
}

impl LaunchGrid {
    /// A grid of `n` points, all NaN and invalid.
    pub fn with_len(n: usize) -> Self {
        Self {
            ball_speed_m_s: vec![f64::NAN; n],
            launch_angle_rad: vec![f64::NAN; n],
            azimuth_rad: vec![f64::NAN; n],
            backspin_rad_s: vec![f64::NAN; n],
            sidespin_rad_s: vec![f64::NAN; n],
            valid: vec![false; n],
        }
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.valid.len()
    }

    /// Whether the grid has no points.
    pub fn is_empty(&self) -> bool {
        self.valid.is_empty()
    }

    /// One launch component, SI units (m/s, rad, rad/s).
    pub fn component(&self, c: LaunchComponent) -> &[f64] {
        match c {
            LaunchComponent::BallSpeed => &self.ball_speed_m_s,
            LaunchComponent::LaunchAngle => &self.launch_angle_rad,
            LaunchComponent::Azimuth => &self.azimuth_rad,
            LaunchComponent::Backspin => &self.backspin_rad_s,
            LaunchComponent::Sidespin => &self.sidespin_rad_s,
        }
    }

    /// Output slices for the points `start..start + len`.
    ///
    /// # Panics
    /// If the range is outside the grid.
    pub fn row_out(&mut self, start: usize, len: usize) -> RowOut<'_> {
        let r = start..start + len;
        RowOut {
            ball_speed_m_s: &mut self.ball_speed_m_s[r.clone()],
            launch_angle_rad: &mut self.launch_angle_rad[r.clone()],
            azimuth_rad: &mut self.azimuth_rad[r.clone()],
            backspin_rad_s: &mut self.backspin_rad_s[r.clone()],
            sidespin_rad_s: &mut self.sidespin_rad_s[r.clone()],
            valid: &mut self.valid[r],
        }
    }

    /// Resize to `n` points (allocates only if the capacity is too small).
    pub fn resize(&mut self, n: usize) {
        self.ball_speed_m_s.resize(n, f64::NAN);
        self.launch_angle_rad.resize(n, f64::NAN);
        self.azimuth_rad.resize(n, f64::NAN);
        self.backspin_rad_s.resize(n, f64::NAN);
        self.sidespin_rad_s.resize(n, f64::NAN);
        self.valid.resize(n, false);
    }

    /// Output slices for the whole grid.
    pub fn all_out(&mut self) -> RowOut<'_> {
        let n = self.len();
        self.row_out(0, n)
    }
}

/// Everything about one (model, delivery) pair that does not depend on the impact location,
/// precomputed once. Cheap to copy; `Send + Sync`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FaceMapKernel {
    /// Roll (torus tube radius `r`), m.
    roll_m: f64,
    /// Torus major radius `R = B − Rr`, m.
    major_m: f64,
    /// Bulge `B`, m.
    bulge_m: f64,
    /// Clubhead CoM in F, m.
    com_m: [f64; 3],
    /// Clubhead CoM velocity in F, m/s.
    v_c: [f64; 3],
    /// Clubhead angular velocity in F, rad/s.
    w_c: [f64; 3],
    /// The model's laws (restitution, ball lever arm, collision matrix, tangential law),
    /// evaluated on lanes with the same code as the scalar solve (with the delivery's
    /// user-defined mass and geometry applied).
    laws: Laws,
    /// The delivery's variables for user-defined `cor`/`et`/`mu` expressions.
    user_vars: [f64; crate::physics::user_terms::NV],
    /// A user-defined mass or geometry expression failed for this delivery: every point is
    /// invalid.
    broken: bool,
    /// `R_GF / m_b`: ball impulse in F → ball velocity in G.
    r_v: [[f64; 3]; 3],
    /// Rows y and z of `R_GF / I_b`: `r_b × P` in F → ball spin components y, z in G.
    r_w: [[f64; 3]; 2],
}

/// Quantities fixed along a row (one impact height `y`), per lane (all lanes equal for a row
/// of a grid; one height per lane for arbitrary points).
#[derive(Debug, Clone, Copy)]
struct Row {
    /// The height is on the torus (`s² > 0`, `ρ > 0`).
    ok: M,
    /// `y`, m.
    y: V,
    /// `y²`, m².
    yy: V,
    /// `s = sqrt(r² − y²)`, m.
    s: V,
    /// `ρ = R + s`, m.
    rho: V,
    /// `ρ²`, m².
    rho2: V,
    /// `1/ρ`, 1/m.
    inv_rho: V,
    /// `n_y = y/r`.
    ny: V,
    /// `s/(ρ·r)`: `n_x = X·s/(ρ·r)`, `n_z = z·s/(ρ·r)`.
    n_scale: V,
    /// `r_c,y = y − r_C,y`, m.
    rcy: V,
    /// `ω_z·r_c,y`, m/s.
    wz_rcy: V,
    /// `ω_x·r_c,y`, m/s.
    wx_rcy: V,
}

/// One vector of points' outputs.
#[derive(Debug, Clone, Copy)]
struct Out {
    speed: V,
    launch: V,
    azimuth: V,
    backspin: V,
    sidespin: V,
    valid: M,
}

/// Fixed-size output chunk.
struct Chunk<'a> {
    speed: &'a mut [f64; LANES],
    launch: &'a mut [f64; LANES],
    azimuth: &'a mut [f64; LANES],
    backspin: &'a mut [f64; LANES],
    sidespin: &'a mut [f64; LANES],
    valid: &'a mut [bool; LANES],
}

impl Chunk<'_> {
    /// Store vector `k` of the chunk.
    #[inline(always)]
    fn store(&mut self, k: usize, o: &Out) {
        let r = k * W..(k + 1) * W;
        self.speed[r.clone()].copy_from_slice(&o.speed.0);
        self.launch[r.clone()].copy_from_slice(&o.launch.0);
        self.azimuth[r.clone()].copy_from_slice(&o.azimuth.0);
        self.backspin[r.clone()].copy_from_slice(&o.backspin.0);
        self.sidespin[r.clone()].copy_from_slice(&o.sidespin.0);
        for (i, v) in self.valid[r].iter_mut().enumerate() {
            *v = o.valid.get(i);
        }
    }
}

impl FaceMapKernel {
    /// Precompute the location-independent part of the impact of `delivery` on `model`.
    /// `delivery`'s impact location is ignored.
    pub fn new(model: &ImpactModel, delivery: &Delivery) -> Self {
        // Every field of the parameters is named here, so that a new one stops the build until
        // the kernel handles it. Most reach the kernel through the model's laws, the face or
        // the face orientation; the rest are read below.
        let ModelParams {
            club_mass_kg: _,           // in laws.collision
            club_com_m,                // r_c below
            club_inertia_kgm2: _,      // in laws.collision
            cor: _,                    // in laws.restitution
            bulge_m: _,                // in model.face()
            roll_m: _,                 // in model.face()
            ball_mass_kg,              // r_v below; in laws.collision
            ball_radius_m: _,          // in laws.ball
            ball_inertia_kgm2,         // r_w below; in laws.collision
            ball_offset_y_m: _,        // in laws.ball
            ball_offset_z_m: _,        // in laws.ball
            tangential_restitution: _, // in laws.tangential
            friction_mu: _,            // in laws.tangential
            cor_speed_k_s_per_m: _,    // in laws.restitution
            cor_power_q: _,            // in laws.restitution
            cor_radial_c_per_m2: _,    // in laws.restitution
            loft_bias_rad: _,          // in model.face_orientation
            face_bias_rad: _,          // in model.face_orientation
            hosel_m: _,                // composed into mass, CoM and inertia by the effects
            user,                      // mass and geometry below; cor, et, mu in laws.user
        } = model.params();
        // User-defined mass and geometry depend on the delivery only (not on the impact
        // location: `crate::effects::user`), so they are fixed for the whole face map.
        let mut laws = *model.laws();
        let mut club_com_m = *club_com_m;
        let mut r_gf = model.face_orientation(delivery);
        let mut broken = false;
        let user_vars = crate::physics::user_terms::delivery_vars(delivery);
        if user.has_pre_solve() {
            match model.shot(delivery) {
                Ok(shot) => {
                    laws = shot.laws;
                    club_com_m = shot.club_com_m;
                    r_gf = shot.r_gf;
                }
                Err(_) => broken = true,
            }
        }
        // Exactly the operations of `ImpactModel::solve`, so u1·n has the same bits.
        let r_fg = r_gf.transpose();
        let v_c = r_fg * delivery.club_velocity_m_s();
        let w_c = r_fg * delivery.club_omega_rad_s;
        let r_v: Matrix3<f64> = r_gf * (1.0 / ball_mass_kg);
        let r_w: Matrix3<f64> = r_gf * (1.0 / ball_inertia_kgm2);
        let face = model.face();
        let arr = |v: Vector3<f64>| [v.x, v.y, v.z];
        Self {
            roll_m: face.roll_m(),
            major_m: face.bulge_m() - face.roll_m(),
            bulge_m: face.bulge_m(),
            com_m: arr(club_com_m),
            v_c: arr(v_c),
            w_c: arr(w_c),
            laws,
            user_vars,
            broken,
            r_v: [
                [r_v[(0, 0)], r_v[(0, 1)], r_v[(0, 2)]],
                [r_v[(1, 0)], r_v[(1, 1)], r_v[(1, 2)]],
                [r_v[(2, 0)], r_v[(2, 1)], r_v[(2, 2)]],
            ],
            r_w: [
                [r_w[(1, 0)], r_w[(1, 1)], r_w[(1, 2)]],
                [r_w[(2, 0)], r_w[(2, 1)], r_w[(2, 2)]],
            ],
        }
    }

    /// Evaluate one row: the points `(y_m, zs_m[j])` into `out` (each slice of `zs_m.len()`).
    ///
    /// # Panics
    /// If an output slice has another length than `zs_m`.
    pub fn eval_row(&self, y_m: f64, zs_m: &[f64], out: RowOut<'_>) {
        self.eval_row_on(simd_level(), y_m, zs_m, out)
    }

    /// [`FaceMapKernel::eval_row`] on a given code path (to check that all paths give the same
    /// bits). A path this machine does not support falls back to [`SimdLevel::Portable`].
    ///
    /// # Panics
    /// If an output slice has another length than `zs_m`.
    pub fn eval_row_on(&self, level: SimdLevel, y_m: f64, zs_m: &[f64], out: RowOut<'_>) {
        out.assert_len(zs_m.len());
        let row = self.row(V::splat(y_m));
        let level = if level == SimdLevel::Avx2 {
            simd_level()
        } else {
            level
        };
        self.dispatch(
            level,
            &RowJob {
                row: &row,
                zs: zs_m,
            },
            out,
        );
    }

    /// Evaluate arbitrary points `(ys_m[i], zs_m[i])` into `out`.
    ///
    /// # Panics
    /// If `ys_m` and `zs_m` differ in length, or an output slice has another length.
    pub fn eval_points(&self, ys_m: &[f64], zs_m: &[f64], out: RowOut<'_>) {
        self.eval_points_on(simd_level(), ys_m, zs_m, out)
    }

    /// [`FaceMapKernel::eval_points`] on a given code path (see
    /// [`FaceMapKernel::eval_row_on`]).
    ///
    /// # Panics
    /// As [`FaceMapKernel::eval_points`].
    pub fn eval_points_on(&self, level: SimdLevel, ys_m: &[f64], zs_m: &[f64], out: RowOut<'_>) {
        assert_eq!(
            ys_m.len(),
            zs_m.len(),
            "eval_points: {} heights for {} heel-toe locations",
            ys_m.len(),
            zs_m.len()
        );
        out.assert_len(zs_m.len());
        let level = if level == SimdLevel::Avx2 {
            simd_level()
        } else {
            level
        };
        self.dispatch(level, &PointsJob { ys: ys_m, zs: zs_m }, out);
    }

    /// Evaluate the grid `ys_m × zs_m` (row-major) on the calling thread.
    ///
    /// # Panics
    /// If `out` does not have `ys_m.len() · zs_m.len()` points.
    pub fn eval_grid(&self, ys_m: &[f64], zs_m: &[f64], out: &mut LaunchGrid) {
        let nz = zs_m.len();
        assert_eq!(out.len(), ys_m.len() * nz, "grid size");
        for (i, &y) in ys_m.iter().enumerate() {
            self.eval_row(y, zs_m, out.row_out(i * nz, nz));
        }
    }

    /// Evaluate the grid `ys_m × zs_m` (row-major), rows in parallel on the rayon pool.
    /// Bit-identical to [`FaceMapKernel::eval_grid`] for any number of threads.
    ///
    /// # Panics
    /// If `out` does not have `ys_m.len() · zs_m.len()` points.
    pub fn par_eval_grid(&self, ys_m: &[f64], zs_m: &[f64], out: &mut LaunchGrid) {
        let nz = zs_m.len();
        assert_eq!(out.len(), ys_m.len() * nz, "grid size");
        if nz == 0 || ys_m.is_empty() {
            return;
        }
        (
            ys_m.par_iter(),
            out.ball_speed_m_s.par_chunks_mut(nz),
            out.launch_angle_rad.par_chunks_mut(nz),
            out.azimuth_rad.par_chunks_mut(nz),
            out.backspin_rad_s.par_chunks_mut(nz),
            out.sidespin_rad_s.par_chunks_mut(nz),
            out.valid.par_chunks_mut(nz),
        )
            .into_par_iter()
            .with_min_len(ROWS_PER_TASK)
            .for_each(
                |(
                    &y,
                    ball_speed_m_s,
                    launch_angle_rad,
                    azimuth_rad,
                    backspin_rad_s,
                    sidespin_rad_s,
                    valid,
                )| {
                    self.eval_row(
                        y,
                        zs_m,
                        RowOut {
                            ball_speed_m_s,
                            launch_angle_rad,
                            azimuth_rad,
                            backspin_rad_s,
                            sidespin_rad_s,
                            valid,
                        },
                    )
                },
            );
    }

    /// The row quantities at heights `y`.
    #[inline(always)]
    fn row(&self, y: V) -> Row {
        // Same operations as `FaceGeometry::contact`.
        let r = self.roll_m;
        let s2 = r * r - y * y;
        let s = s2.sqrt();
        let rho = self.major_m + s;
        let rcy = y - self.com_m[1];
        let zero = V::splat(0.0);
        Row {
            ok: s2.gt(zero) & rho.gt(zero),
            y,
            yy: y * y,
            s,
            rho,
            rho2: rho * rho,
            inv_rho: 1.0 / rho,
            ny: y / r,
            n_scale: s / (rho * r),
            rcy,
            wz_rcy: self.w_c[2] * rcy,
            wx_rcy: self.w_c[0] * rcy,
        }
    }

    /// Impacts at heel–toe locations `z` on `row`: straight-line code, no branches.
    #[inline(always)]
    fn point<const FRICTION: bool, const POWER: bool, const USER: bool>(
        &self,
        row: &Row,
        z: V,
    ) -> Out {
        let zero = V::splat(0.0);
        // Contact point and normal, with the operations of `FaceGeometry::contact`.
        let x2 = row.rho2 - z * z;
        let on_face = row.ok & x2.gt(zero);
        let x = x2.sqrt();
        // n = (s·X/ρ, y, s·z/ρ)/r with the row's s/(ρ·r) (the generic path divides twice;
        // the difference is an ulp or two, and only matters for the sign of u1·n below).
        let nx = x * row.n_scale;
        let ny = row.ny;
        let nz = z * row.n_scale;
        // r_c and u1 = v_c + ω_c × r_c, with the operations of `ImpactModel::solve`.
        let rcx = (x - self.bulge_m) - self.com_m[0];
        let rcy = row.rcy;
        let rcz = z - self.com_m[2];
        let [vx, vy, vz] = self.v_c;
        let [wx, wy, wz] = self.w_c;
        let u1x = vx + (wy * rcz - row.wz_rcy);
        let u1y = vy + (wz * rcx - wx * rcz);
        let u1z = vz + (row.wx_rcy - wy * rcx);
        let (u1n_x, u1n_y, u1n_z) = (u1x * nx, u1y * ny, u1z * nz);
        let u1n = u1n_x + u1n_y + u1n_z;
        // The club approaches the ball if u1·n > 0. The sign of the fast u1·n is certain unless
        // it is within 1e-13 of the terms' magnitude (its error is ~1e-15 of it); there, redo
        // n and u1·n with exactly the operations of the generic path, so that validity agrees
        // with `ImpactModel::solve` to the last bit. (Lanes decide by their own values only.)
        let unsure = u1n
            .abs()
            .le((u1n_x.abs() + u1n_y.abs() + u1n_z.abs()) * 1e-13);
        let approaching = if unsure.any() {
            let nx_exact = row.s * x / row.rho / self.roll_m;
            let nz_exact = row.s * z / row.rho / self.roll_m;
            let u1n_exact = u1x * nx_exact + u1y * ny + u1z * nz_exact;
            unsure.select_mask(u1n_exact.gt(zero), u1n.gt(zero))
        } else {
            u1n.gt(zero)
        };
        let mut valid = on_face & approaching;

        let laws = &self.laws;
        let e = laws.restitution.cor_with::<V, POWER>(u1n, row.yy + z * z);
        let u1 = [u1x, u1y, u1z];
        let n = [nx, ny, nz];
        let (e, e_t, mu) = if USER {
            use crate::physics::user_terms::{NV, VAR_IMPACT_Y, VAR_IMPACT_Z, VAR_U1N, VAR_UT};
            let mut vars: [V; NV] = self.user_vars.map(V::splat);
            vars[VAR_IMPACT_Y as usize] = row.y * 1e3;
            vars[VAR_IMPACT_Z as usize] = z * 1e3;
            vars[VAR_U1N as usize] = u1n;
            vars[VAR_UT as usize] = crate::physics::laws::tangential_speed(&u1, &n, u1n);
            let (e, e_t, mu) = laws.user.contact(
                &mut vars,
                e,
                V::splat(laws.tangential.e_t),
                V::splat(laws.tangential.mu.unwrap_or(f64::INFINITY)),
            );
            // Lanes whose user-defined values are not allowed are invalid (the scalar solve
            // names the effect for them): e and e_t finite, mu > 0 and finite when set.
            let finite = |x: V| x.abs().le(V::splat(f64::MAX));
            valid = valid & finite(e) & finite(e_t);
            if laws.user.sets_mu() {
                valid = valid & finite(mu) & mu.gt(zero);
            }
            (e, e_t, mu)
        } else {
            (
                e,
                V::splat(laws.tangential.e_t),
                V::splat(laws.tangential.mu.unwrap_or(f64::INFINITY)),
            )
        };

        // Impact frame tangents z_I = (−z, 0, X)/ρ, y_I = z_I × n, and the ball lever arm.
        let tzx = -z * row.inv_rho;
        let tzz = x * row.inv_rho;
        let tyx = -(tzz * ny);
        let tyy = tzz * nx - tzx * nz;
        let tyz = tzx * ny;
        let [rbx, rby, rbz] = laws.ball.lever(&n, &[tyx, tyy, tyz], &[tzx, tzz]);
        let k = laws.collision.matrix(&[rcx, rcy, rcz], &[rbx, rby, rbz]);
        let ([px, py, pz], _slip) = if USER {
            TangentialLaw::impulse_with::<V, FRICTION>(&k, &n, &u1, u1n, e, e_t, mu)
        } else {
            laws.tangential.impulse::<V, FRICTION>(&k, &n, &u1, u1n, e)
        };

        // Ball velocity in G, and spin (r_b × P)/I_b in G (components y and z).
        let rv = &self.r_v;
        let vgx = rv[0][0] * px + rv[0][1] * py + rv[0][2] * pz;
        let vgy = rv[1][0] * px + rv[1][1] * py + rv[1][2] * pz;
        let vgz = rv[2][0] * px + rv[2][1] * py + rv[2][2] * pz;
        let wfx = rby * pz - rbz * py;
        let wfy = rbz * px - rbx * pz;
        let wfz = rbx * py - rby * px;
        let rw = &self.r_w;
        let wgy = rw[0][0] * wfx + rw[0][1] * wfy + rw[0][2] * wfz;
        let wgz = rw[1][0] * wfx + rw[1][1] * wfy + rw[1][2] * wfz;

        let speed = (vgx * vgx + vgy * vgy + vgz * vgz).sqrt();
        let horizontal = (vgx * vgx + vgz * vgz).sqrt();
        let launch = atan2_v(vgy, horizontal);
        let azimuth = atan2_v(vgz, vgx);
        let nan = V::splat(f64::NAN);
        Out {
            speed: valid.select(speed, nan),
            launch: valid.select(launch, nan),
            azimuth: valid.select(azimuth, nan),
            backspin: valid.select(wgz, nan),
            sidespin: valid.select(-wgy, nan),
            valid,
        }
    }

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

    /// Run `job` with the kernel's constant switches (friction on, `cor_power` exponent set)
    /// turned into compile-time constants, so that the common case carries neither the slip
    /// branch nor a `pow` call.
    fn dispatch(&self, level: SimdLevel, job: &impl Job, out: RowOut<'_>) {
        if self.broken {
            fill_invalid(out);
            return;
        }
        let user = self.laws.user.has_contact();
        let friction = self.laws.tangential.mu.is_some() || self.laws.user.sets_mu();
        let power = self.laws.restitution.power_q != 0.0;
        match (friction, power, user) {
            (false, false, false) => self.on_level::<false, false, false>(level, job, out),
            (false, true, false) => self.on_level::<false, true, false>(level, job, out),
            (true, false, false) => self.on_level::<true, false, false>(level, job, out),
            (true, true, false) => self.on_level::<true, true, false>(level, job, out),
            // User-defined cor/et/mu: one instance per friction switch (the power law, if
            // any, is taken at run time there).
            (false, _, true) => self.on_level::<false, true, true>(level, job, out),
            (true, _, true) => self.on_level::<true, true, true>(level, job, out),
        }
    }

    #[inline(always)]
    fn on_level<const FRICTION: bool, const POWER: bool, const USER: bool>(
        &self,
        level: SimdLevel,
        job: &impl Job,
        out: RowOut<'_>,
    ) {
        match level {
            #[cfg(target_arch = "x86_64")]
            SimdLevel::Avx2 => unsafe { self.avx2::<FRICTION, POWER, USER>(job, out) },
            _ => job.run::<FRICTION, POWER, USER>(self, out),
        }
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn avx2<const FRICTION: bool, const POWER: bool, const USER: bool>(
        &self,
        job: &impl Job,
        out: RowOut<'_>,
    ) {
        job.run::<FRICTION, POWER, USER>(self, out)
    }
}

/// A row or a set of points, run by [`FaceMapKernel::dispatch`].
trait Job {
    fn run<const FRICTION: bool, const POWER: bool, const USER: bool>(
        &self,
        k: &FaceMapKernel,
        out: RowOut<'_>,
    );
}

/// One grid row: the heights are fixed in `row`.
struct RowJob<'a> {
    row: &'a Row,
    zs: &'a [f64],
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
}

/// Arbitrary points.
struct PointsJob<'a> {
    ys: &'a [f64],
    zs: &'a [f64],
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

/// Run `f` over full chunks of `(a, b)`, then over the tail padded to a full chunk (with the
/// last point repeated), so every point goes through the same code whatever its position.
#[inline(always)]
fn for_chunks(a: &[f64], b: &[f64], out: RowOut<'_>, f: &impl ChunkFn) {
    let n = b.len();
    let full = n - n % LANES;
    let mut i = 0;
    while i < full {
        let r = i..i + LANES;
        f.call(
            a[r.clone()].try_into().unwrap(),
            b[r.clone()].try_into().unwrap(),
            Chunk {
                speed: (&mut out.ball_speed_m_s[r.clone()]).try_into().unwrap(),
                launch: (&mut out.launch_angle_rad[r.clone()]).try_into().unwrap(),
                azimuth: (&mut out.azimuth_rad[r.clone()]).try_into().unwrap(),
                backspin: (&mut out.backspin_rad_s[r.clone()]).try_into().unwrap(),
                sidespin: (&mut out.sidespin_rad_s[r.clone()]).try_into().unwrap(),
                valid: (&mut out.valid[r]).try_into().unwrap(),
            },
        );
        i += LANES;
    }
    if full < n {
        let m = n - full;
        let mut pa = [a[n - 1]; LANES];
        let mut pb = [b[n - 1]; LANES];
        pa[..m].copy_from_slice(&a[full..]);
        pb[..m].copy_from_slice(&b[full..]);
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
        out.ball_speed_m_s[full..].copy_from_slice(&o[0][..m]);
        out.launch_angle_rad[full..].copy_from_slice(&o[1][..m]);
        out.azimuth_rad[full..].copy_from_slice(&o[2][..m]);
        out.backspin_rad_s[full..].copy_from_slice(&o[3][..m]);
        out.sidespin_rad_s[full..].copy_from_slice(&o[4][..m]);
        out.valid[full..].copy_from_slice(&v[..m]);
    }
}

fn fill_invalid(out: RowOut<'_>) {
    out.ball_speed_m_s.fill(f64::NAN);
    out.launch_angle_rad.fill(f64::NAN);
    out.azimuth_rad.fill(f64::NAN);
    out.backspin_rad_s.fill(f64::NAN);
    out.sidespin_rad_s.fill(f64::NAN);
    out.valid.fill(false);
}

/// Which code path the kernel runs on this machine.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SimdLevel {
    /// Portable code (baseline x86-64 SSE2, or any other architecture).
    Portable,
    /// AVX2 + FMA (x86-64), detected at run time. FMA is enabled for the compiler but never
    /// used to contract operations: results are identical to the portable path.
    Avx2,
}

/// The code path [`FaceMapKernel`] uses on this machine (detected once, cached).
pub fn simd_level() -> SimdLevel {
    #[cfg(target_arch = "x86_64")]
    {
        if std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma") {
            return SimdLevel::Avx2;
        }
    }
    SimdLevel::Portable
}

/// Face map over the grid `ys_m × zs_m` (row-major: row `i` is `ys_m[i]`), rows in parallel
/// with rayon. Deterministic: the result does not depend on the number of threads.
pub fn face_map(
    model: &ImpactModel,
    delivery: &Delivery,
    ys_m: &[f64],
    zs_m: &[f64],
) -> LaunchGrid {
    let mut out = LaunchGrid::with_len(ys_m.len() * zs_m.len());
    face_map_into(model, delivery, ys_m, zs_m, &mut out);
    out
}

/// Same as [`face_map`], into a caller-provided grid, for repeated sweeps. `out` is resized to
/// `ys_m.len() · zs_m.len()` points if needed (no allocation when it already has that size).
pub fn face_map_into(
    model: &ImpactModel,
    delivery: &Delivery,
    ys_m: &[f64],
    zs_m: &[f64],
    out: &mut LaunchGrid,
) {
    out.resize(ys_m.len() * zs_m.len());
    FaceMapKernel::new(model, delivery).par_eval_grid(ys_m, zs_m, out);
}
