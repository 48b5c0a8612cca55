//! The batched residual evaluation: the shots of one group [`Lanes::N`] at a time on the lanes
//! (see the module docs of [`super`]), written once, generic over the lane type, and compiled
//! for each code path of [`SimdLevel`] (AVX-512, AVX2, portable), picked at run time.

use nalgebra::Vector3;

use super::{FitProblem, SHOTS_PER_TASK};
use crate::fit::data::SiteCache;
use crate::lanes::{each3, prefetch, LaneMask, Lanes, SimdLevel, MAX_LANES, V};
#[cfg(target_arch = "x86_64")]
use crate::lanes::{F64x4, F64x8};
use crate::physics::impact::ContactInputs;
use crate::physics::user_terms::{
    delivery_var, NV, VAR_DELIVERY, VAR_IMPACT_Y, VAR_IMPACT_Z, VAR_U1N,
};
use crate::physics::{DeliveryFrame, FaceGeometry, ImpactModel, Launch};
use crate::sweep::fastmath::{atan2_v, hypot_v};

/// Predicted launch (SI), ball velocity and spin (G) of [`Lanes::N`] shots, one lane a shot.
#[derive(Clone, Copy)]
pub(super) struct LanePrediction<L> {
    pub(super) launch: [L; 5],
    pub(super) ball_v: [L; 3],
    pub(super) ball_w: [L; 3],
}

impl<L: Lanes> LanePrediction<L> {
    /// All zero.
    #[inline(always)]
    pub(super) fn zero() -> Self {
        let z = L::splat(0.0);
        Self {
            launch: [z; 5],
            ball_v: [z; 3],
            ball_w: [z; 3],
        }
    }

    /// The lanes as arrays, to read shot by shot.
    #[inline(always)]
    pub(super) fn lanewise(&self) -> PredictionArrays<L> {
        let l = &self.launch;
        PredictionArrays {
            launch: [
                l[0].to_array(),
                l[1].to_array(),
                l[2].to_array(),
                l[3].to_array(),
                l[4].to_array(),
            ],
            ball_v: each3(|a| self.ball_v[a].to_array()),
            ball_w: each3(|a| self.ball_w[a].to_array()),
        }
    }
}

/// [`LanePrediction`] as arrays of lanes.
pub(super) struct PredictionArrays<L: Lanes> {
    launch: [L::Array; 5],
    ball_v: [L::Array; 3],
    ball_w: [L::Array; 3],
}

impl<L: Lanes> PredictionArrays<L> {
    /// The launch of lane `l`.
    #[inline(always)]
    pub(super) fn launch(&self, l: usize) -> Launch {
        Launch {
            ball_speed_m_s: self.launch[0][l],
            launch_angle_rad: self.launch[1][l],
            azimuth_rad: self.launch[2][l],
            backspin_rad_s: self.launch[3][l],
            sidespin_rad_s: self.launch[4][l],
        }
    }

    /// The ball's velocity (`spin: false`) or spin in `G` of lane `l`.
    #[inline(always)]
    pub(super) fn ball(&self, l: usize, spin: bool) -> Vector3<f64> {
        let v = if spin { &self.ball_w } else { &self.ball_v };
        Vector3::new(v[0][l], v[1][l], v[2][l])
    }
}

/// The delivery-frame inputs of [`Lanes::N`] shots for one model: clubhead velocities in `F` and
/// the rotation `R_GF`, one lane a shot.
#[derive(Clone, Copy)]
pub(super) struct FrameLanes<L> {
    v_c: [L; 3],
    w_c: [L; 3],
    r_gf: [[L; 3]; 3],
}

/// The face-frame inputs of one site (impact location or node) of [`Lanes::N`] shots, and its
/// weight.
struct SiteLanes<L> {
    point_m: [L; 3],
    normal: [L; 3],
    tangent_y: [L; 3],
    tangent_z_xz: [L; 2],
    y_m: L,
    z_m: L,
    weight: L,
}

/// The shots of `shots` (one lane vector's, at most [`Lanes::N`]) padded to [`Lanes::N`] with
/// copies of the last.
#[inline(always)]
pub(super) fn padded(shots: &[usize]) -> [usize; MAX_LANES] {
    let mut idx = [shots[shots.len() - 1]; MAX_LANES];
    idx[..shots.len()].copy_from_slice(shots);
    idx
}

impl FitProblem<'_> {
    /// Residual rows of the shots `start..` of `chunk` (those of the groups flagged in `groups`)
    /// evaluated [`Lanes::N`] shots at a time on the lanes ([`FitProblem::predict_lanes`]). Shots are
    /// taken group by group (a lane vector shares one model), the last vector of a group padded
    /// with copies of its last shot. Returns `false`, with `chunk` partly written, when a shot
    /// cannot be computed (off the face, not approaching, not finite) or a model has
    /// user-defined effects: the caller then evaluates the chunk one shot at a time.
    ///
    /// Runs the widest lane type the problem's [`SimdLevel`] allows (the same operations on
    /// every path, so the same bits: no fused multiply–add is formed).
    pub(super) fn residuals_on_lanes(
        &self,
        models: &[ImpactModel],
        cache: &SiteCache,
        start: usize,
        chunk: &mut [f64],
        groups: Option<&[bool]>,
    ) -> bool {
        match self.level {
            #[cfg(target_arch = "x86_64")]
            // SAFETY: `self.level` is at most `simd_level()`, which reports AVX-512F only when
            // the CPU (and operating system) have it.
            SimdLevel::Avx512 => unsafe { self.lanes_avx512(models, cache, start, chunk, groups) },
            #[cfg(target_arch = "x86_64")]
            // SAFETY: as above, AVX2.
            SimdLevel::Avx2 => unsafe { self.lanes_avx2(models, cache, start, chunk, groups) },
            _ => self.lanes_portable(models, cache, start, chunk, groups),
        }
    }

    /// [`FitProblem::lanes_impl`] on the portable lanes [`V`], a function of its own (inlined
    /// into `residuals_on_lanes`, its lane loops would share one function with the dispatch,
    /// and LLVM's loop passes take time quadratic in a function's size: see
    /// `flight::integrate::batches_portable`).
    #[inline(never)]
    fn lanes_portable(
        &self,
        models: &[ImpactModel],
        cache: &SiteCache,
        start: usize,
        chunk: &mut [f64],
        groups: Option<&[bool]>,
    ) -> bool {
        self.lanes_impl::<V>(models, cache, start, chunk, groups)
    }

    /// [`FitProblem::lanes_impl`] on [`F64x8`], compiled for AVX-512F (everything it calls in
    /// the inner loop is `#[inline(always)]`, so it is compiled with this instruction set).
    ///
    /// # Safety
    /// The CPU must have AVX-512F.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f")]
    unsafe fn lanes_avx512(
        &self,
        models: &[ImpactModel],
        cache: &SiteCache,
        start: usize,
        chunk: &mut [f64],
        groups: Option<&[bool]>,
    ) -> bool {
        self.lanes_impl::<F64x8>(models, cache, start, chunk, groups)
    }

    /// [`FitProblem::lanes_impl`] on [`F64x4`], compiled for AVX2.
    ///
    /// # Safety
    /// The CPU must have AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn lanes_avx2(
        &self,
        models: &[ImpactModel],
        cache: &SiteCache,
        start: usize,
        chunk: &mut [f64],
        groups: Option<&[bool]>,
    ) -> bool {
        self.lanes_impl::<F64x4>(models, cache, start, chunk, groups)
    }

    /// The body of [`FitProblem::residuals_on_lanes`].
    #[inline(always)]
    fn lanes_impl<L: Lanes>(
        &self,
        models: &[ImpactModel],
        cache: &SiteCache,
        start: usize,
        chunk: &mut [f64],
        groups: Option<&[bool]>,
    ) -> bool {
        // A user-defined loft or face-angle term turns the face shot by shot: such models are
        // evaluated per shot by the scalar solve (every other term runs on the lanes).
        if models.iter().any(|m| m.laws().user.sets_orientation()) {
            super::LANE_REFUSALS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            return false;
        }
        let rows = self.weighting.rows_per_shot();
        let group_of = &self.data.group_of;
        let mut order = [0usize; SHOTS_PER_TASK];
        let mut len = 0;
        for i in start..start + chunk.len() / rows {
            if groups.is_none_or(|g| g[group_of[i]]) {
                order[len] = i;
                len += 1;
            }
        }
        let order = &mut order[..len];
        // Keys are distinct, so the unstable sort (which does not allocate) keeps file order
        // within a group.
        order.sort_unstable_by_key(|&i| (group_of[i], i));
        for run in order.chunk_by(|&a, &b| group_of[a] == group_of[b]) {
            let model = &models[group_of[run[0]]];
            let n = L::N;
            self.prefetch_shots(cache, &run[..run.len().min(n)]);
            for (v, shots) in run.chunks(n).enumerate() {
                self.prefetch_shots(
                    cache,
                    run.get((v + 1) * n..).map_or(&[], |r| &r[..r.len().min(n)]),
                );
                let idx = padded(shots);
                let Some(p) = self.predict_lanes::<L>(model, cache, &idx[..n]) else {
                    return false;
                };
                let p = p.lanewise();
                for (l, &i) in shots.iter().enumerate() {
                    let r = &mut chunk[(i - start) * rows..][..rows];
                    self.write_rows(i, &p.launch(l), &p.ball(l, false), &p.ball(l, true), r);
                }
            }
        }
        true
    }

    /// Asks the CPU to bring the inputs of the shots `shots` (their location nodes, delivery
    /// frames and measurements) into its cache while the lanes solve the shots before them: on
    /// large data sets an evaluation streams them from memory (about 24 bytes a site and 160 a
    /// shot). A hint only: it changes no result.
    #[inline(always)]
    pub(super) fn prefetch_shots(&self, cache: &SiteCache, shots: &[usize]) {
        for &i in shots {
            if let Some(n) = &self.data.impact_nodes {
                prefetch(std::slice::from_ref(&n[i]));
            }
            prefetch(std::slice::from_ref(&cache.frames[i]));
            prefetch(std::slice::from_ref(&self.data.measured[i]));
        }
    }

    /// [`FitProblem::predict`] for the [`Lanes::N`] shots `idx` of one group (model `model`) at once:
    /// [`ImpactModel::solve_contact`] on the lanes (the scalar solve's own contact mechanics),
    /// rotated to `G`, the launch angles by [`atan2_v`] and [`hypot_v`], averaged over the
    /// impact-location nodes as [`crate::measurement::expected_over`] does. Agrees with the
    /// scalar path to rounding (a few ulp). `None` if any lane cannot be computed.
    #[inline(always)]
    fn predict_lanes<L: Lanes>(
        &self,
        model: &ImpactModel,
        cache: &SiteCache,
        idx: &[usize],
    ) -> Option<LanePrediction<L>> {
        let frame = self.frame_lanes::<L>(model, cache, idx);
        let face = (*model.face() != cache.face).then(|| model.face());
        // (An `if`, not `bool::then` with a closure: see `crate::lanes::each2`.)
        let vars = if model.laws().user.is_empty() {
            None
        } else {
            Some(self.user_vars::<L>(idx, model.laws().user.read_mask()))
        };
        let mut out = LanePrediction::zero();
        for k in 0..cache.sites_per_shot {
            let site = self.site_lanes(cache, idx, k, face)?;
            let (launch, v, w) = solve_lanes(model, &frame, &site, vars.as_ref())?;
            self.accumulate(&mut out, &site, launch, v, w);
        }
        Some(out)
    }

    /// [`FitProblem::predict_lanes`] for several models of one group at once (`outs[m]` for
    /// `models[m]`, the same bits as one at a time): each site's inputs are gathered once for all
    /// of them (the models must share one face: `face`, or the cache's when `None`). `frames` is
    /// scratch. `false` if any lane of any model cannot be computed.
    #[inline(always)]
    pub(super) fn predict_lanes_multi<L: Lanes>(
        &self,
        models: &[&ImpactModel],
        (cache, face): (&SiteCache, Option<&FaceGeometry>),
        idx: &[usize],
        frames: &mut Vec<FrameLanes<L>>,
        outs: &mut [LanePrediction<L>],
    ) -> bool {
        debug_assert!(models
            .iter()
            .all(|m| m.face() == face.unwrap_or(&cache.face)));
        frames.clear();
        // A delivery frame depends on the model only through its loft and face biases: models
        // that share them share the frame (the shifted models of a fit with a bias parameter
        // have at most three pairs between them, each made once instead of once a model).
        let biases = |m: &ImpactModel| {
            let p = m.params();
            (p.loft_bias_rad.to_bits(), p.face_bias_rad.to_bits())
        };
        for (k, m) in models.iter().enumerate() {
            let same = models[..k].iter().position(|o| biases(o) == biases(m));
            frames.push(match same {
                Some(o) => frames[o],
                None => self.frame_lanes(m, cache, idx),
            });
        }
        outs.fill(LanePrediction::zero());
        let mut reads = 0;
        let mut user = false;
        for m in models {
            user |= !m.laws().user.is_empty();
            reads |= m.laws().user.read_mask();
        }
        let vars = if user {
            Some(self.user_vars::<L>(idx, reads))
        } else {
            None
        };
        for k in 0..cache.sites_per_shot {
            let Some(site) = self.site_lanes(cache, idx, k, face) else {
                return false;
            };
            for ((model, frame), out) in models.iter().zip(frames.iter()).zip(outs.iter_mut()) {
                let Some((launch, v, w)) = solve_lanes(model, frame, &site, vars.as_ref()) else {
                    return false;
                };
                self.accumulate(out, &site, launch, v, w);
            }
        }
        true
    }

    /// The variables user-defined expressions read of the shots `idx`, one shot a lane
    /// ([`delivery_vars`]: the shot columns in file units and the shaft mass), those in `reads`
    /// (bit `i`: variable `i`) only; the others are 0.
    // Index loops, not iterators, in lane code (see `crate::lanes::each2`).
    #[allow(clippy::needless_range_loop)]
    #[inline(always)]
    fn user_vars<L: Lanes>(&self, idx: &[usize], reads: u64) -> [L; NV] {
        let d = &self.data.deliveries;
        let mut out = [L::splat(0.0); NV];
        for k in VAR_DELIVERY as usize..VAR_U1N as usize {
            if reads & (1 << k) == 0 {
                continue;
            }
            let mut lanes = [0.0; MAX_LANES];
            for l in 0..L::N {
                lanes[l] = delivery_var(&d[idx[l]], k);
            }
            out[k] = L::load(&lanes);
        }
        out
    }

    /// The delivery-frame lanes of the shots `idx` for `model` (cached when its biases are the
    /// cache's).
    #[inline(always)]
    fn frame_lanes<L: Lanes>(
        &self,
        model: &ImpactModel,
        cache: &SiteCache,
        idx: &[usize],
    ) -> FrameLanes<L> {
        if cache.frames_fit(model) {
            gather_frames(|l| &cache.frames[idx[l]])
        } else {
            // Only the lanes' own frames are made (a frame costs a face orientation), from the
            // cached trigonometry (only the angles of the biases that differ are taken again).
            let mut made = [cache.frames[idx[0]]; MAX_LANES];
            for (f, &i) in made.iter_mut().zip(&idx[..L::N]) {
                *f = model.delivery_frame_from(&self.data.deliveries[i], &cache.trig[i]);
            }
            gather_frames(|l| &made[l])
        }
    }

    /// The inputs of site `k` (impact location or node `k`) of the shots `idx`: the location,
    /// its weight, and the contact frame there on `face` (the cache's when `None`), computed
    /// on the lanes by [`FaceGeometry::contact_on`], the scalar [`FaceGeometry::contact`]'s
    /// own equations (the same bits; two square roots and seven divisions a vector are cheaper
    /// than reading a stored frame of 104 bytes a site from memory). `None` if a location is
    /// off the face.
    #[inline(always)]
    fn site_lanes<L: Lanes>(
        &self,
        cache: &SiteCache,
        idx: &[usize],
        k: usize,
        face: Option<&FaceGeometry>,
    ) -> Option<SiteLanes<L>> {
        let (y_m, z_m, weight) = match self.data.impact_nodes.as_ref() {
            Some(n) => (
                L::from_fn(|l| n[idx[l]][k].y_m),
                L::from_fn(|l| n[idx[l]][k].z_m),
                L::from_fn(|l| n[idx[l]][k].weight),
            ),
            None => {
                let d = &self.data.deliveries;
                (
                    L::from_fn(|l| d[idx[l]].impact_y_m),
                    L::from_fn(|l| d[idx[l]].impact_z_m),
                    L::splat(1.0),
                )
            }
        };
        let (on_face, cf) = face.unwrap_or(&cache.face).contact_on(y_m, z_m);
        if (!on_face).any() {
            return None;
        }
        Some(SiteLanes {
            point_m: cf.point_m,
            normal: cf.normal,
            tangent_y: cf.tangent_y,
            tangent_z_xz: [cf.tangent_z[0], cf.tangent_z[2]],
            y_m,
            z_m,
            weight,
        })
    }

    /// Adds one site's solution to `out`: its weighted share over the impact-location nodes, or
    /// the solution itself with locations taken as measured (one site a shot).
    #[inline(always)]
    fn accumulate<L: Lanes>(
        &self,
        out: &mut LanePrediction<L>,
        site: &SiteLanes<L>,
        launch: [L; 5],
        v: [L; 3],
        w: [L; 3],
    ) {
        if self.data.impact_nodes.is_none() {
            *out = LanePrediction {
                launch,
                ball_v: v,
                ball_w: w,
            };
        } else {
            let weight = site.weight;
            for (a, c) in out.launch.iter_mut().zip(launch) {
                *a = *a + weight * c;
            }
            for a in 0..3 {
                out.ball_v[a] = out.ball_v[a] + weight * v[a];
                out.ball_w[a] = out.ball_w[a] + weight * w[a];
            }
        }
    }
}

/// The delivery-frame lanes of the frames `frame(l)` of the lanes `l`.
#[inline(always)]
fn gather_frames<'a, L: Lanes>(frame: impl Fn(usize) -> &'a DeliveryFrame) -> FrameLanes<L> {
    let f = &frame;
    let v = |a| move |fr: &DeliveryFrame| fr.club_velocity_f_m_s[a];
    let w = |a| move |fr: &DeliveryFrame| fr.club_omega_f_rad_s[a];
    let r = |a, b| move |fr: &DeliveryFrame| fr.r_gf[(a, b)];
    FrameLanes {
        v_c: [gather(f, v(0)), gather(f, v(1)), gather(f, v(2))],
        w_c: [gather(f, w(0)), gather(f, w(1)), gather(f, w(2))],
        r_gf: [
            [gather(f, r(0, 0)), gather(f, r(0, 1)), gather(f, r(0, 2))],
            [gather(f, r(1, 0)), gather(f, r(1, 1)), gather(f, r(1, 2))],
            [gather(f, r(2, 0)), gather(f, r(2, 1)), gather(f, r(2, 2))],
        ],
    }
}

/// The lanes `field(frame(l))`. (Written out per field by the caller rather than through
/// `each3`, whose closure the compiler may keep out of line with the vector loads in it.)
#[inline(always)]
fn gather<'a, L: Lanes>(
    frame: &impl Fn(usize) -> &'a DeliveryFrame,
    field: impl Fn(&DeliveryFrame) -> f64,
) -> L {
    L::from_fn(|l| field(frame(l)))
}

/// One site of [`Lanes::N`] shots solved by `model`: the launch (SI) and the ball's velocity and spin in
/// `G`. `None` unless the club approaches the ball and the ball's and club's states after impact
/// are finite in every lane (the scalar solve's checks).
///
/// `vars`: the shots' variables for the model's user-defined effects ([`FitProblem::user_vars`];
/// `None` when it has none): their mass and geometry terms and their `cor`, `et` and `mu` are
/// evaluated on the lanes at the site's impact location, the scalar solve's own definitions
/// ([`ImpactModel::shot_consts_of`], [`ImpactModel::solve_contact_shot`]). `None` also when a
/// term's value is not allowed in any lane (the scalar solve then names it).
#[inline(always)]
fn solve_lanes<L: Lanes>(
    model: &ImpactModel,
    f: &FrameLanes<L>,
    site: &SiteLanes<L>,
    vars: Option<&[L; NV]>,
) -> Option<([L; 5], [L; 3], [L; 3])> {
    let x = ContactInputs {
        club_velocity_f_m_s: f.v_c,
        club_omega_f_rad_s: f.w_c,
        point_m: site.point_m,
        normal: site.normal,
        tangent_y: site.tangent_y,
        tangent_z_xz: site.tangent_z_xz,
        y_m: site.y_m,
        z_m: site.z_m,
    };
    // The shot path for every model: without user-defined effects its constants are the
    // model's and no term is evaluated (one instance of the contact mechanics, not two).
    let mut vars = match vars {
        Some(v) => {
            let mut vars = *v;
            vars[VAR_IMPACT_Y as usize] = site.y_m * 1e3;
            vars[VAR_IMPACT_Z as usize] = site.z_m * 1e3;
            vars
        }
        None => [L::splat(0.0); NV],
    };
    let mut valid = !L::no();
    let c = model.shot_consts_of(&mut vars, &mut valid);
    let s = model.solve_contact_shot(&x, &c, &mut vars, &mut valid);
    if !valid.all() {
        return None;
    }
    let inv_mc = L::splat(1.0) / c.club_mass_kg;

    let p = &s.impulse_n_s;
    // Only its finiteness is read (the scalar solve's check of the club's state after impact).
    let club_dv = [p[0] * inv_mc, p[1] * inv_mc, p[2] * inv_mc];
    let r_c = &s.contact_from_club_com_m;
    let moment = [
        r_c[1] * p[2] - r_c[2] * p[1],
        r_c[2] * p[0] - r_c[0] * p[2],
        r_c[0] * p[1] - r_c[1] * p[0],
    ];
    let min_approach = L::splat(crate::limits::MIN_NORMAL_APPROACH_M_S);
    if (!s.normal_approach_speed_m_s.gt(min_approach)).any()
        || (!s.cor_allowed).any()
        || !(finite(&s.ball_velocity_f_m_s)
            && finite(&s.ball_spin_f_rad_s)
            && finite(&club_dv)
            && finite(&moment))
    {
        return None;
    }
    let v = rotate(&f.r_gf, &s.ball_velocity_f_m_s);
    let w = rotate(&f.r_gf, &s.ball_spin_f_rad_s);
    let launch = [
        (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt(),
        atan2_v(v[1], hypot_v(v[0], v[2])),
        atan2_v(v[2], v[0]),
        w[2],
        -w[1],
    ];
    Some((launch, v, w))
}

/// Whether every lane of every component of `v` is finite.
#[inline(always)]
fn finite<L: Lanes>(v: &[L; 3]) -> bool {
    (v[0].finite() & v[1].finite() & v[2].finite()).all()
}

/// `r v` (a rotation of lane vectors).
#[inline(always)]
fn rotate<L: Lanes>(r: &[[L; 3]; 3], v: &[L; 3]) -> [L; 3] {
    each3(|a| r[a][0] * v[0] + r[a][1] * v[1] + r[a][2] * v[2])
}

#[cfg(test)]
mod tests;
