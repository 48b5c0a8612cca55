//! The summary metrics of one design: the impacts [`evaluate`] computes and how they reduce to
//! the metrics defined in [`super::metrics`] (names, units, [`Output`]s).

use crate::physics::{ImpactModel, LaunchComponent};
use crate::sweep::kernel::{FaceMapKernel, LaunchGrid};
use crate::units::{mm, mph};

use super::distribution::SwingGroup;
use super::metrics::{ls_slope, Metric, Output, Side};
use super::spec::Study;

/// Probe offsets `0, s, 2s, …` up to `L` (inclusive when `L` is a multiple of `s`), mm.
fn probe_offsets(study: &Study) -> Vec<f64> {
    let p = study.probe;
    let n = (p.half_width_mm / p.step_mm + 1e-9).floor() as usize;
    (0..=n).map(|i| i as f64 * p.step_mm).collect()
}

/// Number of impacts [`evaluate`] computes for one design.
pub fn impacts_per_design(study: &Study, groups: &[SwingGroup]) -> usize {
    let n = probe_offsets(study).len();
    // CoF, then the horizontal line (2n − 1 points) and the vertical line (2n − 1 points).
    1 + 2 * (2 * n - 1) + groups.iter().map(|g| g.weights.len()).sum::<usize>()
}

/// Why a metric of `model` could not be computed, in the user's terms: the first impact of the
/// summary probe lines or of the distribution that the scalar solve refuses, with its reason (a
/// user-defined effect and its expression, an impact off the face, a swing that does not reach
/// the ball), or a distribution swing slower than the impact model's floor. `None` when every
/// impact solves (the metric's arithmetic then overflowed).
pub fn culprit(model: &ImpactModel, study: &Study, groups: &[SwingGroup]) -> Option<String> {
    let offs = probe_offsets(study);
    let probes = offs
        .iter()
        .flat_map(|&o| [(0.0, o), (0.0, -o), (o, 0.0), (-o, 0.0)])
        .map(|(y, z)| (study.swing, y, z, "the summary probe lines"));
    let drawn = groups.iter().flat_map(|g| {
        g.ys_m
            .iter()
            .zip(&g.zs_m)
            .map(move |(y, z)| (g.swing, y * 1e3, z * 1e3, "the [distribution]"))
    });
    for (swing, y_mm, z_mm, source) in probes.chain(drawn) {
        let floor = crate::limits::CLUB_SPEED_MPH;
        if let Err(m) = floor.check(swing.club_speed_mph) {
            return Some(format!(
                "a swing of {source}: {m}; narrow the club speed's spread"
            ));
        }
        if let Err(e) = model.solve(&swing.delivery(y_mm, z_mm)) {
            return Some(format!(
                "the impact at y = {} mm, z = {} mm of {source}: {e}",
                crate::limits::fmt_value(y_mm),
                crate::limits::fmt_value(z_mm)
            ));
        }
    }
    None
}

/// All metrics of one model, in [`Metric::all`] order. `groups` is the study distribution's
/// impacts (empty without a distribution).
pub fn evaluate(model: &ImpactModel, study: &Study, groups: &[SwingGroup]) -> Vec<f64> {
    let probes = Probes::new(model, study);
    let moments = (!groups.is_empty()).then(|| Moments::new(model, groups));
    Metric::all(moments.is_some())
        .into_iter()
        .map(|metric| match (metric, &moments) {
            (Metric::Mean(o), Some(m)) => m.mean[o.index()],
            (Metric::Std(o), Some(m)) => m.std[o.index()],
            (Metric::Mean(_) | Metric::Std(_), None) => unreachable!("listed with a distribution"),
            _ => probes.value(metric),
        })
        .collect()
}

/// The impacts at the centre and along the two lines through it, for the metrics that are not
/// distribution moments.
struct Probes {
    /// Line coordinates from −L to L, mm.
    line: Vec<f64>,
    /// Launch at the centre (point 0), the horizontal line, then the vertical line.
    grid: LaunchGrid,
    club_speed_m_s: f64,
}

impl Probes {
    /// First point of the horizontal line (z = −L).
    const H0: usize = 1;

    fn new(model: &ImpactModel, study: &Study) -> Self {
        let offs = probe_offsets(study);
        let line: Vec<f64> = offs
            .iter()
            .rev()
            .map(|o| -o)
            .chain(offs.iter().skip(1).copied())
            .collect();
        let mut ys = vec![0.0];
        let mut zs = vec![0.0];
        for &c in &line {
            ys.push(0.0);
            zs.push(mm(c));
        }
        for &c in &line {
            ys.push(mm(c));
            zs.push(0.0);
        }
        let swing = study.swing;
        let kernel = FaceMapKernel::new(model, &swing.delivery(0.0, 0.0));
        let mut grid = LaunchGrid::with_len(ys.len());
        kernel.eval_points(&ys, &zs, grid.row_out(0, ys.len()));
        Self {
            line,
            grid,
            club_speed_m_s: mph(swing.club_speed_mph),
        }
    }

    /// First point of the vertical line (y = −L).
    fn v0(&self) -> usize {
        1 + self.line.len()
    }

    /// Output `o` at point `k` of the line starting at `start`.
    fn val(&self, o: Output, start: usize, k: usize) -> f64 {
        o.file_value(&self.grid, start + k, self.club_speed_m_s)
    }

    /// Least-squares slope of `o` against the line coordinate over points `range` of the line
    /// starting at `start`.
    fn slope(&self, o: Output, start: usize, range: std::ops::Range<usize>) -> f64 {
        let x: Vec<f64> = range.clone().map(|k| self.line[k]).collect();
        let v: Vec<f64> = range.map(|k| self.val(o, start, k)).collect();
        ls_slope(&x, &v)
    }

    /// A metric computed from the probes (not a distribution moment).
    fn value(&self, metric: Metric) -> f64 {
        let m = self.line.len();
        let centre = m / 2; // index of 0 within the line
        let speed = Output::Launch(LaunchComponent::BallSpeed);
        match metric {
            Metric::Centre(o) => o.file_value(&self.grid, 0, self.club_speed_m_s),
            Metric::SpeedLoss(side) => {
                let (start, range, sign) = match side {
                    Side::Toe => (Self::H0, centre..m, 1.0),
                    Side::Heel => (Self::H0, 0..centre + 1, -1.0),
                    Side::Crown => (self.v0(), centre..m, 1.0),
                    Side::Sole => (self.v0(), 0..centre + 1, -1.0),
                };
                -sign * self.slope(speed, start, range)
            }
            Metric::GearSidespin => {
                self.slope(Output::Launch(LaunchComponent::Sidespin), Self::H0, 0..m)
            }
            Metric::GearBackspin => {
                self.slope(Output::Launch(LaunchComponent::Backspin), self.v0(), 0..m)
            }
            Metric::Mean(_) | Metric::Std(_) => unreachable!("a distribution moment"),
        }
    }
}

/// Weighted mean and standard deviation of every output over the distribution.
struct Moments {
    mean: [f64; 6],
    std: [f64; 6],
}

impl Moments {
    fn new(model: &ImpactModel, groups: &[SwingGroup]) -> Self {
        let mut sum = [0.0; 6];
        let mut sum2 = [0.0; 6];
        let mut samples: Vec<([f64; 6], f64)> = Vec::new();
        for grp in groups {
            let k = FaceMapKernel::new(model, &grp.swing.delivery(0.0, 0.0));
            let mut lg = LaunchGrid::with_len(grp.ys_m.len());
            k.eval_points(&grp.ys_m, &grp.zs_m, lg.row_out(0, grp.ys_m.len()));
            let cs = mph(grp.swing.club_speed_mph);
            for (i, w) in grp.weights.iter().enumerate() {
                let v = Output::ALL.map(|o| o.file_value(&lg, i, cs));
                for j in 0..6 {
                    sum[j] += w * v[j];
                }
                samples.push((v, *w));
            }
        }
        for (v, w) in &samples {
            for j in 0..6 {
                sum2[j] += w * (v[j] - sum[j]).powi(2);
            }
        }
        Self {
            mean: sum,
            std: sum2.map(f64::sqrt),
        }
    }
}
