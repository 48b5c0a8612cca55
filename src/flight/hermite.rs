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
    /// The downward crossing in [0, 1] given `at(0) ≥ 0 > at(1)`: Newton kept inside a
    /// shrinking bracket. A step that starts on the ground while rising (the launch step of a
    /// flight shorter than one step) also has a root at θ = 0, the launch itself; the landing
    /// is then searched after the step's highest point.
    pub(crate) fn root(&self) -> f64 {
        let lo0 = if self.y0 <= 0.0 && self.m0 > 0.0 {
            self.argmax().0
        } else {
            0.0
        };
        let (mut lo, mut hi) = (lo0, 1.0);
        let y_lo = self.at(lo0);
        let mut t = if y_lo - self.y1 > 0.0 {
            (lo0 + (1.0 - lo0) * y_lo / (y_lo - self.y1)).clamp(lo0, 1.0)
        } else {
            0.5 * (lo0 + 1.0)
        };
        for _ in 0..100 {
            let f = self.at(t);
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
    /// Largest value over [0, 1].
    pub(crate) fn max(&self) -> f64 {
        self.argmax().1
    }
    /// Where on [0, 1] the interpolant is largest, and its value there.
    pub(crate) fn argmax(&self) -> (f64, f64) {
        // slope(θ) = A θ² + B θ + C.
        let a = 6.0 * self.y0 + 3.0 * self.m0 - 6.0 * self.y1 + 3.0 * self.m1;
        let b = -6.0 * self.y0 - 4.0 * self.m0 + 6.0 * self.y1 - 2.0 * self.m1;
        let c = self.m0;
        let mut best = if self.y0 >= self.y1 {
            (0.0, self.y0)
        } else {
            (1.0, self.y1)
        };
        let mut try_t = |t: f64| {
            if (0.0..=1.0).contains(&t) {
                let y = self.at(t);
                if y > best.1 {
                    best = (t, y);
                }
            }
        };
        if a.abs() < 1e-300 {
            if b != 0.0 {
                try_t(-c / b);
            }
        } else {
            let disc = b * b - 4.0 * a * c;
            if disc >= 0.0 {
                let q = -0.5 * (b + b.signum() * disc.sqrt());
                if q != 0.0 {
                    try_t(q / a);
                    try_t(c / q);
                }
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
        assert!((hm.root() - 1.0).abs() < 1e-6);
    }
}
