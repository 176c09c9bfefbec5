//! `sin` and `cos` of the rotation together, for the equation of motion.
//!
//! The right-hand side needs both at every evaluation, at rotations below
//! `thetaOv < alpha`, mostly a few hundredths of a radian. Two calls to the
//! platform's libm cost about a sixth of an integrator step and differ in
//! the last bit between platforms (glibc, msvcrt); their Taylor series,
//! summed here in one pass, are faithful (within one ulp, checked against
//! libm in the tests) and the same on every platform.

/// Below this `|x|` (rad) the series are used; above it, libm.
const SERIES_MAX: f64 = 0.8;

/// `(sin x, cos x)`.
#[inline(always)]
pub(crate) fn sin_cos(x: f64) -> (f64, f64) {
    if x.abs() > SERIES_MAX {
        return x.sin_cos();
    }
    // sin x = x + x³ P(x²), cos x = 1 + x² Q(x²), Taylor to x^17 and x^16:
    // the first omitted terms, x^19/19! and x^20/20!, are below 1.7e-19 of
    // the result at |x| = 0.8.
    const S: [f64; 8] = [
        -1.0 / 6.0,
        1.0 / 120.0,
        -1.0 / 5040.0,
        1.0 / 362_880.0,
        -1.0 / 39_916_800.0,
        1.0 / 6_227_020_800.0,
        -1.0 / 1_307_674_368_000.0,
        1.0 / 355_687_428_096_000.0,
    ];
    const C: [f64; 8] = [
        -1.0 / 2.0,
        1.0 / 24.0,
        -1.0 / 720.0,
        1.0 / 40_320.0,
        -1.0 / 3_628_800.0,
        1.0 / 479_001_600.0,
        -1.0 / 87_178_291_200.0,
        1.0 / 20_922_789_888_000.0,
    ];
    let x2 = x * x;
    let (mut p, mut q) = (S[7], C[7]);
    for k in (0..7).rev() {
        p = S[k] + x2 * p;
        q = C[k] + x2 * q;
    }
    (x + x * x2 * p, 1.0 + x2 * q)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Units in the last place between `a` and the correctly rounded `b`
    /// (libm's result, itself within an ulp).
    fn ulps(a: f64, b: f64) -> f64 {
        (a - b).abs() / (b.abs() * f64::EPSILON)
    }

    #[test]
    fn series_within_one_ulp_of_libm_over_their_range() {
        let mut worst = (0.0f64, 0.0f64);
        for i in 0..=400_000 {
            let x = SERIES_MAX * (i as f64 / 400_000.0);
            for x in [x, -x, x * 1e-3, x * 1e-9] {
                let (s, c) = sin_cos(x);
                if x != 0.0 {
                    worst.0 = worst.0.max(ulps(s, x.sin()));
                }
                worst.1 = worst.1.max(ulps(c, x.cos()));
            }
        }
        assert!(worst.0 <= 1.0 && worst.1 <= 1.0, "ulps {worst:?}");
    }

    #[test]
    fn libm_beyond_the_series() {
        for x in [0.81, 1.2, -1.5, 3.0] {
            assert_eq!(sin_cos(x), x.sin_cos());
        }
    }
}
