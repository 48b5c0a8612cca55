//! The cubic Hermite interpolant of one integration step (positions and velocities at both
//! ends, error `O(h⁴)` like the RK4 step itself): where the ball crosses the ground and how
//! high it rises within a step.

use crate::lanes::{LaneMask, Lanes, Real, V};

/// Cubic Hermite interpolant on one step: values `y0, y1`, slopes (per unit θ) `m0, m1`.
#[derive(Clone, Copy)]
pub(crate) struct Hermite {
    pub(crate) y0: f64,
    pub(crate) y1: f64,
    pub(crate) m0: f64,
    pub(crate) m1: f64,
}

impl Hermite {
    pub(crate) fn new(y0: f64, y1: f64, v0: f64, v1: f64, h: f64) -> Self {
        Self {
            y0,
            y1,
            m0: h * v0,
            m1: h * v1,
        }
    }
    pub(crate) fn at(&self, t: f64) -> f64 {
        at_on(self.coefficients(), t)
    }
    /// Derivative with respect to θ.
    pub(crate) fn slope(&self, t: f64) -> f64 {
        slope_on(self.coefficients(), t)
    }
    /// `[y0, y1, m0, m1]`.
    pub(crate) fn coefficients(&self) -> [f64; 4] {
        [self.y0, self.y1, self.m0, self.m1]
    }
    /// The first time in [0, 1] the interpolant comes down to `level` (the ground), or `None`
    /// when it stays above it over the whole step. Ground contact is found on the
    /// interpolant, not at the step's ends, so a ball that dips below the ground and rises
    /// again within one step lands there whatever the step (a step-end test missed such a dip
    /// at a long step and found it at a short one).
    ///
    /// A step that starts on the ground while rising (the launch of a ball lying on the
    /// ground) touches `level` at θ = 0, the launch itself: the search then starts at the
    /// step's highest point. A step that starts on the ground while not rising lands at θ = 0.
    ///
    /// The integrator runs it in two halves: [`Hermite::crossing`], then [`Hermite::root`] or,
    /// for several landings at once, [`roots_between`].
    #[cfg(test)]
    pub(crate) fn first_down_to(&self, level: f64) -> Option<f64> {
        self.crossing(level).map(|c| self.root(level, c))
    }

    /// Whether the interpolant stays so far above `level` over [0, 1] that no evaluation of it
    /// comes out below `level`, so that the full search finds no crossing (most
    /// substeps of a step re-integrated for a contact, cheaply). The cubic lies in the convex
    /// hull of its Bézier control points `y0, y0 + m0/3, y1 − m1/3, y1`, so it is at least
    /// their least; the margin, 1e-12 of the sum of the four coefficients' magnitudes, is
    /// hundreds of times the rounding error of these values and of [`Hermite::at`] (a few ulp
    /// of that sum). Any NaN or infinity makes the margin NaN or infinite: not above.
    #[inline(always)]
    fn stays_above(&self, level: f64) -> bool {
        let lowest = (self.y0.min(self.y1))
            .min(self.y0 + self.m0 / 3.0)
            .min(self.y1 - self.m1 / 3.0);
        let margin = 1e-12 * (self.y0.abs() + self.y1.abs() + self.m0.abs() + self.m1.abs());
        lowest - margin > level
    }

    /// Where the search of [`Hermite::first_down_to`] for the crossing of `level` starts, or
    /// `None` when there is none. Inlined, with the shortcut ([`Hermite::stays_above`]), into
    /// the batched integrator, where a call spills its vector registers: most calls take it.
    #[inline(always)]
    pub(crate) fn crossing(&self, level: f64) -> Option<Crossing> {
        if self.stays_above(level) {
            return None;
        }
        self.bracket_down_to(level)
    }

    /// [`Hermite::crossing`] without the shortcut.
    #[inline(never)]
    fn bracket_down_to(&self, level: f64) -> Option<Crossing> {
        let lo = if self.y0 <= level && self.m0 > 0.0 {
            self.argmax().0
        } else {
            0.0
        };
        if self.at(lo) - level < 0.0 {
            return Some(Crossing::At(lo));
        }
        // The bracket's far end: the first local minimum after `lo` below the level, else the
        // step's end if it is below. Between `lo` and that point the interpolant rises at
        // most once and then falls, so it crosses the level exactly once.
        let below = |t: f64| self.at(t) - level < 0.0;
        let hi = self
            .critical_points()
            .into_iter()
            .flatten()
            .filter(|&t| t > lo && self.curvature(t) > 0.0)
            .find(|&t| below(t))
            .or_else(|| below(1.0).then_some(1.0))?;
        // Newton's start in the bracket: the secant's root.
        let (f_lo, f_hi) = (self.at(lo) - level, self.at(hi) - level);
        let t = if f_lo - f_hi > 0.0 {
            (lo + (hi - lo) * f_lo / (f_lo - f_hi)).clamp(lo, hi)
        } else {
            0.5 * (lo + hi)
        };
        Some(Crossing::Between { lo, hi, t })
    }

    /// [`Hermite::first_down_to`] without the shortcut of [`Hermite::stays_above`].
    #[cfg(test)]
    fn search_down_to(&self, level: f64) -> Option<f64> {
        self.bracket_down_to(level).map(|c| self.root(level, c))
    }

    /// The crossing of `level` from where [`Hermite::crossing`] left it ([`roots_between`] on
    /// one lane).
    pub(crate) fn root(&self, level: f64, c: Crossing) -> f64 {
        let Crossing::Between { lo, hi, t } = c else {
            return c.start();
        };
        let hm = self.coefficients().map(V::splat);
        let all = !<V as Real>::no();
        let (lo, hi, t) = (V::splat(lo), V::splat(hi), V::splat(t));
        roots_between::<V>(hm, level, (lo, hi), t, all).lane(0)
    }

    /// Second derivative with respect to θ.
    fn curvature(&self, t: f64) -> f64 {
        (12.0 * t - 6.0) * self.y0
            + (6.0 * t - 4.0) * self.m0
            + (6.0 - 12.0 * t) * self.y1
            + (6.0 * t - 2.0) * self.m1
    }

    /// The zeros of the slope in [0, 1], in increasing order.
    fn critical_points(&self) -> [Option<f64>; 2] {
        // slope(θ) = A θ² + B θ + C.
        let a = 6.0 * self.y0 + 3.0 * self.m0 - 6.0 * self.y1 + 3.0 * self.m1;
        let b = -6.0 * self.y0 - 4.0 * self.m0 + 6.0 * self.y1 - 2.0 * self.m1;
        let c = self.m0;
        let inside = |t: f64| (0.0..=1.0).contains(&t).then_some(t);
        let mut r = [None, None];
        if a.abs() < 1e-300 {
            if b != 0.0 {
                r[0] = inside(-c / b);
            }
        } else {
            let disc = b * b - 4.0 * a * c;
            if disc >= 0.0 {
                let q = -0.5 * (b + b.signum() * disc.sqrt());
                if q != 0.0 {
                    let (t1, t2) = (q / a, c / q);
                    r = [inside(t1.min(t2)), inside(t1.max(t2))];
                }
            }
        }
        if r[0].is_none() {
            r = [r[1], None];
        }
        r
    }

    /// Largest value over [0, `end`].
    pub(crate) fn max_until(&self, end: f64) -> f64 {
        let mut best = self.y0.max(self.at(end));
        for t in self.critical_points().into_iter().flatten() {
            if t <= end {
                best = best.max(self.at(t));
            }
        }
        best
    }

    /// Largest value over [0, 1].
    pub(crate) fn max(&self) -> f64 {
        self.argmax().1
    }
    /// Where on [0, 1] the interpolant is largest, and its value there.
    pub(crate) fn argmax(&self) -> (f64, f64) {
        let mut best = if self.y0 >= self.y1 {
            (0.0, self.y0)
        } else {
            (1.0, self.y1)
        };
        for t in self.critical_points().into_iter().flatten() {
            let y = self.at(t);
            if y > best.1 {
                best = (t, y);
            }
        }
        best
    }
}

/// Where the search for a crossing starts ([`Hermite::crossing`]).
#[derive(Clone, Copy, Debug)]
pub(crate) enum Crossing {
    /// The crossing is at this time (the start of the step or of its search).
    At(f64),
    /// The one crossing in `[lo, hi]` is searched from `t` ([`roots_between`]).
    Between { lo: f64, hi: f64, t: f64 },
}

impl Crossing {
    /// Where the search starts: the crossing itself for [`Crossing::At`].
    pub(crate) fn start(self) -> f64 {
        match self {
            Crossing::At(t) | Crossing::Between { t, .. } => t,
        }
    }
}

/// The interpolant with coefficients `[y0, y1, m0, m1]` at `t`, on numbers or lanes (the same
/// operations either way).
#[inline(always)]
fn at_on<R: Real>([y0, y1, m0, m1]: [R; 4], t: R) -> R {
    let (t2, t3) = (t * t, t * t * t);
    (t3 * 2.0 - t2 * 3.0 + 1.0) * y0
        + (t3 - t2 * 2.0 + t) * m0
        + (t3 * -2.0 + t2 * 3.0) * y1
        + (t3 - t2) * m1
}

/// The derivative of [`at_on`] with respect to θ.
#[inline(always)]
fn slope_on<R: Real>([y0, y1, m0, m1]: [R; 4], t: R) -> R {
    let t2 = t * t;
    (t2 * 6.0 - t * 6.0) * y0
        + (t2 * 3.0 - t * 4.0 + 1.0) * m0
        + (t2 * -6.0 + t * 6.0) * y1
        + (t2 * 3.0 - t * 2.0) * m1
}

/// The crossings of `level` by the interpolants `hm` (coefficients lane by lane, see
/// [`at_on`]) in their brackets `[lo, hi]` (`at(lo) ≥ level > at(hi)`, one crossing there),
/// searched from `t` in the lanes `active` (the others keep `t`): Newton kept inside a
/// shrinking bracket. Each lane runs the same operations as on its own, so several landings'
/// searches overlap at the cost of one.
#[inline(always)]
pub(crate) fn roots_between<L: Lanes>(
    hm: [L; 4],
    level: f64,
    (mut lo, mut hi): (L, L),
    mut t: L,
    mut active: L::Mask,
) -> L {
    let zero = L::splat(0.0);
    for _ in 0..100 {
        if !active.any() {
            break;
        }
        let f = at_on(hm, t) - level;
        // Found exactly.
        active = active & !f.eq(zero);
        let above = f.gt(zero);
        lo = L::select(active & above, t, lo);
        hi = L::select(active & !above, t, hi);
        active = active & !(hi - lo).lt(L::splat(1e-15));
        let d = slope_on(hm, t);
        let tn = t - f / d;
        let newton = !d.eq(zero) & tn.gt(lo) & tn.lt(hi);
        t = L::select(active, L::select(newton, tn, (lo + hi) * 0.5), t);
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hermite_root_and_max_on_a_parabola() {
        // y = 1 + 2θ − 3θ² on [0, 1] (dy/dθ = 2 − 6θ): root (1 + 2)/3 = 1, max at 1/3 = 4/3.
        let hm = Hermite {
            y0: 1.0,
            y1: 0.0 - 1e-9,
            m0: 2.0,
            m1: -4.0,
        };
        assert!((hm.max() - 4.0 / 3.0).abs() < 1e-8);
        assert!((hm.first_down_to(0.0).unwrap() - 1.0).abs() < 1e-6);
    }

    /// Where [`Hermite::stays_above`] takes the shortcut, the full search finds no crossing
    /// either; over a grid of cubics crossing, grazing and clearing the level (and NaN).
    #[test]
    fn the_shortcut_is_taken_only_where_the_search_finds_nothing() {
        let values = [
            -1.0,
            -1e-9,
            0.0,
            1e-13,
            1e-9,
            0.05,
            0.3,
            1.0,
            30.0,
            f64::NAN,
        ];
        let slopes = [-40.0, -3.0, -0.5, -1e-9, 0.0, 1e-9, 0.5, 3.0, 40.0];
        let mut taken = 0;
        for &y0 in &values {
            for &y1 in &values {
                for &m0 in &slopes {
                    for &m1 in &slopes {
                        let hm = Hermite { y0, y1, m0, m1 };
                        for level in [0.0, -0.01, 0.2] {
                            if hm.stays_above(level) {
                                taken += 1;
                                assert_eq!(hm.search_down_to(level), None, "{y0} {y1} {m0} {m1}");
                            }
                        }
                    }
                }
            }
        }
        assert!(taken > 1000, "{taken}");
    }

    /// A crossing searched among other lanes' ([`roots_between`]) is the one searched alone:
    /// four interpolants whose searches take different numbers of iterations, in every order.
    #[test]
    fn crossings_searched_together_are_the_ones_searched_alone() {
        let cubics = [
            Hermite::new(0.7, -0.3, -20.0, -21.0, 0.04375),
            Hermite::new(0.05, -0.9, -18.0, -19.5, 0.04375),
            Hermite::new(3.0 / 16.0, 3.0 / 16.0, -1.0, 1.0, 1.0),
            Hermite::new(0.3, -0.2, 1.0, -40.0, 0.04375),
        ];
        let alone: Vec<f64> = cubics
            .iter()
            .map(|c| c.first_down_to(0.0).unwrap())
            .collect();
        for shift in 0..4 {
            let at = |q: usize| cubics[(q + shift) % 4];
            let starts: Vec<Crossing> = (0..4).map(|q| at(q).crossing(0.0).unwrap()).collect();
            let lane = |f: &dyn Fn(usize) -> f64| V::from_fn(f);
            let hm = [
                lane(&|q| at(q).y0),
                lane(&|q| at(q).y1),
                lane(&|q| at(q).m0),
                lane(&|q| at(q).m1),
            ];
            let ends = |q: usize| match starts[q] {
                Crossing::Between { lo, hi, .. } => (lo, hi),
                Crossing::At(t) => (t, t),
            };
            let bracket = (lane(&|q| ends(q).0), lane(&|q| ends(q).1));
            let active = lane(&|q| f64::from(matches!(starts[q], Crossing::Between { .. })));
            let t = lane(&|q| starts[q].start());
            let together = roots_between::<V>(hm, 0.0, bracket, t, active.gt(V::splat(0.5)));
            for q in 0..4 {
                assert_eq!(together.lane(q).to_bits(), alone[(q + shift) % 4].to_bits());
            }
        }
    }

    /// A dip below the level inside the step is found although both ends are above it, and
    /// the first of two crossings is the one returned.
    #[test]
    fn first_down_to_finds_a_dip_within_the_step() {
        // y = (θ − ½)² − 1/16 = θ² − θ + 3/16: above 0 at both ends, zeros at ¼ and ¾.
        let hm = Hermite {
            y0: 3.0 / 16.0,
            y1: 3.0 / 16.0,
            m0: -1.0,
            m1: 1.0,
        };
        assert!((hm.first_down_to(0.0).unwrap() - 0.25).abs() < 1e-12);
        // Above the trough's level: no contact.
        assert_eq!(hm.first_down_to(-0.1), None);
        // Starting on the level going down: contact at once.
        let down = Hermite {
            y0: 0.0,
            y1: 0.5,
            m0: -0.2,
            m1: 2.0,
        };
        assert_eq!(down.first_down_to(0.0), Some(0.0));
        // Starting on the level going up (a launch from the ground): not a contact.
        let up = Hermite {
            y0: 0.0,
            y1: 0.5,
            m0: 1.0,
            m1: 0.1,
        };
        assert_eq!(up.first_down_to(0.0), None);
    }
}
