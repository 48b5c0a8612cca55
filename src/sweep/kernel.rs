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
//! portable fallback; AVX-512 machines run the AVX2 path: unlike the fits and the flight
//! integrator, the kernel still runs the portable lane type [`V`], vectorised by the compiler).
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
//! User-defined mass and geometry expressions are usually fixed by the delivery and folded in
//! here once. One that reads the impact location (`impact_y_mm`, `impact_z_mm`) differs from
//! point to point: such a kernel builds a kernel per point at its location (`kernel/located.rs`)
//! and evaluates it with the same vector code; kernels without one keep the precomputed path.
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

mod eval;
mod grid;
mod jobs;
mod located;

use super::fastmath::atan2_v;
pub use crate::lanes::{simd_level, SimdLevel};
use crate::lanes::{M, V, W};
use crate::physics::impact::cor_allowed;
use crate::physics::laws::{LawWithCor, LawWithUser, Laws};
use crate::physics::{Delivery, ImpactModel, ModelParams};
pub use eval::{face_map, face_map_into};
use grid::fill_invalid;
pub use grid::{LaunchGrid, RowOut};
use jobs::Job;

/// Points per chunk: the unit the vector code works on.
pub const LANES: usize = 8;

/// Fewest grid rows a rayon task takes (a row of a few hundred points is only a few µs).
const ROWS_PER_TASK: usize = 4;

/// Everything about one (model, delivery) pair that does not depend on the impact location,
/// precomputed once. Cheap to clone; `Send + Sync`.
#[derive(Debug, Clone, PartialEq)]
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
    /// The model and delivery, when a user-defined mass or geometry expression reads the impact
    /// location: each point then gets its own kernel ([`located`]).
    located: Option<std::sync::Arc<located::Located>>,
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
    /// `s = sqrt(r² − y²)`, m.
    s: V,
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

/// Where and how fast the club meets the ball at one vector of points ([`FaceMapKernel::approach`]).
#[derive(Debug, Clone, Copy)]
struct Approach {
    /// `X = sqrt(ρ² − z²)`, m.
    x: V,
    /// Unit face normal.
    n: [V; 3],
    /// Contact point relative to the clubhead CoM, m.
    r_c: [V; 3],
    /// Contact-point velocity of the club, m/s.
    u1: [V; 3],
    /// Normal approach speed `u1·n`, m/s.
    u1n: V,
    /// On the face and approaching.
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
    /// `delivery`'s impact location is ignored. When a user-defined mass or geometry expression
    /// reads the impact location, that part depends on the point after all: the kernel then
    /// keeps the model and builds a kernel per point ([`located`]); otherwise (the library's
    /// effects, and every other user-defined expression) it is computed once here.
    pub fn new(model: &ImpactModel, delivery: &Delivery) -> Self {
        let mut k = Self::at_location(model, delivery);
        if model.params().user.pre_solve_reads_location() {
            k.located = Some(located::Located::new(model, delivery));
        }
        k
    }

    /// The kernel of `delivery` on `model` with the user-defined mass and geometry evaluated at
    /// `delivery`'s impact location.
    fn at_location(model: &ImpactModel, delivery: &Delivery) -> Self {
        // Every field of the parameters is named here, so that a new one stops the build until
        // the kernel handles it. Most reach the kernel through the model's laws, the face or
        // the face orientation; the rest are read below.
        let ModelParams {
            club_mass_kg: _,                 // in laws.collision
            club_com_m,                      // r_c below
            club_inertia_kgm2: _,            // in laws.collision
            cor: _,                          // in laws.restitution
            bulge_m: _,                      // in model.face()
            roll_m: _,                       // in model.face()
            ball_mass_kg,                    // r_v below; in laws.collision
            ball_radius_m: _,                // in laws.ball
            ball_inertia_kgm2,               // r_w below; in laws.collision
            ball_offset_y_m: _,              // in laws.ball
            ball_offset_z_m: _,              // in laws.ball
            tangential_restitution: _,       // in laws.tangential
            friction_mu: _,                  // in laws.tangential
            cor_speed_k_s_per_m: _,          // in laws.restitution
            cor_power_q: _,                  // in laws.restitution
            cor_radial_c_per_m2: _,          // in laws.restitution
            cor_radial_moment_per_m: _,      // in laws.restitution
            cor_radial_offset: _,            // in laws.restitution
            loft_bias_rad: _,                // in model.face_orientation
            face_bias_rad: _,                // in model.face_orientation
            hosel_m: _,                      // composed into mass, CoM and inertia by the effects
            contact_time_s: _,               // in laws.contact
            tangential_restitution_slope: _, // in laws.tangential
            gear_restitution: _,             // in laws.tangential
            user,                            // mass and geometry below; cor, et, mu in laws.user
        } = model.params();
        // User-defined mass and geometry at the delivery's location (`new` handles the case
        // where they depend on it).
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
            located: None,
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
            s,
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
        let a = self.approach(row, z);
        let (e, e_t, mu, valid) = self.contact_laws::<POWER, USER>(row, z, &a);
        let (p, w_f) = self.impulse::<FRICTION, USER>(row, z, &a, [e, e_t, mu]);
        self.launch_out(&p, &w_f, valid)
    }

    /// Contact point, normal, lever arm and approach velocity of impacts at `z` on `row`, and
    /// whether they are physical (on the face, club approaching the ball).
    #[inline(always)]
    fn approach(&self, row: &Row, z: V) -> Approach {
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
        // The club approaches the ball if u1·n exceeds the threshold `t`
        // (`limits::MIN_NORMAL_APPROACH_M_S`). The fast u1·n's error is ~1e-15 of the terms'
        // magnitude, so its decision is certain unless it is within 1e-13 of that magnitude
        // from `t`; there, redo n and u1·n with exactly the operations of the generic path, so
        // that validity agrees with `ImpactModel::solve` to the last bit. (Lanes decide by
        // their own values only.)
        let t = V::splat(crate::limits::MIN_NORMAL_APPROACH_M_S);
        let unsure = (u1n - t)
            .abs()
            .le((u1n_x.abs() + u1n_y.abs() + u1n_z.abs()) * 1e-13);
        let approaching = if unsure.any() {
            let s_n = row.s * row.inv_rho * (1.0 / self.roll_m);
            let (nx_exact, nz_exact) = (x * s_n, z * s_n);
            let u1n_exact = u1x * nx_exact + u1y * ny + u1z * nz_exact;
            unsure.select_mask(u1n_exact.gt(t), u1n.gt(t))
        } else {
            u1n.gt(t)
        };
        Approach {
            x,
            n: [nx, ny, nz],
            r_c: [rcx, rcy, rcz],
            u1: [u1x, u1y, u1z],
            u1n,
            valid: on_face & approaching,
        }
    }

    /// The restitution `e`, tangential restitution `e_t` and friction `mu` of the impacts (the
    /// library's laws, then the user-defined `cor`/`et`/`mu` terms when `USER`), and the
    /// validity with the lanes whose user-defined values are not allowed removed.
    #[inline(always)]
    fn contact_laws<const POWER: bool, const USER: bool>(
        &self,
        row: &Row,
        z: V,
        a: &Approach,
    ) -> (V, V, V, M) {
        let laws = &self.laws;
        let e = laws.restitution.cor_with::<V, POWER>(a.u1n, row.y, z);
        let e_t = V::splat(laws.tangential.e_t);
        let mu = V::splat(laws.tangential.mu.unwrap_or(f64::INFINITY));
        // A COR outside (0, 1] is no collision (`ImpactError::CorOutOfRange`): the cell is
        // invalid, as the scalar solve refuses it.
        if !USER {
            return (e, e_t, mu, a.valid & cor_allowed(e));
        }
        use crate::physics::user_terms::{NV, VAR_IMPACT_Y, VAR_IMPACT_Z, VAR_U1N, VAR_UT};
        let mut vars: [V; NV] = self.user_vars.map(V::splat);
        vars[VAR_IMPACT_Y as usize] = row.y * 1e3;
        vars[VAR_IMPACT_Z as usize] = z * 1e3;
        vars[VAR_U1N as usize] = a.u1n;
        vars[VAR_UT as usize] = crate::physics::laws::tangential_speed(&a.u1, &a.n, a.u1n);
        // Lanes whose user-defined values are not allowed are invalid (the scalar solve names
        // the effect for them), by the scalar solve's own per-term decision.
        let mut valid = a.valid;
        let (e, e_t, mu) = laws.user.contact(&mut vars, [e, e_t, mu], &mut valid);
        (e, e_t, mu, valid & cor_allowed(e))
    }

    /// The impulse on the ball and the ball's angular impulse `r_b × P`, in F, with the laws'
    /// values `[e, e_t, mu]` (`e_t` and `mu` are read only when `USER`).
    #[inline(always)]
    fn impulse<const FRICTION: bool, const USER: bool>(
        &self,
        row: &Row,
        z: V,
        a: &Approach,
        [e, e_t, mu]: [V; 3],
    ) -> ([V; 3], [V; 3]) {
        let laws = &self.laws;
        let n = a.n;
        let [nx, ny, nz] = n;
        // Impact frame tangents z_I = (−z, 0, X)/ρ, y_I = z_I × n, and the ball lever arm.
        let tzx = -z * row.inv_rho;
        let tzz = a.x * row.inv_rho;
        let tyx = -(tzz * ny);
        let tyy = tzz * nx - tzx * nz;
        let tyz = tzx * ny;
        let r_b = laws.ball.lever(&n, &[tyx, tyy, tyz], &[tzx, tzz]);
        let w_c = self.w_c.map(V::splat);
        let geometry = crate::physics::laws::ContactGeometry {
            normal: n,
            tangent_y: [tyx, tyy, tyz],
            tangent_z_xz: [tzx, tzz],
            r_c: a.r_c,
            r_b,
            u1: a.u1,
            u1n: a.u1n,
            w_c,
        };
        let (collision, radius) = (&laws.collision.lanes::<V>(), laws.ball.radius_m);
        // The scalar solve's laws: with user-defined terms the user's e_t (plus
        // tangential_compliance's rise) and mu (`ImpactModel::solve_contact_shot`).
        let fi = if USER {
            let law = LawWithUser::<V, FRICTION> {
                law: &laws.tangential,
                e,
                e_t,
                mu,
            };
            laws.contact.impact(law, collision, radius, &geometry)
        } else {
            let law = LawWithCor::<V, FRICTION> {
                law: &laws.tangential,
                e,
            };
            laws.contact.impact(law, collision, radius, &geometry)
        };
        let (p, w_f) = (fi.impulse, fi.ball_angular_impulse);
        (p, w_f)
    }

    /// Launch outputs from the ball's impulse `p` and angular impulse `w_f` (F); NaN where not
    /// `valid`.
    #[inline(always)]
    fn launch_out(&self, p: &[V; 3], w_f: &[V; 3], valid: M) -> Out {
        let [px, py, pz] = *p;
        let [wfx, wfy, wfz] = *w_f;
        // Ball velocity in G, and spin (r_b × P)/I_b in G (components y and z).
        let rv = &self.r_v;
        let vgx = rv[0][0] * px + rv[0][1] * py + rv[0][2] * pz;
        let vgy = rv[1][0] * px + rv[1][1] * py + rv[1][2] * pz;
        let vgz = rv[2][0] * px + rv[2][1] * py + rv[2][2] * pz;
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

    /// Run `job` with the kernel's constant switches (friction on, `cor_power` exponent set)
    /// turned into compile-time constants, so that the common case carries neither the slip
    /// branch nor a `pow` call.
    fn dispatch(&self, level: SimdLevel, job: &impl Job, out: RowOut<'_>) {
        if let Some(loc) = &self.located {
            loc.run(level, job, out);
            return;
        }
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
            // SAFETY: `level` is at most `simd_level()` (the callers' `or_supported`), so the
            // CPU has AVX2.
            SimdLevel::Avx2 | SimdLevel::Avx512 => unsafe {
                self.avx2::<FRICTION, POWER, USER>(job, out)
            },
            _ => self.portable::<FRICTION, POWER, USER>(job, out),
        }
    }

    /// The point code on the portable lanes, a function of its own for each instance (inlined
    /// into `dispatch`, twelve instances' lane loops would make one function whose loop passes
    /// take time quadratic in its size: see `flight::integrate::batches_portable`).
    #[inline(never)]
    fn portable<const FRICTION: bool, const POWER: bool, const USER: bool>(
        &self,
        job: &impl Job,
        out: RowOut<'_>,
    ) {
        job.run::<FRICTION, POWER, USER>(self, out)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn avx2<const FRICTION: bool, const POWER: bool, const USER: bool>(
        &self,
        job: &impl Job,
        out: RowOut<'_>,
    ) {
        job.run::<FRICTION, POWER, USER>(self, out)
    }
}
