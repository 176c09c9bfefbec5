//! Kinks of `af` (docs/model.md §2): rotations where the right-hand side of
//! the equation of motion is continuous but not smooth, and where the step
//! loop cuts its steps.

use crate::interface::{solve_increasing, Law, Threshold, THRESHOLDS};
use crate::model::Model;
use crate::shape::Shape;

use super::dense::{first_event, Hermite, Hit};

/// Kink levels of `|theta|`, at most a few.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Kinks {
    levels: [f64; THRESHOLDS],
    n: usize,
    /// The interface's moving thresholds (docs/model.md §6.4), in their
    /// fixed order, and the level of each at the weight below `thetaOv`.
    pub thresholds: [Option<Threshold>; THRESHOLDS],
    pub at_weight: [Option<f64>; THRESHOLDS],
    /// Which side of its point each threshold's edge is on is read from
    /// the contact's edge where the bed resultant is dear: a circle's
    /// takes arcsines (some 1000 instructions for a ring), the contact's
    /// edge from the table some 300; a rectangle's is cheaper than either
    /// (docs/performance.md).
    pub sides_from_edge: bool,
}

impl Kinks {
    /// Rotations where the right-hand side has a kink (flexible laws), below
    /// `thetaOv`: there `af'` (hence `I'`, which the `shiftingPivot` term
    /// multiplies by `omega²`) is continuous but its derivative jumps, and a
    /// step across would see a low-order error and be rejected several times,
    /// so steps are cut there. They are the rotations at which the
    /// interface's thresholds are reached under the weight: `thetaJo`,
    /// `thetaC`, and where the contact edge `a` or the plastic edge
    /// `xp = a - fm / (kn phi)` passes a break of the width function (the
    /// flanges of a hollow rectangle, where `w` jumps; the inner circle of a
    /// hollow circle, where `w'` is infinite). Found by bisection on the
    /// contact solve (`a` decreases with `phi` beyond `thetaJo`, `xp`
    /// increases beyond `thetaC`).
    pub(super) fn of(model: &Model) -> Kinks {
        let it = &model.interface;
        let mut k = Kinks {
            thresholds: it.moving_thresholds(),
            sides_from_edge: matches!(
                it.shape(),
                Shape::SolidCircle { .. } | Shape::HollowCircle { .. }
            ),
            ..Kinks::default()
        };
        let (kn, fm) = match it.law() {
            Law::Rigid => return k,
            Law::Elastic { kn } => (kn, f64::INFINITY),
            Law::ElastoPlastic { kn, fm } => (kn, fm),
        };
        let ov = model.theta_ov;
        let (jo, c) = (it.theta_jo(), it.theta_c());
        let a = |phi: f64| it.contact(phi).a;
        let xp = |phi: f64| a(phi) - fm / (kn * phi);
        let level = |t: Threshold| match t {
            Threshold::Contact(x) if x == it.depth() => Some(jo),
            Threshold::Plastic(0.0) => Some(c),
            // a(phi) = x: a from D at thetaJo down
            Threshold::Contact(x) => {
                (jo < ov && a(ov) < x).then(|| solve_increasing(|p| x - a(p), jo, ov))
            }
            // xp(phi) = x: xp from 0 at thetaC up
            Threshold::Plastic(x) => {
                (c < ov && xp(ov) > x).then(|| solve_increasing(|p| xp(p) - x, c, ov))
            }
        };
        for (i, t) in k.thresholds.into_iter().enumerate() {
            let l = t.and_then(level).filter(|&l| l > 0.0 && l < ov);
            if let Some(l) = l {
                k.levels[k.n] = l;
                k.n += 1;
            }
            k.at_weight[i] = l;
        }
        k
    }

    pub(super) fn as_slice(&self) -> &[f64] {
        &self.levels[..self.n]
    }

    /// After a step of `hh` (interpolated by `herm`) was rejected: the step
    /// `h` to retry, shortened to end just past the first kink inside the
    /// step (the accepted step is then cut there), at least `min_step`.
    pub(super) fn retry_past(
        &self,
        herm: &Hermite,
        side: f64,
        theta_ov: f64,
        hh: f64,
        h: f64,
        min_step: f64,
    ) -> f64 {
        match first_event(herm, side, theta_ov, self.as_slice()) {
            Some((Hit::Kink(_), tau)) => h.min(1.01 * tau * hh).max(min_step),
            _ => h,
        }
    }
}
