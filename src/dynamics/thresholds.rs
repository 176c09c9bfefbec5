//! The moving thresholds under a vertical input (docs/model.md §6.4): the
//! zeros of `1 - Nbed(phi)/N`, where an edge of the stress profile reaches
//! a point of the base (joint opening, crushing onset, a break of the
//! width), with the bed resultants `Nbed` kept for the rotations a step
//! starts and ends at.

use std::cell::Cell;

use crate::interface::{Interface, Threshold, THRESHOLDS};

use super::Simulator;

/// The thresholds in the order the contact edges' limits fall (from the
/// heel, `x = D`, down to the first break of the width) and the plastic
/// edges' rise (from the toe, `x = 0`, up): indices into
/// [`Interface::moving_thresholds`]. Along a chain, an edge short of (or
/// past) one point at both ends of a step is short of (past) every later
/// one too (`Nbed` grows with `a`), so those are not evaluated.
const CONTACT_CHAIN: [usize; 3] = [0, 4, 2];
const PLASTIC_CHAIN: [usize; 3] = [1, 3, 5];

/// The thresholds' bed resultants at the last two rotations asked for
/// (their bits), each computed when first needed (NaN until then): a
/// step's end is the next step's start, across calls too. A cache of a
/// function of `phi` alone: what it holds changes no result.
#[derive(Clone, Debug)]
pub(super) struct LimitCache {
    keys: [Cell<u64>; 2],
    limits: [[Cell<f64>; THRESHOLDS]; 2],
}

impl Default for LimitCache {
    fn default() -> LimitCache {
        LimitCache {
            keys: std::array::from_fn(|_| Cell::new(f64::NAN.to_bits())),
            limits: std::array::from_fn(|_| std::array::from_fn(|_| Cell::new(f64::NAN))),
        }
    }
}

impl LimitCache {
    /// The entry of `phi`, made the newest (the older one dropped) if
    /// neither holds it.
    fn entry(&self, phi: f64) -> &[Cell<f64>; THRESHOLDS] {
        let key = phi.to_bits();
        if self.keys[0].get() == key {
            return &self.limits[0];
        }
        if self.keys[1].get() != key {
            self.keys[1].set(self.keys[0].get());
            for (old, new) in self.limits[1].iter().zip(&self.limits[0]) {
                old.set(new.get());
                new.set(f64::NAN);
            }
            self.keys[0].set(key);
            return &self.limits[0];
        }
        &self.limits[1]
    }
}

impl Simulator {
    /// The margin of the `i`-th moving threshold (in the order of
    /// [`Interface::moving_thresholds`]) at `phi` under the bed resultant
    /// `n` (N): `1 - Nbed/n`, positive while the edge is past its point;
    /// at `phi <= 0` 1 for a contact edge, -1 for a plastic one; 1 where
    /// the interface has no such threshold. `cached`: keep the bed
    /// resultant for the next call at the same `phi` (a step's ends).
    pub(crate) fn threshold_margin(&self, i: usize, phi: f64, n: f64, cached: bool) -> f64 {
        let Some(t) = self.kinks.thresholds[i] else {
            return 1.0;
        };
        if phi <= 0.0 {
            return match t {
                Threshold::Contact(_) => 1.0,
                Threshold::Plastic(_) => -1.0,
            };
        }
        let it = &self.model.interface;
        let limit = if cached {
            let slot = &self.threshold_limits.entry(phi)[i];
            if slot.get().is_nan() {
                slot.set(it.threshold_resultant(phi, t));
            }
            slot.get()
        } else {
            it.threshold_resultant(phi, t)
        };
        Interface::threshold_margin(limit, n)
    }

    /// Every threshold's margin at `phi` under `n` (Model Exchange's event
    /// indicators).
    pub(crate) fn threshold_margins(&self, phi: f64, n: f64) -> [f64; THRESHOLDS] {
        std::array::from_fn(|i| self.threshold_margin(i, phi, n, false))
    }

    /// The thresholds whose margin changes sign between `(phi0, n0)` and
    /// `(phi1, n1)`, a step's ends, with their margins there; those that
    /// cannot ([`CONTACT_CHAIN`]) are not evaluated. A margin within
    /// `1e-10` of zero at the start is the kink the step starts on, not a
    /// crossing.
    pub(crate) fn thresholds_crossed(
        &self,
        (phi0, n0): (f64, f64),
        (phi1, n1): (f64, f64),
    ) -> impl Iterator<Item = (usize, f64, f64)> + '_ {
        let mut found = [None; THRESHOLDS];
        for (chain, past) in [(CONTACT_CHAIN, true), (PLASTIC_CHAIN, false)] {
            for i in chain {
                if self.kinks.thresholds[i].is_none() {
                    break;
                }
                let m0 = self.threshold_margin(i, phi0, n0, true);
                let m1 = self.threshold_margin(i, phi1, n1, true);
                if m0.abs() > 1e-10 && (m0 > 0.0) != (m1 > 0.0) {
                    found[i] = Some((i, m0, m1));
                }
                // past (short of) this point at both ends: past (short
                // of) the later ones too
                if (m0 > 0.0) == past && (m1 > 0.0) == past {
                    break;
                }
            }
        }
        found.into_iter().flatten()
    }
}
