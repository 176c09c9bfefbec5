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
/// And the contact edge at the last point asked for
/// ([`edge`](Self::edge)).
#[derive(Clone, Debug)]
pub(super) struct LimitCache {
    keys: [Cell<u64>; 2],
    limits: [[Cell<f64>; THRESHOLDS]; 2],
    edge: Cell<(u64, u64, f64)>,
    /// The last contact solved at `N` by the equation of motion: a step's
    /// last stage is at its end.
    solved: Cell<(u64, u64, f64)>,
}

impl Default for LimitCache {
    fn default() -> LimitCache {
        LimitCache {
            keys: std::array::from_fn(|_| Cell::new(f64::NAN.to_bits())),
            limits: std::array::from_fn(|_| std::array::from_fn(|_| Cell::new(f64::NAN))),
            edge: Cell::new((f64::NAN.to_bits(), 0, f64::NAN)),
            solved: Cell::new((f64::NAN.to_bits(), 0, f64::NAN)),
        }
    }
}

impl LimitCache {
    /// Notes the edge `a` (m) of a contact solved at `(phi, n)`.
    #[inline]
    pub(super) fn note_solved(&self, phi: f64, n: f64, a: f64) {
        self.solved.set((phi.to_bits(), n.to_bits(), a));
    }

    /// The contact edge `a` (m) at `(phi, n)`: the last one asked for or
    /// solved at `phi` under `n` to 1e-12, else from `find` (the contact
    /// solved there); kept for the next call: a step's end is the next
    /// step's start, across calls too, where the next call's interpolant
    /// of `av` may put `N` an ulp apart. Such an edge moves by some 1e-12
    /// of itself, and a solved one differs in its last bits with its warm
    /// start; edges are only read where they are farther than `1e-8 D`
    /// from a threshold's point ([`Interface::threshold_side`]), so neither
    /// changes a result.
    pub(super) fn edge(&self, phi: f64, n: f64, find: impl FnOnce() -> f64) -> f64 {
        let a = [&self.edge, &self.solved]
            .iter()
            .map(|c| c.get())
            .find(|&(p, q, _)| p == phi.to_bits() && (f64::from_bits(q) - n).abs() <= 1e-12 * n)
            .map_or_else(find, |(_, _, a)| a);
        self.edge.set((phi.to_bits(), n.to_bits(), a));
        a
    }

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
    /// cannot ([`CONTACT_CHAIN`]) are not evaluated. `a0`, `a1`: the edge
    /// `a` (m) of the contact solved at each end (NaN if none): where it
    /// shows the side of a threshold's point at both ends
    /// ([`Interface::threshold_side`]) and the sides agree, the bed
    /// resultants are not computed; the margins' signs are those sides, so
    /// the answer is the one of the margins. A margin within `1e-10` of
    /// zero at the start is the kink the step starts on, not a crossing.
    pub(crate) fn thresholds_crossed(
        &self,
        (phi0, n0, a0): (f64, f64, f64),
        (phi1, n1, a1): (f64, f64, f64),
    ) -> impl Iterator<Item = (usize, f64, f64)> + '_ {
        let it = &self.model.interface;
        let edges = [(phi0, n0, a0), (phi1, n1, a1)]
            .iter()
            .all(|&(phi, n, a)| phi > 0.0 && n > 0.0 && a.is_finite());
        // the side at both ends where the edges show it and agree
        let mut known = [None; THRESHOLDS];
        if edges {
            for (k, t) in known.iter_mut().zip(self.kinks.thresholds) {
                let sides = t.map(|t| {
                    (
                        it.threshold_side(phi0, a0, t),
                        it.threshold_side(phi1, a1, t),
                    )
                });
                if let Some((Some(s0), Some(s1))) = sides {
                    *k = (s0 == s1).then_some(s0);
                }
            }
        }
        let mut found = [None; THRESHOLDS];
        for (chain, past) in [(CONTACT_CHAIN, true), (PLASTIC_CHAIN, false)] {
            for i in chain {
                if self.kinks.thresholds[i].is_none() {
                    break;
                }
                let sides = match known[i] {
                    Some(s) => (s, s),
                    None => {
                        let m0 = self.threshold_margin(i, phi0, n0, true);
                        let m1 = self.threshold_margin(i, phi1, n1, true);
                        if m0.abs() > 1e-10 && (m0 > 0.0) != (m1 > 0.0) {
                            found[i] = Some((i, m0, m1));
                        }
                        (m0 > 0.0, m1 > 0.0)
                    }
                };
                // past (short of) this point at both ends: past (short
                // of) the later ones too
                if sides == (past, past) {
                    break;
                }
            }
        }
        found.into_iter().flatten()
    }
}

#[cfg(test)]
mod tests {
    use super::super::eom::Eom;
    use super::*;
    use crate::dynamics::{GroundInput, VerticalInput};
    use crate::model::{LawKind, MassKind, ShapeKind};
    use crate::Params;

    /// Crushing beds under a stone ring (the width's breaks at the inner
    /// circle) and a box section (at the flanges).
    fn bodies() -> [Params; 2] {
        let crushing = Params {
            interface: LawKind::ElastoPlastic,
            kn: 1e8,
            fm: 1.5e6,
            ..Params::default()
        };
        let ring = Params {
            shape: ShapeKind::HollowCircle,
            ro: 1.0,
            ri: 0.6,
            mass_model: MassKind::Lumped,
            w: 2e5,
            hg: 4.0,
            ic: 1.16e5,
            ..crushing
        };
        let hollow_box = Params {
            shape: ShapeKind::HollowRectangle,
            t: 0.12,
            ..crushing
        };
        [ring, hollow_box]
    }

    /// The points `(phi, N)` of a grid: 40 rotations below `thetaOv`, `N`
    /// from 0.3 W to 1.7 W.
    fn grid(sim: &Simulator) -> Vec<(f64, f64)> {
        let (ov, w) = (sim.model.theta_ov, sim.model.body.weight);
        let mut points = Vec::new();
        for j in 1..=40 {
            for q in 0..=28 {
                points.push((ov * j as f64 / 41.0, w * (0.3 + 0.05 * q as f64)));
            }
        }
        points
    }

    /// Where the contact's edge shows a threshold's side
    /// (`Interface::threshold_side`), it is the sign of the margin from the
    /// explicit bed resultant; the edge the step loop reads
    /// (`Eom::contact_edge`: the table at the weight where the toe has not
    /// crushed) is the solver's at `(phi, N)` to 1e-10 D.
    #[test]
    fn edge_sides_are_the_margins_signs() {
        for p in bodies() {
            let sim = Simulator::new(p.build().unwrap(), 1e-9);
            let it = &sim.model.interface;
            let eom =
                Eom::with_vertical(&sim, 0.0, GroundInput::default(), VerticalInput::default());
            let (mut shown, mut total) = (0, 0);
            for (phi, n) in grid(&sim) {
                let a = eom.contact_edge(phi, n, f64::NAN);
                let solved = sim.model.contact_loaded(phi, n).0.a;
                assert!(
                    (a - solved).abs() <= 1e-10 * it.depth(),
                    "{p:?}: phi {phi}, N {n}: edge {a}, solved {solved}"
                );
                for t in it.moving_thresholds().into_iter().flatten() {
                    total += 1;
                    let margin = Interface::threshold_margin(it.threshold_resultant(phi, t), n);
                    if let Some(past) = it.threshold_side(phi, a, t) {
                        shown += 1;
                        assert_eq!(
                            past,
                            margin > 0.0,
                            "phi {phi}, N {n}, {t:?}: edge {a}, margin {margin}"
                        );
                    }
                }
            }
            // measured: every side shown on this grid (6960 of 6960 on each body)
            assert!(shown * 100 >= 95 * total, "{shown} of {total} sides shown");
        }
    }

    /// The thresholds crossed between two points, found with the contacts'
    /// edges, are those found from the bed resultants alone, with the same
    /// margins bit for bit: over pairs of grid points a step apart in
    /// rotation and in `N`, and far apart.
    #[test]
    fn crossings_from_edges_are_those_of_the_margins() {
        for p in bodies() {
            let sim = Simulator::new(p.build().unwrap(), 1e-9);
            let eom =
                Eom::with_vertical(&sim, 0.0, GroundInput::default(), VerticalInput::default());
            let points = grid(&sim);
            let (mut crossings, mut breaks) = (0, 0);
            for (k, &(phi0, n0)) in points.iter().enumerate() {
                for &(phi1, n1) in [1, 29, 30, 31, 600]
                    .iter()
                    .filter_map(|s| points.get(k + s))
                {
                    let (a0, a1) = (
                        eom.contact_edge(phi0, n0, f64::NAN),
                        eom.contact_edge(phi1, n1, f64::NAN),
                    );
                    let bits = |v: Vec<(usize, f64, f64)>| -> Vec<(usize, u64, u64)> {
                        v.into_iter()
                            .map(|(i, m0, m1)| (i, m0.to_bits(), m1.to_bits()))
                            .collect()
                    };
                    let with = bits(
                        sim.thresholds_crossed((phi0, n0, a0), (phi1, n1, a1))
                            .collect(),
                    );
                    let without = bits(
                        sim.thresholds_crossed((phi0, n0, f64::NAN), (phi1, n1, f64::NAN))
                            .collect(),
                    );
                    assert_eq!(with, without, "({phi0}, {n0}) to ({phi1}, {n1})");
                    crossings += with.len();
                    breaks += with.iter().filter(|c| c.0 >= 2).count();
                }
            }
            // measured: 691 crossings on the ring (236 at its breaks), 216 on
            // the box (all at its flanges)
            assert!(
                crossings > 100 && breaks > 100,
                "{crossings} crossings, {breaks} at breaks"
            );
        }
    }
}
