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
//! The rotations are cut at those, and at every octave from the first
//! iterative regime (for a stiff interface `a` goes as `phi^(-1/2)` over
//! decades); each interval is cut in two, and each half fitted by a
//! Chebyshev series in `s` (in `[0, 1]`) from its outer end: `phi = end +
//! L s²` when that end is one of the rotations above (the square-root end
//! becomes smooth in `s`), `phi = end + L s` otherwise (an octave). Every piece is checked against
//! the solver between its nodes and halved until the four agree to
//! `FIT_RTOL`; a piece that does not after `MAX_DEPTH` halvings is left to
//! the solver (`contact` returns `None` there).

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use super::{Contact, Interface, Law, Regime};

/// No body rotates this far before it overturns (`alpha < pi/2`), rad.
const PHI_CAP: f64 = std::f64::consts::FRAC_PI_2;
/// Tables kept for reuse in this process ([`ContactTable::shared`]); past
/// this many, those no simulator holds are dropped.
const SHARED_MAX: usize = 64;

/// Chebyshev terms per piece.
const DEGREE: usize = 16;
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
    /// The end the map starts from, and the reciprocal of the signed
    /// length `len`: `phi = end + len s²` beside a rotation where the
    /// resultants have a square-root end (`sqrt`), else `phi = end + len s`.
    end: f64,
    inv_len: f64,
    sqrt: bool,
    /// Chebyshev coefficients of `[af, af']` and of `[a, a']`, lowest
    /// first, each cut after the last term that matters (`truncate`);
    /// empty: the solver answers on this piece.
    af: Vec<[f64; 2]>,
    a: Vec<[f64; 2]>,
}

impl Piece {
    /// The Chebyshev variable `x = 2 s - 1` at `phi`.
    #[inline(always)]
    fn x(&self, phi: f64) -> f64 {
        let u = ((phi - self.end) * self.inv_len).clamp(0.0, 1.0);
        2.0 * if self.sqrt { u.sqrt() } else { u } - 1.0
    }

    /// Clenshaw's sum of `coef` at `x`, with `c_k - b_{k+2}` taken off
    /// the chain of dependent operations (one product and one sum a term).
    #[inline(always)]
    fn sum(coef: &[[f64; 2]], x: f64) -> [f64; 2] {
        let x2 = 2.0 * x;
        let (mut b1, mut b2) = ([0.0; 2], [0.0; 2]);
        for ck in coef[1..].iter().rev() {
            let b0 = [(ck[0] - b2[0]) + x2 * b1[0], (ck[1] - b2[1]) + x2 * b1[1]];
            b2 = b1;
            b1 = b0;
        }
        [
            (coef[0][0] - b2[0]) + x * b1[0],
            (coef[0][1] - b2[1]) + x * b1[1],
        ]
    }

    fn at(&self, phi: f64) -> [f64; 4] {
        let x = self.x(phi);
        let ([af, daf], [a, da]) = (Self::sum(&self.af, x), Self::sum(&self.a, x));
        [af, daf, a, da]
    }
}

/// The table of one interface from `min(thetaJo, thetaC)` over whole octaves.
#[derive(Clone, Debug)]
pub struct ContactTable {
    pieces: Vec<Piece>,
    /// The pieces' upper ends, in order (the search touches only these).
    his: Vec<f64>,
    /// `a` at each piece's lower end, m: the largest on the piece (`a`
    /// falls as `phi` grows, `da/dphi = -F/(phi L0)`, docs/model.md §2).
    /// Beside the pieces, not in them: a larger piece made every
    /// evaluation dearer (docs/performance.md).
    a_lo: Vec<f64>,
    /// For each bucket of rotations (see `bucket`) from the table's lower
    /// end, the first piece that reaches into it.
    first: Vec<u32>,
    /// The bucket of the table's lower end.
    bucket0: u64,
}

/// A bucket of positive rotations: the exponent and the first three bits of
/// the mantissa, a piecewise-linear `log2` with eight buckets an octave. The
/// pieces span at most an octave, so a bucket starts at most a few pieces
/// before the one that holds a rotation, and the lookup needs no search.
#[inline(always)]
fn bucket(phi: f64) -> u64 {
    phi.to_bits() >> 49
}

fn solved(it: &Interface, phi: f64) -> [f64; 4] {
    let c = it.contact(phi);
    [c.af, c.daf, c.a, c.da]
}

/// `coef` without its trailing terms whose absolute sum is below `tol[q]`
/// for both series `q` (the most they can change the sum on `[-1, 1]`).
fn truncate(coef: &[[f64; 4]], pair: usize, tol: [f64; 2]) -> Vec<[f64; 2]> {
    let mut tail = [0.0f64; 2];
    let mut keep = coef.len();
    while keep > 1 {
        let c = coef[keep - 1];
        let next = [tail[0] + c[pair].abs(), tail[1] + c[pair + 1].abs()];
        if next[0] > tol[0] || next[1] > tol[1] {
            break;
        }
        tail = next;
        keep -= 1;
    }
    coef[..keep]
        .iter()
        .map(|c| [c[pair], c[pair + 1]])
        .collect()
}

/// Chebyshev fit of the solver on `[lo, hi]` from `end`, or `None` when it
/// misses `FIT_RTOL` between the nodes.
fn fit(it: &Interface, lo: f64, hi: f64, end: f64, sqrt: bool) -> Option<Piece> {
    let n = DEGREE;
    let len = if end == lo { hi - lo } else { lo - hi };
    let angle = |k: usize, j: f64| std::f64::consts::PI * k as f64 * j / n as f64;
    let vals: Vec<[f64; 4]> = (0..n)
        .map(|j| {
            let s = 0.5 * (angle(1, j as f64 + 0.5).cos() + 1.0);
            solved(it, end + len * if sqrt { s * s } else { s })
        })
        .collect();
    let coef: Vec<[f64; 4]> = (0..n)
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
    // The check below is relative: to the value for `af` and `a` (never 0
    // on a piece), to the largest value on the piece for the derivatives
    // (`a'` may pass through 0).
    let smallest = |q: usize| vals.iter().fold(f64::INFINITY, |m, v| m.min(v[q].abs()));
    let largest = |q: usize| vals.iter().fold(0.0f64, |m, v| m.max(v[q].abs()));
    let scale: [f64; 4] = std::array::from_fn(|q| if q % 2 == 1 { largest(q) } else { 0.0 });
    // what truncation may cost: a tenth of the check's allowance
    let cut: [f64; 4] = std::array::from_fn(|q| {
        let size = if q % 2 == 1 { largest(q) } else { smallest(q) };
        0.1 * FIT_RTOL[q] * size
    });
    let piece = Piece {
        lo,
        hi,
        end,
        inv_len: 1.0 / len,
        sqrt,
        af: truncate(&coef, 0, [cut[0], cut[1]]),
        a: truncate(&coef, 2, [cut[2], cut[3]]),
    };
    // midway between the nodes (not at the ends: the neighbouring regime's
    // derivatives differ there)
    let ok = (1..n).all(|j| {
        let s = 0.5 * (angle(1, j as f64).cos() + 1.0);
        let phi = end + len * if sqrt { s * s } else { s };
        let (t, r) = (piece.at(phi), solved(it, phi));
        (0..4).all(|q| (t[q] - r[q]).abs() <= FIT_RTOL[q] * r[q].abs().max(scale[q]))
    });
    ok.then_some(piece)
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
    /// The table of `it` reaching `phi_max` ([`new`](Self::new)), built
    /// once per process for each interface and octave and kept while any simulator uses it (and, up to
    /// `SHARED_MAX` tables, after): a study runs the same body many times,
    /// and a build (about a millisecond) costs as much as a few hundred
    /// communication steps.
    pub fn shared(it: &Interface, phi_max: f64) -> Option<Arc<ContactTable>> {
        static TABLES: OnceLock<Mutex<HashMap<String, Option<Arc<ContactTable>>>>> =
            OnceLock::new();
        // Debug prints every f64 so that it reads back to the same bits:
        // equal keys are the same interface and range
        let key = format!("{it:?} {:?}", Self::span(it, phi_max)?.1);
        let tables = TABLES.get_or_init(Default::default);
        if let Some(t) = tables.lock().ok()?.get(&key) {
            return t.clone();
        }
        // built outside the lock: another thread may build the same table,
        // the same to the bit
        let table = ContactTable::new(it, phi_max).map(Arc::new);
        let mut tables = tables.lock().ok()?;
        if tables.len() >= SHARED_MAX {
            tables.retain(|_, t| t.as_ref().is_some_and(|t| Arc::strong_count(t) > 1));
        }
        tables.insert(key, table.clone());
        table
    }

    /// The table of `it` from the first iterative regime, `min(thetaJo,
    /// thetaC)`, over as many octaves as reach `phi_max` (rad); `None` for
    /// the rigid law (closed form) or when no iterative regime starts below
    /// `phi_max`. The pieces depend on the interface alone (not on
    /// `phi_max`, which only decides where they stop), so that `af` is a
    /// function of the interface's parameters only.
    pub fn new(it: &Interface, phi_max: f64) -> Option<ContactTable> {
        let (phi0, top) = Self::span(it, phi_max)?;
        let (kn, fm) = match it.law() {
            Law::Rigid => return None,
            Law::Elastic { kn } => (kn, f64::INFINITY),
            Law::ElastoPlastic { kn, fm } => (kn, fm),
        };
        let (jo, c) = (it.theta_jo(), it.theta_c());
        // octaves from phi0 (for a stiff interface `a` goes as
        // `phi^(-1/2)` over decades), the regime thresholds, and where an
        // edge of the stress profile passes a kink of the width, searched up
        // to PHI_CAP whatever phi_max
        let mut cuts: Vec<f64> = std::iter::successors(Some(phi0), |&p| Some(2.0 * p))
            .take_while(|&p| p <= top)
            .collect();
        // where the resultants have a square-root end or a kink
        let mut singular = vec![jo, c];
        let above = |x: f64| x * (1.0 + 1e-12);
        for edge in it.shape().width_breaks().into_iter().flatten() {
            singular.extend(crossing(|p| it.contact(p).a, edge, above(jo), PHI_CAP));
            if fm.is_finite() && above(c) < PHI_CAP {
                let xp = |p: f64| it.contact(p).a - fm / (kn * p);
                singular.extend(crossing(xp, edge, above(c), PHI_CAP));
            }
        }
        cuts.extend(singular.iter().filter(|&&x| x > phi0));
        cuts.retain(|&x| x < top);
        cuts.push(top);
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        let mut pieces = Vec::new();
        for w in cuts.windows(2) {
            let (lo, hi) = (w[0], w[1]);
            let mid = 0.5 * (lo + hi);
            // the halves from the interval's ends (kinks or not)
            let singular = |x: f64| singular.contains(&x);
            Self::cover(it, lo, mid, lo, singular(lo), 0, &mut pieces);
            Self::cover(it, mid, hi, hi, singular(hi), 0, &mut pieces);
        }
        if pieces.is_empty() {
            return None;
        }
        let his: Vec<f64> = pieces.iter().map(|p| p.hi).collect();
        let a_lo = pieces
            .iter()
            .map(|p| {
                if p.af.is_empty() {
                    f64::NAN
                } else {
                    p.at(p.lo)[2]
                }
            })
            .collect();
        let bucket0 = bucket(pieces[0].lo);
        let first = (bucket0..=bucket(top))
            .map(|k| his.partition_point(|&hi| hi < f64::from_bits(k << 49)) as u32)
            .collect();
        Some(ContactTable {
            pieces,
            his,
            a_lo,
            first,
            bucket0,
        })
    }

    /// `(min(thetaJo, thetaC), phi0 2^k)` with the least `k` that reaches
    /// `phi_max`, or `None` when there is nothing to tabulate.
    fn span(it: &Interface, phi_max: f64) -> Option<(f64, f64)> {
        let phi0 = it.theta_jo().min(it.theta_c());
        if it.law() == Law::Rigid || phi_max.is_nan() || phi_max <= phi0 || phi_max > PHI_CAP {
            return None;
        }
        let top = std::iter::successors(Some(phi0), |&p| Some(2.0 * p)).find(|&p| p >= phi_max)?;
        Some((phi0, top))
    }

    /// Fits `[lo, hi]` from `end`; where that misses, each half from its
    /// outer end (so the half beside `end` keeps it), to `MAX_DEPTH`.
    fn cover(
        it: &Interface,
        lo: f64,
        hi: f64,
        end: f64,
        sqrt: bool,
        depth: u32,
        out: &mut Vec<Piece>,
    ) {
        if let Some(p) = fit(it, lo, hi, end, sqrt) {
            out.push(p);
        } else if depth >= MAX_DEPTH {
            out.push(Piece {
                lo,
                hi,
                end: lo,
                inv_len: 1.0 / (hi - lo),
                sqrt: false,
                af: Vec::new(),
                a: Vec::new(),
            });
        } else {
            let mid = 0.5 * (lo + hi);
            // the half beside `end` keeps its map
            let (at_lo, at_hi) = (sqrt && end == lo, sqrt && end == hi);
            Self::cover(it, lo, mid, lo, at_lo, depth + 1, out);
            Self::cover(it, mid, hi, hi, at_hi, depth + 1, out);
        }
    }

    /// The rotations the table covers, rad.
    pub fn range(&self) -> (f64, f64) {
        (self.pieces[0].lo, self.pieces[self.pieces.len() - 1].hi)
    }

    /// Number of pieces, and of those left to the solver.
    pub fn pieces(&self) -> (usize, usize) {
        let open = self.pieces.iter().filter(|p| p.af.is_empty()).count();
        (self.pieces.len(), open)
    }

    /// The piece that answers at `phi = |theta|` and the regime there.
    #[inline(always)]
    fn lookup(&self, it: &Interface, phi: f64) -> Option<(&Piece, Regime)> {
        self.index(it, phi)
            .map(|(i, regime)| (&self.pieces[i], regime))
    }

    /// [`lookup`](Self::lookup) by the piece's index.
    #[inline(always)]
    fn index(&self, it: &Interface, phi: f64) -> Option<(usize, Regime)> {
        let (lo, hi) = self.range();
        if !(phi > lo && phi <= hi) {
            return None;
        }
        let regime = it.regime_at(phi);
        if regime == Regime::FullContact {
            return None;
        }
        // the bucket's first piece ends at or above the bucket's start,
        // and the last piece at the table's end: the scan stops in range
        let mut i = self.first[(bucket(phi) - self.bucket0) as usize] as usize;
        while self.his[i] < phi {
            i += 1;
        }
        (!self.pieces[i].af.is_empty()).then_some((i, regime))
    }

    /// The contact of `it` (the interface the table was built for) at
    /// `phi = |theta|` from the table; `None` outside its range, in full
    /// contact (closed form) and on a piece left to the solver.
    #[inline]
    pub fn contact(&self, it: &Interface, phi: f64) -> Option<Contact> {
        let phi = phi.abs();
        let (piece, regime) = self.lookup(it, phi)?;
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

    /// Like [`contact`](Self::contact), but only `af` and `af'` (what the
    /// equation of motion needs): `a`, `a'` and the contact length are NaN.
    #[inline(always)]
    pub fn reaction(&self, it: &Interface, phi: f64) -> Option<Contact> {
        let phi = phi.abs();
        let (piece, regime) = self.lookup(it, phi)?;
        Some(Self::reaction_on(piece, regime, phi))
    }

    /// `af` and `af'` on `piece` at `phi >= 0`.
    #[inline(always)]
    fn reaction_on(piece: &Piece, regime: Regime, phi: f64) -> Contact {
        let [af, daf] = Piece::sum(&piece.af, piece.x(phi));
        Contact {
            af,
            daf,
            a: f64::NAN,
            contact_length: f64::NAN,
            phi,
            da: f64::NAN,
            regime,
            iterations: 0,
        }
    }

    /// [`reaction`](Self::reaction) and a bound on the contact's `a`, m:
    /// the table's `a` at the lower end of its piece (at most a few ulps
    /// below the solver's there, within the fit's tolerance; `a` falls as `phi` grows).
    #[inline(always)]
    pub fn reaction_bounded(&self, it: &Interface, phi: f64) -> Option<(Contact, f64)> {
        let phi = phi.abs();
        let (i, regime) = self.index(it, phi)?;
        let piece = &self.pieces[i];
        Some((Self::reaction_on(piece, regime, phi), self.a_lo[i]))
    }
}
