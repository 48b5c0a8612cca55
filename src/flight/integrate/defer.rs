//! Contact searches put off and done together (`super`). A lane that may touch the ground in a
//! step leaves its group and waits, with its state at the start of that step, until a vector's
//! worth of such lanes, from any group, step and batch of the run, is re-integrated and
//! searched at once ([`contacts`]): one refinement for [`Lanes::N`] landings, where searching
//! each group's contacts in its step took one for every group and step in which any lane may
//! land (about three a group of eight drives).
//!
//! Every lane's operations are its own whatever the vector it is in, so a landing found here is
//! the same bits as one found in the step. A lane whose search finds no landing there (a dip
//! that does not reach the ground: it flies on) is flown again from its launch with each
//! contact searched in its step ([`Queue::redo`]), which is what it would have been.

use super::super::aero::CoefficientModel;
use super::land::contacts;
use super::step::St;
use super::{Consts, Lanewise};
use crate::flight::{Flight, FlightConfig, FlightError};
use crate::lanes::{Lanes, MAX_LANES};

#[cfg(test)]
thread_local! {
    /// Whether contact searches are put off on this thread (the tests compare both ways).
    pub(super) static DEFER: std::cell::Cell<bool> = const { std::cell::Cell::new(true) };
    /// Launches flown again on this thread after a put-off search found no landing.
    pub(super) static REDONE: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

/// Whether contact searches are put off ([`DEFER`] in the tests).
#[cfg(test)]
pub(super) fn deferring() -> bool {
    DEFER.with(std::cell::Cell::get)
}

/// Whether contact searches are put off: always.
#[cfg(not(test))]
pub(super) const fn deferring() -> bool {
    true
}

/// Lanes waiting for their contact search: the state at the start of the step, the unit spin
/// axis, the step's start time, the apex before the step and the launch (index), per slot.
pub(super) struct Queue {
    n: usize,
    p: [[f64; MAX_LANES]; 3],
    v: [[f64; MAX_LANES]; 3],
    w: [f64; MAX_LANES],
    axis: [[f64; MAX_LANES]; 3],
    t: [f64; MAX_LANES],
    top: [f64; MAX_LANES],
    at: [usize; MAX_LANES],
    /// Launches whose contact search found no landing, to be flown again with each contact
    /// searched in its step.
    pub(super) redo: Vec<usize>,
}

impl Queue {
    pub(super) fn new() -> Self {
        let zero = [0.0; MAX_LANES];
        Self {
            n: 0,
            p: [zero; 3],
            v: [zero; 3],
            w: zero,
            axis: [zero; 3],
            t: zero,
            top: zero,
            at: [0; MAX_LANES],
            redo: Vec::new(),
        }
    }

    /// Put off the contact search of lane `i` of the group at `from` (unit spin axis `axis`)
    /// in the step from time `t`, apex `top` before it, launch `at`; `true` when the queue is
    /// then full ([`Queue::search`] is due).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn push<L: Lanes>(
        &mut self,
        from: &Lanewise<L>,
        axis: [f64; 3],
        i: usize,
        t: f64,
        top: f64,
        at: usize,
    ) -> bool {
        let q = self.n;
        for j in 0..3 {
            self.p[j][q] = from.p[j][i];
            self.v[j][q] = from.v[j][i];
            self.axis[j][q] = axis[j];
        }
        self.w[q] = from.w[i];
        self.t[q] = t;
        self.top[q] = top;
        self.at[q] = at;
        self.n += 1;
        self.n == L::N
    }

    /// Search the waiting lanes' contacts together: a landing goes to `out` at its launch, a
    /// launch that does not land there to [`Queue::redo`]. The empty slots are padded with the
    /// first lane (searched for nothing).
    #[inline(always)]
    pub(super) fn search<L: Lanes, C: CoefficientModel>(
        &mut self,
        cfg: &FlightConfig,
        k: &Consts,
        model: &C,
        out: &mut [Result<Flight, FlightError>],
    ) {
        let n = self.n;
        if n == 0 {
            return;
        }
        let mut contact = [false; MAX_LANES];
        for q in 0..L::N {
            contact[q] = q < n;
            let from = if q < n { q } else { 0 };
            for j in 0..3 {
                self.p[j][q] = self.p[j][from];
                self.v[j][q] = self.v[j][from];
                self.axis[j][q] = self.axis[j][from];
            }
            self.w[q] = self.w[from];
        }
        let (p, v, a) = (&self.p, &self.v, &self.axis);
        let s = St {
            p: [L::load(&p[0]), L::load(&p[1]), L::load(&p[2])],
            v: [L::load(&v[0]), L::load(&v[1]), L::load(&v[2])],
            w: L::load(&self.w),
        };
        let axis = [L::load(&a[0]), L::load(&a[1]), L::load(&a[2])];
        let found = contacts::<L, C>(cfg, k, model, (&axis, &s), &contact, &mut self.top, &self.t);
        for q in 0..n {
            match found[q] {
                Some(f) => out[self.at[q]] = Ok(f),
                None => {
                    #[cfg(test)]
                    REDONE.with(|n| n.set(n.get() + 1));
                    self.redo.push(self.at[q]);
                }
            }
        }
        self.n = 0;
    }
}
