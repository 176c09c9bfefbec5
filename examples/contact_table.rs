//! A measurement, not a model: what a table of the contact solve would
//! cost and how accurate it would be, for the Dharahara base (issue 14,
//! docs/performance.md, "Contact solve").
//!
//! For each case, the partial-contact rotations from `min(thetaJo, thetaC)`
//! to 1.1 alpha are cut at every rotation where the resultants are not
//! smooth (`thetaJo`, `thetaC`, and where the contact edge `a` or the
//! plastic edge `a - fm/(kn phi)` passes the inner circle's edges `Ro -+ Ri`);
//! the intervals are cut further so that none spans more than a factor 2
//! (`a` goes as `phi^(-1/2)` over decades when the interface is stiff); each
//! interval is halved, and each half fitted by Chebyshev series of
//! degree `N` in `s`, `phi = end + L s^2` from its outer end (the square-root
//! ends of the circles' chords become smooth in `s`). Printed: the
//! largest relative error of `af`, `af'` and `a` against the solver over a
//! dense grid, and the cost of one evaluation of the table (`af`, `af'`,
//! `a`, `a'`) against one warm solve (`Interface::contact_near`).
//!
//! ```sh
//! cargo run --release --example contact_table
//! ```

use std::hint::black_box;
use std::time::Instant;

use rocking::{Interface, Law, Shape};

const RO: f64 = 3.99;
const RI: f64 = 2.12;
const W: f64 = 24_003.94e3;
const ALPHA: f64 = 0.13135;

struct Piece {
    lo: f64,
    hi: f64,
    end: f64,
    len: f64,
    /// Chebyshev coefficients of af, af', a, a' (interleaved, one Clenshaw pass).
    coef: Vec<[f64; 4]>,
}

fn quantities(it: &Interface, phi: f64) -> [f64; 4] {
    let c = it.contact(phi);
    [c.af, c.daf, c.a, c.da]
}

fn fit(it: &Interface, lo: f64, hi: f64, end: f64, n: usize) -> Piece {
    let len = if end == lo { hi - lo } else { lo - hi };
    let mut vals = vec![[0.0; 4]; n];
    for (j, v) in vals.iter_mut().enumerate() {
        let x = (std::f64::consts::PI * (j as f64 + 0.5) / n as f64).cos();
        let s = 0.5 * (x + 1.0);
        *v = quantities(it, end + len * s * s);
    }
    let coef = (0..n)
        .map(|k| {
            std::array::from_fn(|q| {
                let sum: f64 = (0..n)
                    .map(|j| {
                        vals[j][q]
                            * (std::f64::consts::PI * k as f64 * (j as f64 + 0.5) / n as f64).cos()
                    })
                    .sum();
                sum * 2.0 / n as f64 * if k == 0 { 0.5 } else { 1.0 }
            })
        })
        .collect();
    Piece {
        lo,
        hi,
        end,
        len,
        coef,
    }
}

fn eval(pieces: &[Piece], phi: f64) -> [f64; 4] {
    let i = pieces.partition_point(|p| p.hi < phi).min(pieces.len() - 1);
    let p = &pieces[i];
    let s = ((phi - p.end) / p.len).max(0.0).sqrt();
    let x2 = 2.0 * (2.0 * s - 1.0);
    let (mut b1, mut b2) = ([0.0; 4], [0.0; 4]);
    for ck in p.coef.iter().skip(1).rev() {
        let b0: [f64; 4] = std::array::from_fn(|q| ck[q] + x2 * b1[q] - b2[q]);
        b2 = b1;
        b1 = b0;
    }
    std::array::from_fn(|q| p.coef[0][q] + 0.5 * x2 * b1[q] - b2[q])
}

/// The rotation in `[lo, hi]` where the monotone `g` crosses `target`, if it does.
fn crossing(g: impl Fn(f64) -> f64, target: f64, mut lo: f64, mut hi: f64) -> Option<f64> {
    let (glo, ghi) = (g(lo) - target, g(hi) - target);
    if glo * ghi >= 0.0 {
        return None;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if (g(mid) - target) * glo > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(0.5 * (lo + hi))
}

fn table(it: &Interface, kn: f64, fm: f64, phi_max: f64, n: usize) -> Vec<Piece> {
    let phi0 = it.theta_jo().min(it.theta_c());
    let mut cuts = vec![phi0, it.theta_jo(), phi_max];
    if it.theta_c() < phi_max {
        cuts.push(it.theta_c());
    }
    for edge in [RO - RI, RO + RI] {
        let a = |phi: f64| it.contact(phi).a;
        cuts.extend(crossing(a, edge, it.theta_jo() * (1.0 + 1e-12), phi_max));
        if fm.is_finite() {
            let xp = |phi: f64| it.contact(phi).a - fm / (kn * phi);
            let from = it.theta_c().max(phi0) * (1.0 + 1e-12);
            if from < phi_max {
                cuts.extend(crossing(xp, edge, from, phi_max));
            }
        }
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    // a ~ phi^(-1/2) over decades for stiff interfaces: at most a factor 2 a piece
    let mut fine = vec![cuts[0]];
    for &c in &cuts[1..] {
        let last = *fine.last().unwrap();
        let parts = ((c / last).ln() / 2f64.ln()).ceil().max(1.0) as usize;
        for j in 1..=parts {
            fine.push(last * (c / last).powf(j as f64 / parts as f64));
        }
        *fine.last_mut().unwrap() = c;
    }
    let cuts = fine;
    let mut pieces = Vec::new();
    for w in cuts.windows(2) {
        let (lo, hi) = (w[0], w[1]);
        if hi <= lo {
            continue;
        }
        let mid = 0.5 * (lo + hi);
        pieces.push(fit(it, lo, mid, lo, n));
        pieces.push(fit(it, mid, hi, hi, n));
    }
    pieces
}

fn main() {
    let shape = Shape::HollowCircle { ro: RO, ri: RI };
    println!(
        "| case | N | pieces | max rel. error af | af' | a | table ns/eval | warm solve ns/eval |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for (name, kn, fm) in [
        ("F170_fm5", 170e6, 5e6),
        ("F85_fm2", 85e6, 2e6),
        ("I15_elastic", 15e9, f64::INFINITY),
        ("I15_fm2", 15e9, 2e6),
    ] {
        let law = if fm.is_finite() {
            Law::ElastoPlastic { kn, fm }
        } else {
            Law::Elastic { kn }
        };
        let it = Interface::new(shape, law, W);
        let phi_max = 1.1 * ALPHA;
        for n in [16, 24, 32] {
            let pieces = table(&it, kn, fm, phi_max, n);
            let (lo, hi) = (pieces[0].lo, phi_max);
            let mut err = [0.0f64; 3];
            let m = 200_000;
            for i in 0..=m {
                let phi = lo + (hi - lo) * i as f64 / m as f64;
                let (t, r) = (eval(&pieces, phi), quantities(&it, phi));
                for q in 0..3 {
                    err[q] = err[q].max(((t[q] - r[q]) / r[q]).abs());
                }
            }
            // a rocking-like sweep of rotations, each near the last
            let rots: Vec<f64> = (0..1_000_000)
                .map(|i| lo + (hi - lo) * 0.5 * (1.0 - (i as f64 * 1e-4).cos()))
                .collect();
            let t0 = Instant::now();
            let mut acc = 0.0;
            for &phi in &rots {
                acc += eval(&pieces, black_box(phi))[0];
            }
            let table_ns = t0.elapsed().as_nanos() as f64 / rots.len() as f64;
            let t0 = Instant::now();
            let mut hint = f64::NAN;
            for &phi in &rots {
                let c = it.contact_near(black_box(phi), hint);
                hint = c.a;
                acc += c.af;
            }
            let solve_ns = t0.elapsed().as_nanos() as f64 / rots.len() as f64;
            black_box(acc);
            println!(
                "| {name} | {n} | {} | {:.1e} | {:.1e} | {:.1e} | {table_ns:.0} | {solve_ns:.0} |",
                pieces.len(),
                err[0],
                err[1],
                err[2]
            );
        }
    }
}
