//! The cubic Hermite interpolant of one integration step (positions and velocities at both
//! ends, error `O(h⁴)` like the RK4 step itself): where the ball crosses the ground and how
//! high it rises within a step.

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
        let (t2, t3) = (t * t, t * t * t);
        (2.0 * t3 - 3.0 * t2 + 1.0) * self.y0
            + (t3 - 2.0 * t2 + t) * self.m0
            + (-2.0 * t3 + 3.0 * t2) * self.y1
            + (t3 - t2) * self.m1
    }
    /// Derivative with respect to θ.
    pub(crate) fn slope(&self, t: f64) -> f64 {
        let t2 = t * t;
        (6.0 * t2 - 6.0 * t) * self.y0
            + (3.0 * t2 - 4.0 * t + 1.0) * self.m0
            + (-6.0 * t2 + 6.0 * t) * self.y1
            + (3.0 * t2 - 2.0 * t) * self.m1
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
    pub(crate) fn first_down_to(&self, level: f64) -> Option<f64> {
        if self.stays_above(level) {
            return None;
        }
        self.search_down_to(level)
    }

    /// Whether the interpolant stays so far above `level` over [0, 1] that no evaluation of it
    /// comes out below `level`, so that [`Hermite::search_down_to`] finds no crossing (most
    /// substeps of a step re-integrated for a contact, cheaply). The cubic lies in the convex
    /// hull of its Bézier control points `y0, y0 + m0/3, y1 − m1/3, y1`, so it is at least
    /// their least; the margin, 1e-12 of the sum of the four coefficients' magnitudes, is
    /// hundreds of times the rounding error of these values and of [`Hermite::at`] (a few ulp
    /// of that sum). Any NaN or infinity makes the margin NaN or infinite: not above.
    fn stays_above(&self, level: f64) -> bool {
        let lowest = (self.y0.min(self.y1))
            .min(self.y0 + self.m0 / 3.0)
            .min(self.y1 - self.m1 / 3.0);
        let margin = 1e-12 * (self.y0.abs() + self.y1.abs() + self.m0.abs() + self.m1.abs());
        lowest - margin > level
    }

    /// [`Hermite::first_down_to`] without the shortcut of [`Hermite::stays_above`].
    fn search_down_to(&self, level: f64) -> Option<f64> {
        let lo = if self.y0 <= level && self.m0 > 0.0 {
            self.argmax().0
        } else {
            0.0
        };
        if self.at(lo) - level < 0.0 {
            return Some(lo);
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
        Some(self.root_between(level, lo, hi))
    }

    /// The crossing of `level` in `[lo, hi]` given `at(lo) ≥ level > at(hi)` and one crossing
    /// there: Newton kept inside a shrinking bracket.
    fn root_between(&self, level: f64, lo: f64, hi: f64) -> f64 {
        let (mut lo, mut hi) = (lo, hi);
        let (f_lo, f_hi) = (self.at(lo) - level, self.at(hi) - level);
        let mut t = if f_lo - f_hi > 0.0 {
            (lo + (hi - lo) * f_lo / (f_lo - f_hi)).clamp(lo, hi)
        } else {
            0.5 * (lo + hi)
        };
        for _ in 0..100 {
            let f = self.at(t) - level;
            if f == 0.0 {
                return t;
            }
            if f > 0.0 {
                lo = t;
            } else {
                hi = t;
            }
            if hi - lo < 1e-15 {
                break;
            }
            let d = self.slope(t);
            let tn = t - f / d;
            t = if d != 0.0 && tn > lo && tn < hi {
                tn
            } else {
                0.5 * (lo + hi)
            };
        }
        t
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
