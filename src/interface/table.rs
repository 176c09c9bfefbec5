//! The contact solve tabulated: `af`, `af'`, `a` and `a'` against the
//! rotation, fitted once per body so that a contact costs a polynomial
//! evaluation instead of an equilibrium solve (docs/performance.md,
//! "Contact solve").
//!
//! Between the rotations where the stress resultants are not smooth (the
//! regime thresholds `thetaJo`, `thetaC`, and where the contact edge `a` or
//! the plastic edge `a - fm/(kn phi)` passes a kink of the width: a hollow
//! rectangle's flange edge, a hollow circle's inner edge) the four are
//! analytic in `phi`, except that a circle's chord has a square-root end, so
//! that beside those rotations they are analytic in `sqrt(phi - phi_k)`.
//! Each interval is therefore cut in two, and each half fitted by a
//! Chebyshev series in `s`, `phi = end + L s²` (`s` in `[0, 1]`), from its
//! outer end; pieces span at most a factor 2 in `phi` (for a stiff interface
//! `a` goes as `phi^(-1/2)` over decades). Every piece is checked against
//! the solver between its nodes and halved until the four agree to
//! `FIT_RTOL`; a piece that does not after `MAX_DEPTH` halvings is left to
//! the solver (`contact` returns `None` there).

use super::{Contact, Interface, Law, Regime};
use crate::shape::Shape;

/// Chebyshev terms per piece.
const DEGREE: usize = 24;
/// What each piece must reach against the solver, relative, for `[af, af',
/// a, a']` (checked midway between the nodes; the derivatives relative to
/// their largest value on the piece), above the solver's own accuracy:
/// about 1e-10 for `af'` (docs/interface.md) and 3e-8 for `a'` (evaluated
/// before the solve's last Taylor step; it only predicts the next solve and
/// enters the output derivative of `contactLength`).
const FIT_RTOL: [f64; 4] = [4e-13, 1e-9, 4e-13, 1e-7];
/// Halvings of a piece that misses `FIT_RTOL` before it is left to the solver.
const MAX_DEPTH: u32 = 8;

/// One fitted piece `[lo, hi]` of the rotation.
#[derive(Clone, Debug)]
struct Piece {
    lo: f64,
    hi: f64,
    /// The end the square-root map starts from, and the signed length:
    /// `phi = end + len s²`.
    end: f64,
    len: f64,
    /// Chebyshev coefficients of `[af, af', a, a']`, lowest first; empty:
    /// the solver answers on this piece.
    coef: Vec<[f64; 4]>,
}

impl Piece {
    fn at(&self, phi: f64) -> [f64; 4] {
        let s = ((phi - self.end) / self.len).clamp(0.0, 1.0).sqrt();
        let x2 = 2.0 * (2.0 * s - 1.0);
        let (mut b1, mut b2) = ([0.0; 4], [0.0; 4]);
        for ck in self.coef.iter().skip(1).rev() {
            let b0: [f64; 4] = std::array::from_fn(|q| ck[q] + x2 * b1[q] - b2[q]);
            b2 = b1;
            b1 = b0;
        }
        std::array::from_fn(|q| self.coef[0][q] + 0.5 * x2 * b1[q] - b2[q])
    }
}

/// The table of one interface on `[min(thetaJo, thetaC), phi_max]`.
#[derive(Clone, Debug)]
pub struct ContactTable {
    pieces: Vec<Piece>,
}

fn solved(it: &Interface, phi: f64) -> [f64; 4] {
    let c = it.contact(phi);
    [c.af, c.daf, c.a, c.da]
}

/// Chebyshev fit of the solver on `[lo, hi]` from `end`, or `None` when it
/// misses `FIT_RTOL` between the nodes.
fn fit(it: &Interface, lo: f64, hi: f64, end: f64) -> Option<Piece> {
    let n = DEGREE;
    let len = if end == lo { hi - lo } else { lo - hi };
    let angle = |k: usize, j: f64| std::f64::consts::PI * k as f64 * j / n as f64;
    let vals: Vec<[f64; 4]> = (0..n)
        .map(|j| {
            let s = 0.5 * (angle(1, j as f64 + 0.5).cos() + 1.0);
            solved(it, end + len * s * s)
        })
        .collect();
    let coef = (0..n)
        .map(|k| {
            let half = if k == 0 { 0.5 } else { 1.0 };
            std::array::from_fn(|q| {
                let sum: f64 = (0..n)
                    .map(|j| vals[j][q] * angle(k, j as f64 + 0.5).cos())
                    .sum();
                half * 2.0 / n as f64 * sum
            })
        })
        .collect();
    let piece = Piece {
        lo,
        hi,
        end,
        len,
        coef,
    };
    // `a'` may pass through 0: the derivatives relative to their size on the piece
    let scale: [f64; 4] = std::array::from_fn(|q| {
        let big = vals.iter().fold(0.0f64, |m, v| m.max(v[q].abs()));
        if q % 2 == 1 {
            big
        } else {
            0.0
        }
    });
    // midway between the nodes (not at the ends: the neighbouring regime's
    // derivatives differ there)
    let ok = (1..n).all(|j| {
        let s = 0.5 * (angle(1, j as f64).cos() + 1.0);
        let phi = end + len * s * s;
        let (t, r) = (piece.at(phi), solved(it, phi));
        (0..4).all(|q| (t[q] - r[q]).abs() <= FIT_RTOL[q] * r[q].abs().max(scale[q]))
    });
    ok.then_some(piece)
}

/// Where the width of `shape` has a kink or a square-root end inside the base.
fn width_kinks(shape: &Shape) -> Vec<f64> {
    match *shape {
        Shape::SolidRectangle { .. } | Shape::SolidCircle { .. } => vec![],
        Shape::HollowRectangle { b, t, .. } => vec![t, b - t],
        Shape::HollowCircle { ro, ri } => vec![ro - ri, ro + ri],
    }
}

/// The rotation in `[lo, hi]` where the monotone `g` crosses `target`, if it does.
fn crossing(g: impl Fn(f64) -> f64, target: f64, mut lo: f64, mut hi: f64) -> Option<f64> {
    let glo = g(lo) - target;
    if glo * (g(hi) - target) >= 0.0 {
        return None;
    }
    while hi - lo > 4.0 * f64::EPSILON * hi {
        let mid = 0.5 * (lo + hi);
        if (g(mid) - target) * glo > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(0.5 * (lo + hi))
}

impl ContactTable {
    /// The table of `it` up to the rotation `phi_max` (rad); `None` for the
    /// rigid law (closed form) or when no iterative regime starts below `phi_max`.
    pub fn new(it: &Interface, phi_max: f64) -> Option<ContactTable> {
        let (kn, fm) = match it.law() {
            Law::Rigid => return None,
            Law::Elastic { kn } => (kn, f64::INFINITY),
            Law::ElastoPlastic { kn, fm } => (kn, fm),
        };
        let (jo, c) = (it.theta_jo(), it.theta_c());
        let phi0 = jo.min(c);
        if phi_max.is_nan() || phi_max <= phi0 {
            return None;
        }
        let mut cuts = vec![phi0, phi_max];
        cuts.extend([jo, c].into_iter().filter(|&x| x > phi0 && x < phi_max));
        let above = |x: f64| x * (1.0 + 1e-12);
        for edge in width_kinks(it.shape()) {
            cuts.extend(crossing(|p| it.contact(p).a, edge, above(jo), phi_max));
            if fm.is_finite() && above(c) < phi_max {
                let xp = |p: f64| it.contact(p).a - fm / (kn * p);
                cuts.extend(crossing(xp, edge, above(c), phi_max));
            }
        }
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        let mut pieces = Vec::new();
        for w in cuts.windows(2) {
            let parts = (w[1] / w[0]).log2().ceil().max(1.0) as usize;
            let point = |j: usize| match j {
                0 => w[0],
                j if j == parts => w[1],
                j => w[0] * (w[1] / w[0]).powf(j as f64 / parts as f64),
            };
            for j in 0..parts {
                let (lo, hi) = (point(j), point(j + 1));
                let mid = 0.5 * (lo + hi);
                // the halves from the interval's ends (kinks or not)
                Self::cover(it, lo, mid, lo, 0, &mut pieces);
                Self::cover(it, mid, hi, hi, 0, &mut pieces);
            }
        }
        Some(ContactTable { pieces }).filter(|t| !t.pieces.is_empty())
    }

    /// Fits `[lo, hi]` from `end`; where that misses, each half from its
    /// outer end (so the half beside `end` keeps it), to `MAX_DEPTH`.
    fn cover(it: &Interface, lo: f64, hi: f64, end: f64, depth: u32, out: &mut Vec<Piece>) {
        if let Some(p) = fit(it, lo, hi, end) {
            out.push(p);
        } else if depth >= MAX_DEPTH {
            let len = hi - lo;
            out.push(Piece {
                lo,
                hi,
                end: lo,
                len,
                coef: Vec::new(),
            });
        } else {
            let mid = 0.5 * (lo + hi);
            Self::cover(it, lo, mid, lo, depth + 1, out);
            Self::cover(it, mid, hi, hi, depth + 1, out);
        }
    }

    /// The rotations the table covers, rad.
    pub fn range(&self) -> (f64, f64) {
        (self.pieces[0].lo, self.pieces[self.pieces.len() - 1].hi)
    }

    /// Number of pieces, and of those left to the solver.
    pub fn pieces(&self) -> (usize, usize) {
        let open = self.pieces.iter().filter(|p| p.coef.is_empty()).count();
        (self.pieces.len(), open)
    }

    /// The contact of `it` (the interface the table was built for) at
    /// `phi = |theta|` from the table; `None` outside its range, in full
    /// contact (closed form) and on a piece left to the solver.
    #[inline]
    pub fn contact(&self, it: &Interface, phi: f64) -> Option<Contact> {
        let phi = phi.abs();
        let (lo, hi) = self.range();
        if !(phi > lo && phi <= hi) {
            return None;
        }
        let regime = it.regime_at(phi);
        if regime == Regime::FullContact {
            return None;
        }
        let i = self.pieces.partition_point(|p| p.hi < phi);
        let piece = self.pieces.get(i)?;
        if piece.coef.is_empty() {
            return None;
        }
        let [af, daf, a, da] = piece.at(phi);
        Some(Contact {
            af,
            daf,
            a,
            contact_length: a.min(it.depth()),
            phi,
            da,
            regime,
            iterations: 0,
        })
    }
}
