//! What the corner tests share.
// Each test file uses only some of these.
#![allow(dead_code)]

/// Uniform numbers in [0, 1) from a 64-bit linear congruential generator started at `seed`.
/// Hand-written rather than a random-number crate: the sampled corners and geometries must be
/// the same on every platform and with every dependency version, so a failure names a case
/// that can be run again.
pub fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 33) as f64 / f64::from(1u32 << 31)
    }
}

/// A macroblock at hinge level `z1` drawn from `next` in the order X3 X1 X2 Y3 Y2 Y1: each
/// wall's base in [v, base_max], green top in [base, green_max], red width in `red` (m);
/// `pick(r, lo, hi)` turns a draw r in [0, 1) into a length in [lo, hi].
pub fn draw_geometry(
    next: &mut impl FnMut() -> f64,
    pick: impl Fn(f64, f64, f64) -> f64,
    z1: f64,
    v: f64,
    base_max: f64,
    green_max: f64,
    red: (f64, f64),
) -> corner::Geometry {
    let mut wall = || {
        let base = pick(next(), v, base_max);
        let green = pick(next(), base, green_max);
        (green, pick(next(), red.0, red.1), base)
    };
    let (x1, x2, x3) = wall();
    let (y2, y1, y3) = wall();
    corner::Geometry {
        x1,
        x2,
        x3,
        y1,
        y2,
        y3,
        z1,
    }
}

/// The default options without the Nelder-Mead refinement: the exact grid search alone.
pub fn grid_only() -> corner::Options {
    corner::Options {
        refine: false,
        ..corner::Options::default()
    }
}
