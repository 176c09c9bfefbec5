//! Dense output of one step and the location of events on it.
//!
//! For the second-order system the step's end values `theta, omega, theta''`
//! at both ends determine the quintic Hermite interpolant of `theta`
//! (local error `O(h^6)`, no extra right-hand-side evaluation); `omega` is
//! its derivative divided by `h`. Events are the first `tau` in `(0, 1]` where `s theta`
//! falls to 0 (an impact) or rises to `thetaOv` (overturning). The step is
//! cut into monotone pieces of `theta` at the roots of `omega`, so a root is
//! bracketed even when `theta` turns around inside the step (a small
//! excursion after an impact), and refined by safeguarded Newton. The same
//! search cuts steps at the kinks of the right-hand side (regime
//! thresholds), where the error estimate of a step across would be
//! meaningless.

/// `theta(t0 + tau h) = sum_k c[k] tau^k`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Hermite {
    c: [f64; 6],
}

impl Hermite {
    /// From `(theta, omega, theta'')` at the start and at the end of a step of length `h`.
    pub fn new(h: f64, start: [f64; 3], end: [f64; 3]) -> Hermite {
        let (p0, v0, a0) = (start[0], h * start[1], h * h * start[2]);
        let (p1, v1, a1) = (end[0], h * end[1], h * h * end[2]);
        let d = p1 - p0 - v0 - 0.5 * a0;
        let v = v1 - v0 - a0;
        let a = a1 - a0;
        Hermite {
            c: [
                p0,
                v0,
                0.5 * a0,
                10.0 * d - 4.0 * v + 0.5 * a,
                -15.0 * d + 7.0 * v - a,
                6.0 * d - 3.0 * v + 0.5 * a,
            ],
        }
    }

    /// `theta` at `tau`.
    #[inline]
    pub fn theta(&self, tau: f64) -> f64 {
        let c = &self.c;
        c[0] + tau * (c[1] + tau * (c[2] + tau * (c[3] + tau * (c[4] + tau * c[5]))))
    }

    /// Bounds of `theta` on `[0, 1]`, widened by what rounding may add to
    /// a value computed by [`theta`](Self::theta): the hull of the Bernstein
    /// coefficients, which encloses the polynomial.
    pub fn bounds(&self) -> (f64, f64) {
        let c = &self.c;
        let b = [
            c[0],
            c[0] + 0.2 * c[1],
            c[0] + 0.4 * c[1] + 0.1 * c[2],
            c[0] + 0.6 * c[1] + 0.3 * c[2] + 0.1 * c[3],
            c[0] + 0.8 * c[1] + 0.6 * c[2] + 0.4 * c[3] + 0.2 * c[4],
            c[0] + c[1] + c[2] + c[3] + c[4] + c[5],
        ];
        let margin = 16.0 * f64::EPSILON * c.iter().map(|x| x.abs()).sum::<f64>();
        let (lo, hi) = b
            .iter()
            .fold((b[0], b[0]), |(l, h), &x| (l.min(x), h.max(x)));
        (lo - margin, hi + margin)
    }

    /// `d theta / d tau` (= `h omega`).
    #[inline]
    fn dtheta(&self, tau: f64) -> f64 {
        let c = &self.c;
        c[1] + tau * (2.0 * c[2] + tau * (3.0 * c[3] + tau * (4.0 * c[4] + tau * 5.0 * c[5])))
    }

    /// `d² theta / d tau²`.
    #[inline]
    fn d2theta(&self, tau: f64) -> f64 {
        let c = &self.c;
        2.0 * c[2] + tau * (6.0 * c[3] + tau * (12.0 * c[4] + tau * 20.0 * c[5]))
    }
}

/// What the step ran into.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Hit {
    /// `theta` reaches 0: an impact.
    Impact,
    /// `|theta|` reaches `thetaOv`.
    Overturn,
    /// `|theta|` reaches the `k`-th kink level of the right-hand side (a
    /// regime threshold): the step is cut there, nothing else happens.
    Kink(usize),
    /// A moving threshold under a vertical input (docs/model.md §6.4: the
    /// heel closing or the toe starting to crush at `N(t)`): cut there like
    /// a kink, at the level of `|theta|` found on the step.
    MovingKink,
}

/// Pieces the step is sampled in to find the turning points of `theta`.
const PIECES: usize = 8;

/// The first event in `(0, 1]` of the step interpolated by `p`, for a body
/// on side `s` (`s theta >= 0` at the start): `(hit, tau)`. `kinks` are
/// levels of `|theta|` in `(0, thetaOv)` crossed in either direction.
pub(crate) fn first_event(p: &Hermite, s: f64, theta_ov: f64, kinks: &[f64]) -> Option<(Hit, f64)> {
    // Nothing to find when the bounds of g keep clear of 0, thetaOv and
    // every kink: each value the walk below computes lies within them.
    let (lo, hi) = p.bounds();
    let (g_min, g_max) = if s > 0.0 { (lo, hi) } else { (-hi, -lo) };
    if g_min > 0.0 && g_max < theta_ov && kinks.iter().all(|&l| l < g_min || l > g_max) {
        return None;
    }
    // g(tau) = s theta(tau); g(0) >= 0. Walk the monotone pieces of g.
    let g = |tau: f64| s * p.theta(tau);
    let dg = |tau: f64| s * p.dtheta(tau);
    let mut lo = 0.0;
    let mut g_lo = g(0.0);
    for k in 1..=PIECES {
        let hi = k as f64 / PIECES as f64;
        let d_lo = slope_sign(p, s, lo);
        let d_hi = dg(hi);
        // split at a turning point of theta inside (lo, hi)
        let mut cuts = [hi; 2];
        let mut n = 1;
        if d_lo * d_hi < 0.0 {
            let tp = refine(&dg, &|t| s * p.d2theta(t), lo, hi, d_lo > 0.0, 0.0);
            if tp > lo && tp < hi {
                cuts = [tp, hi];
                n = 2;
            }
        }
        for &b in &cuts[..n] {
            let g_b = g(b);
            // impact: g from > 0 to <= 0
            if g_lo > 0.0 && g_b <= 0.0 {
                let first = first_kink_down(kinks, g_lo, g_b.max(0.0));
                return Some(match first {
                    Some(i) => (Hit::Kink(i), refine(&g, &dg, lo, b, true, kinks[i])),
                    None => (Hit::Impact, refine(&g, &dg, lo, b, true, 0.0)),
                });
            }
            // overturning: g from < thetaOv to >= thetaOv
            if g_lo < theta_ov && g_b >= theta_ov {
                let first = first_kink_up(kinks, g_lo, theta_ov);
                return Some(match first {
                    Some(i) => (Hit::Kink(i), refine(&g, &dg, lo, b, false, kinks[i])),
                    None => (Hit::Overturn, refine(&g, &dg, lo, b, false, theta_ov)),
                });
            }
            if g_b > g_lo {
                if let Some(i) = first_kink_up(kinks, g_lo, g_b) {
                    return Some((Hit::Kink(i), refine(&g, &dg, lo, b, false, kinks[i])));
                }
            } else if let Some(i) = first_kink_down(kinks, g_lo, g_b) {
                return Some((Hit::Kink(i), refine(&g, &dg, lo, b, true, kinks[i])));
            }
            lo = b;
            g_lo = g_b;
        }
    }
    None
}

/// The largest `|theta|` on `[0, tau_end]` of the step: at the ends and at
/// the turning points of `theta` inside, found as in [`first_event`] (the
/// interval cut into `PIECES`, a root of `omega` bracketed in a piece where
/// it changes sign, refined to the last bits).
pub(crate) fn max_abs(p: &Hermite, tau_end: f64) -> f64 {
    let dg = |tau: f64| p.dtheta(tau);
    let d2g = |tau: f64| p.d2theta(tau);
    let mut m = p.theta(0.0).abs();
    let mut lo = 0.0;
    for k in 1..=PIECES {
        let hi = tau_end * k as f64 / PIECES as f64;
        let (d_lo, d_hi) = (dg(lo), dg(hi));
        if d_lo * d_hi < 0.0 {
            let tp = refine(&dg, &d2g, lo, hi, d_lo > 0.0, 0.0);
            m = m.max(p.theta(tp).abs());
        }
        m = m.max(p.theta(hi).abs());
        lo = hi;
    }
    m
}

/// The lowest level `L` with `from < L <= to` (g rising).
fn first_kink_up(kinks: &[f64], from: f64, to: f64) -> Option<usize> {
    let mut best: Option<usize> = None;
    for (i, &l) in kinks.iter().enumerate() {
        if from < l && l <= to && best.is_none_or(|j| l < kinks[j]) {
            best = Some(i);
        }
    }
    best
}

/// The highest level `L` with `to <= L < from` (g falling).
fn first_kink_down(kinks: &[f64], from: f64, to: f64) -> Option<usize> {
    let mut best: Option<usize> = None;
    for (i, &l) in kinks.iter().enumerate() {
        if to <= l && l < from && best.is_none_or(|j| l > kinks[j]) {
            best = Some(i);
        }
    }
    best
}

/// Sign of `s theta'` just after `tau` (from `theta''` where `omega` is 0).
#[inline]
fn slope_sign(p: &Hermite, s: f64, tau: f64) -> f64 {
    let d = s * p.dtheta(tau);
    if d != 0.0 {
        d
    } else {
        s * p.d2theta(tau)
    }
}

/// Root of `f = target` on `[lo, hi]` where `f` is monotone, decreasing
/// through the target if `decreasing`; bisection-safeguarded Newton to the
/// last bits. Returns the end of the bracket where `f` has crossed.
fn refine(
    f: &dyn Fn(f64) -> f64,
    df: &dyn Fn(f64) -> f64,
    mut lo: f64,
    mut hi: f64,
    decreasing: bool,
    target: f64,
) -> f64 {
    // normalise to an increasing function crossing 0
    let sgn = if decreasing { -1.0 } else { 1.0 };
    let r = |t: f64| sgn * (f(t) - target);
    let mut x = 0.5 * (lo + hi);
    for _ in 0..100 {
        let fx = r(x);
        if fx >= 0.0 {
            hi = x;
        } else {
            lo = x;
        }
        let d = sgn * df(x);
        let mut next = if d != 0.0 { x - fx / d } else { f64::NAN };
        if !(next > lo && next < hi) {
            next = 0.5 * (lo + hi);
        }
        if next <= lo || next >= hi || hi - lo <= 4.0 * f64::EPSILON {
            break;
        }
        if (next - x).abs() <= 2.0 * f64::EPSILON * x.abs().max(f64::MIN_POSITIVE) {
            x = next;
            if r(x) >= 0.0 {
                hi = x;
                break;
            }
            // Converged from below without crossing: `hi` is still the far
            // end of the bracket (returning it put a turning point, or an
            // event, at the end of its piece). Go on from the middle of
            // what is left: the bracket at least halves every round.
            lo = x;
            x = 0.5 * (lo + hi);
            continue;
        }
        x = next;
    }
    hi
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn max_abs_finds_a_peak_between_step_ends_below_it() {
        // theta = 0.5 + 2 tau (1 - tau) (h = 1): ends 0.5, peak 1 at tau = 1/2;
        // the quintic Hermite reproduces a quadratic exactly
        for s in [1.0, -1.0] {
            let p = Hermite::new(
                1.0,
                [0.5 * s, 2.0 * s, -4.0 * s],
                [0.5 * s, -2.0 * s, -4.0 * s],
            );
            assert!((max_abs(&p, 1.0) - 1.0).abs() <= 1e-15);
            // rising all the way on [0, 1/4]
            assert!((max_abs(&p, 0.25) - 0.875).abs() <= 1e-15);
        }
    }
}
