//! One step of Dormand-Prince 8(5,3) for the spatial state: the planar
//! integrator's tableau (`dynamics::erk`) on `N` components, with Hairer's
//! error estimate from the embedded 5th- and 3rd-order formulas.

use crate::dynamics::erk::{DOP_A, DOP_C, DOP_E3, DOP_E5, N12};

use super::eom::{Eom, N};

/// One attempted step.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Step {
    /// The state at the end.
    pub y: [f64; N],
    /// Scaled error: acceptable when `<= 1`.
    pub err: f64,
}

/// A step of `h` (s) from `(t, y0)` with `f0 = dy/dt` there, the contact on
/// the side of `d0`; `scale(y0, y1)` gives each component's error weight.
pub(crate) fn dop853(
    eom: &Eom,
    t: f64,
    (y0, f0): (&[f64; N], &[f64; N]),
    h: f64,
    d0: [f64; 2],
    scale: impl Fn(&[f64; N], &[f64; N]) -> [f64; N],
) -> Step {
    let mut k = [[0.0; N]; N12];
    k[0] = *f0;
    // the last stage is at c = 1 but not at y1: DOP853 is not FSAL
    for i in 1..N12 {
        let y = combine(y0, h, &DOP_A[i], &k, i);
        k[i] = eom.rates(t + DOP_C[i] * h, &y, d0);
    }
    let y1 = combine(y0, h, &DOP_A[N12], &k, N12);
    let sc = scale(y0, &y1);
    let (mut n5, mut n3) = (0.0, 0.0);
    for c in 0..N {
        let (mut e5, mut e3) = (0.0, 0.0);
        for j in 0..N12 {
            e5 += DOP_E5[j] * k[j][c];
            e3 += DOP_E3[j] * k[j][c];
        }
        n5 += (e5 / sc[c]).powi(2);
        n3 += (e3 / sc[c]).powi(2);
    }
    let err = if n5 == 0.0 && n3 == 0.0 {
        0.0
    } else {
        h.abs() * n5 / ((n5 + 0.01 * n3) * N as f64).sqrt()
    };
    Step { y: y1, err }
}

/// `y0 + h sum_{j < i} row_j k_j`.
#[inline]
fn combine(y0: &[f64; N], h: f64, row: &[f64; N12], k: &[[f64; N]; N12], i: usize) -> [f64; N] {
    let mut y = *y0;
    for (c, yc) in y.iter_mut().enumerate() {
        let mut s = 0.0;
        for j in 0..i {
            s += row[j] * k[j][c];
        }
        *yc += h * s;
    }
    y
}
