//! The step-size controller: the starting step, the factors after an
//! accepted or a rejected step, the smallest step, and the limit on steps
//! toward `theta = 0` in partial contact (docs/dynamics.md §3).

use super::erk::{Start, Tol};

/// Largest `h |omega / theta|` of a step toward `theta = 0` in partial
/// contact (flexible laws).
const R_MAX: f64 = 0.5;

/// Hairer's starting step (Solving ODEs I, §II.4) from `s`, for a method
/// of order `order`, s. One evaluation (`hint`: the contact solve's warm
/// start, carried on).
pub(crate) fn initial_step(s: &Start, tol: &Tol, hint: &mut f64, order: u32) -> f64 {
    let (y, a0) = (s.y0, s.a0);
    let sc = tol.scales(y, y);
    let norm = |u: f64, v: f64| ((u / sc[0]).powi(2) + (v / sc[1]).powi(2)).sqrt() / 2f64.sqrt();
    let d0 = norm(y[0], y[1]);
    let d1 = norm(y[1], a0);
    let h0 = if d0 < 1e-5 || d1 < 1e-5 {
        1e-6
    } else {
        0.01 * d0 / d1
    };
    let y1 = [y[0] + h0 * y[1], y[1] + h0 * a0];
    let a1 = s.accel(s.t + h0, y1, hint);
    let d2 = norm(y1[1] - y[1], a1 - a0) / h0;
    let dm = d1.max(d2);
    let h1 = if dm <= 1e-15 {
        (h0 * 1e-3).max(1e-6)
    } else {
        (0.01 / dm).powf(1.0 / (order as f64 + 1.0))
    };
    (100.0 * h0).min(h1)
}

/// The smallest step from `t` for an attempted step `hh`, s: as the step
/// `t + m` actually makes once rounded to a representable time, so that a
/// step rejected down to it is then accepted (compared with the unrounded
/// `m`, the rounded step could exceed it and be rejected for ever).
pub(crate) fn min_step(t: f64, hh: f64) -> f64 {
    let m = 16.0 * f64::EPSILON * t.abs().max(hh);
    ((t + m) - t).max(m)
}

/// The factor on a rejected step with scaled error `err` (`err_exp` the
/// controller's exponent, see `Pair::ERR_EXP`).
pub(crate) fn shrink(err: f64, err_exp: f64) -> f64 {
    if err.is_finite() {
        (0.9 * err.powf(err_exp)).clamp(0.2, 1.0)
    } else {
        0.2
    }
}

/// The factor on an accepted step with scaled error `err`: at most 1 right
/// after a rejection.
pub(crate) fn grow(err: f64, err_exp: f64, after_rejection: bool) -> f64 {
    let fac = if err == 0.0 {
        10.0
    } else {
        (0.9 * err.powf(err_exp)).clamp(0.2, 10.0)
    };
    if after_rejection {
        fac.min(1.0)
    } else {
        fac
    }
}

/// Flexible laws, approaching `theta = 0` in partial contact: the contact
/// varies on the scale of `phi` itself (`af ~ phi^(-1/2)`), so the error of
/// a step is a function of `r = h |omega / theta|`: control `r` (grown by the
/// same factor `fac` as `h`) and keep it below `R_MAX`, rather than let `h`
/// grow into the steep region. Returns `h_next` so limited; `y` the end of
/// the accepted step `hh`.
pub(super) fn toward_zero(h_next: f64, hh: f64, fac: f64, y: [f64; 2], theta_jo: f64) -> f64 {
    if y[0] * y[1] < 0.0 && y[0].abs() > theta_jo {
        let time_to_zero = (y[0] / y[1]).abs();
        let r = (hh / time_to_zero * fac).min(R_MAX);
        if r > 0.0 {
            return h_next.min(r * time_to_zero);
        }
    }
    h_next
}
