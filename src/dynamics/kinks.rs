//! Kinks of `af` (docs/model.md §2): rotations where the right-hand side of
//! the equation of motion is continuous but not smooth, and where the step
//! loop cuts its steps.

use crate::interface::{solve_increasing, Law};
use crate::model::Model;
use crate::shape::Shape;

use super::dense::{first_event, Hermite, Hit};

/// Kink levels of `|theta|`, at most a few.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Kinks {
    levels: [f64; 8],
    n: usize,
}

impl Kinks {
    /// Rotations where the right-hand side has a kink (flexible laws), below
    /// `thetaOv`: there `af'` (hence `I'`, which the `shiftingPivot` term
    /// multiplies by `omega²`) is continuous but its derivative jumps, and a
    /// step across would see a low-order error and be rejected several times,
    /// so steps are cut there. They are the regime thresholds `thetaJo` and
    /// `thetaC`, and the rotations where the contact edge `a` or the plastic
    /// edge `xp = a - fm / (kn phi)` passes a corner of the width function:
    /// the flanges of a hollow rectangle (`w` jumps), the inner circle of a
    /// hollow circle (`w'` is infinite). Found by bisection on the contact
    /// solve (`a` decreases with `phi` beyond `thetaJo`, `xp` increases beyond
    /// `thetaC`).
    pub(super) fn of(model: &Model) -> Kinks {
        let mut k = Kinks::default();
        let (kn, fm) = match model.interface.law() {
            Law::Rigid => return k,
            Law::Elastic { kn } => (kn, f64::INFINITY),
            Law::ElastoPlastic { kn, fm } => (kn, fm),
        };
        let ov = model.theta_ov;
        let mut push = |l: f64| {
            if l > 0.0 && l < ov && k.n < k.levels.len() {
                k.levels[k.n] = l;
                k.n += 1;
            }
        };
        let (jo, c) = (model.interface.theta_jo(), model.interface.theta_c());
        push(jo);
        push(c);
        let corners: &[f64] = match *model.interface.shape() {
            Shape::HollowRectangle { b, t, .. } => &[t, b - t],
            Shape::HollowCircle { ro, ri } => &[ro - ri, ro + ri],
            _ => &[],
        };
        let a = |phi: f64| model.interface.contact(phi).a;
        let xp = |phi: f64| a(phi) - fm / (kn * phi);
        for &x in corners {
            // a(phi) = x: a from D at thetaJo down
            if jo < ov && a(ov) < x {
                push(solve_increasing(|p| x - a(p), jo, ov));
            }
            // xp(phi) = x: xp from 0 at thetaC up
            if c < ov && xp(ov) > x {
                push(solve_increasing(|p| xp(p) - x, c, ov));
            }
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
