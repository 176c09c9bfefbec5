//! Benchmark of the corner limit analysis (`cargo bench -p corner --bench study`).
//!
//! Prints a table: the wall time of the paper's five-orientation study (pi/4..pi/2) for each
//! mechanism, grid only and with the Nelder-Mead refinement, the candidate geometries per
//! orientation, and the cost per candidate; then a 0..pi/2 sweep of 33 orientations.
//! Target: the five-orientation study in under a second.

use std::f64::consts::{FRAC_PI_2, PI};
use std::time::Instant;

use corner::{corner_multiplier, CornerModel, Options, Specimen};

/// Minimum wall time of `f` over repetitions filling about `budget` s.
fn time_it(budget: f64, mut f: impl FnMut()) -> f64 {
    let mut best = f64::INFINITY;
    let start = Instant::now();
    let mut n = 0;
    while n < 3 || (start.elapsed().as_secs_f64() < budget && n < 1000) {
        let t0 = Instant::now();
        f();
        best = best.min(t0.elapsed().as_secs_f64());
        n += 1;
    }
    best
}

/// The study of `model` over `alphas`: candidate geometries per orientation, those evaluated
/// over all orientations, and the best wall time of the whole study (s) within `budget` s.
fn study(model: &CornerModel, alphas: &[f64], budget: f64) -> (u64, u64, f64) {
    let candidates = corner_multiplier(model, alphas[0]).unwrap().candidates;
    let evaluated: u64 = alphas
        .iter()
        .map(|&a| corner_multiplier(model, a).unwrap().evaluated)
        .sum();
    let t = time_it(budget, || {
        for &a in alphas {
            std::hint::black_box(corner_multiplier(model, a).unwrap());
        }
    });
    (candidates, evaluated, t)
}

fn main() {
    let alphas: Vec<f64> = (4..=8).map(|i| PI * f64::from(i) / 16.0).collect();
    println!("five-orientation study (pi/4..pi/2), paper specimen, best of repeated runs");
    println!(
        "{:>4} {:>4} {:>8} {:>14} {:>16} {:>12} {:>14}",
        "m", "k", "refine", "candidates/α", "evaluated (5 α)", "study (ms)", "ns/candidate"
    );
    for (m, k) in [(1, 0.3), (1, 0.6), (0, 0.3)] {
        for refine in [false, true] {
            let o = Options {
                refine,
                ..Options::default()
            };
            let model = CornerModel::new(Specimen::paper(), m, k, o).unwrap();
            let (candidates, evaluated, t) = study(&model, &alphas, 1.0);
            println!(
                "{:>4} {:>4} {:>8} {:>14} {:>16} {:>12.2} {:>14.2}",
                m,
                k,
                refine,
                candidates,
                evaluated,
                1e3 * t,
                1e9 * t / (5.0 * candidates as f64)
            );
        }
    }
    let model = CornerModel::paper(1, 0.3).unwrap();
    let t = time_it(1.0, || {
        for i in 0..=32 {
            let a = FRAC_PI_2 * f64::from(i) / 32.0;
            std::hint::black_box(corner_multiplier(&model, a).unwrap());
        }
    });
    println!(
        "sweep of 33 orientations over 0..pi/2 (m = 1, k = 0.3, refined): {:.1} ms",
        1e3 * t
    );
    // A larger corner: 18 courses, 14 blocks per wall (about 30x the candidates).
    let big = Specimen {
        courses: 18,
        blocks_x: 14,
        blocks_y: 14,
        ..Specimen::paper()
    };
    let o = Options {
        refine: false,
        ..Options::default()
    };
    let model = CornerModel::new(big, 1, 0.3, o).unwrap();
    let (candidates, evaluated, t) = study(&model, &alphas, 2.0);
    println!(
        "18 courses x 14 blocks per wall, grid only: {} candidates per orientation, {} evaluated over five orientations, five orientations {:.1} ms ({:.2} ns/candidate)",
        candidates,
        evaluated,
        1e3 * t,
        1e9 * t / (5.0 * candidates as f64)
    );
}
