//! Base sections (docs/model.md §1) and the cumulative moments of their width
//! function (docs/model.md §2).
//!
//! `x` is measured along the rocking direction from the toe (`x = 0`) to the
//! heel (`x = D`). Every interface computation goes through
//! [`Shape::moments`], `S_k(x) = ∫_0^x s^k w(s) ds` for `k = 0, 1, 2`, which
//! is closed form for every shape, so one contact solve serves all of them.

/// A base section, symmetric about its centroid. All lengths in metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// Depth `b` (along the rocking direction, `B` in docs/model.md) and width `l` (`L`).
    SolidRectangle { b: f64, l: f64 },
    /// Box section: outer depth `b`, outer width `l`, wall thickness `t`.
    HollowRectangle { b: f64, l: f64, t: f64 },
    /// Disc of radius `ro`.
    SolidCircle { ro: f64 },
    /// Annulus of outer radius `ro` and inner radius `ri` (concentric).
    HollowCircle { ro: f64, ri: f64 },
}

impl Shape {
    /// Base depth `D` along the rocking direction, m.
    pub fn depth(&self) -> f64 {
        match *self {
            Shape::SolidRectangle { b, .. } | Shape::HollowRectangle { b, .. } => b,
            Shape::SolidCircle { ro } | Shape::HollowCircle { ro, .. } => 2.0 * ro,
        }
    }

    /// Section area `A`, m² (docs/model.md §1).
    pub fn area(&self) -> f64 {
        match *self {
            Shape::SolidRectangle { b, l } => b * l,
            Shape::HollowRectangle { b, l, t } => b * l - (b - 2.0 * t) * (l - 2.0 * t),
            Shape::SolidCircle { ro } => std::f64::consts::PI * ro * ro,
            Shape::HollowCircle { ro, ri } => std::f64::consts::PI * (ro * ro - ri * ri),
        }
    }

    /// Second moment `Is = ∫ (x - D/2)² w dx` about the centroidal axis
    /// parallel to the rocking axis, m⁴ (docs/model.md §1).
    pub fn second_moment(&self) -> f64 {
        match *self {
            Shape::SolidRectangle { b, l } => l * b.powi(3) / 12.0,
            Shape::HollowRectangle { b, l, t } => {
                (l * b.powi(3) - (l - 2.0 * t) * (b - 2.0 * t).powi(3)) / 12.0
            }
            Shape::SolidCircle { ro } => std::f64::consts::PI * ro.powi(4) / 4.0,
            Shape::HollowCircle { ro, ri } => {
                std::f64::consts::PI * (ro.powi(4) - ri.powi(4)) / 4.0
            }
        }
    }

    /// Width `w(x)` perpendicular to the rocking plane at `x` (docs/model.md §1), m.
    /// Zero outside `[0, D]`.
    pub fn width(&self, x: f64) -> f64 {
        let d = self.depth();
        if !(0.0..=d).contains(&x) {
            return 0.0;
        }
        match *self {
            Shape::SolidRectangle { l, .. } => l,
            Shape::HollowRectangle { b, l, t } => {
                if x <= t || x >= b - t {
                    l
                } else {
                    2.0 * t
                }
            }
            Shape::SolidCircle { ro } => chord(ro, x - ro),
            Shape::HollowCircle { ro, ri } => chord(ro, x - ro) - chord(ri, x - ro),
        }
    }

    /// Where the width has a kink or a square-root end inside the base
    /// (m from the toe): a hollow rectangle's flange edges (`w` jumps), a
    /// hollow circle's inner circle (`w'` is infinite); none on a solid
    /// section.
    pub fn width_breaks(&self) -> Option<[f64; 2]> {
        match *self {
            Shape::SolidRectangle { .. } | Shape::SolidCircle { .. } => None,
            Shape::HollowRectangle { b, t, .. } => Some([t, b - t]),
            Shape::HollowCircle { ro, ri } => Some([ro - ri, ro + ri]),
        }
    }

    /// Whether `w` is smooth (analytic) on `[lo, hi]`: no flange step of a
    /// hollow rectangle and no circle edge (square-root point) inside.
    pub fn is_smooth_on(&self, lo: f64, hi: f64) -> bool {
        let outside = |k: f64| k < lo || k > hi;
        match *self {
            Shape::SolidRectangle { .. } => true,
            Shape::HollowRectangle { b, t, .. } => outside(t) && outside(b - t),
            Shape::SolidCircle { ro } => outside(0.0) && outside(2.0 * ro),
            Shape::HollowCircle { ro, ri } => {
                outside(0.0) && outside(2.0 * ro) && outside(ro - ri) && outside(ro + ri)
            }
        }
    }

    /// Whether the expression of `w` that holds on `[p, q]` is analytic on
    /// `[p - margin, q + margin]`. Unlike [`Shape::is_smooth_on`] of the
    /// widened interval, a corner beside `[p, q]` is harmless when the
    /// expression on `[p, q]` does not break there: a hollow rectangle is a
    /// constant on each side of a flange step, and a ring is its outer chord
    /// alone beyond the hole's span (the inner chord's branch points
    /// `ro ± ri` bound only the span itself).
    fn analytic_around(&self, p: f64, q: f64, margin: f64) -> bool {
        let clear = |k: f64| k < p - margin || k > q + margin;
        match *self {
            Shape::SolidRectangle { .. } => true,
            Shape::HollowRectangle { .. } => self.is_smooth_on(p, q),
            Shape::SolidCircle { ro } => clear(0.0) && clear(2.0 * ro),
            Shape::HollowCircle { ro, ri } => {
                let beside_hole = q <= ro - ri || p >= ro + ri;
                clear(0.0) && clear(2.0 * ro) && (beside_hole || (clear(ro - ri) && clear(ro + ri)))
            }
        }
    }

    /// Moments of `[p, q]` about its start, `[L0, L1, L2] = ∫_p^q (x - p)^k w dx`.
    ///
    /// Mathematically `S_k(q) - S_k(p)` shifted to `p`; for a narrow zone far
    /// from the toe that difference cancels most digits (and the contact
    /// solve multiplies it by `kn theta`; `af'` takes the zone's central
    /// moment, a further difference, and lost up to 1.5e-7 relative on a
    /// ring beside its hole), so where the expression of `w` on the zone is
    /// analytic around it the zone is integrated directly by 8-point
    /// Gauss-Legendre instead: with the expression's nearest singular point
    /// at least 4 zone lengths away the rule's error is below 1e-18 relative.
    #[inline]
    pub fn zone_moments(&self, p: f64, q: f64) -> [f64; 3] {
        let sp = || {
            if p > 0.0 {
                self.moments(p)
            } else {
                [0.0; 3]
            }
        };
        self.zone_moments_from(p, q, sp, || self.moments(q))
    }

    /// [`zone_moments`](Self::zone_moments) for a caller that has the
    /// cumulative moments at the ends, `sp = moments(p)` (zero at `p = 0`)
    /// and `sq = moments(q)`: taken from them where the difference is
    /// used, not evaluated again.
    #[inline]
    pub fn zone_moments_from(
        &self,
        p: f64,
        q: f64,
        sp: impl FnOnce() -> [f64; 3],
        sq: impl FnOnce() -> [f64; 3],
    ) -> [f64; 3] {
        if q <= p {
            return [0.0; 3];
        }
        let l = q - p;
        if l < 0.05 * p && self.analytic_around(p, q, 4.0 * l) {
            let mut out = [0.0; 3];
            for (z, wt) in GAUSS8 {
                let y = 0.5 * l * (1.0 + z);
                let f = 0.5 * l * wt * self.width(p + y);
                out[0] += f;
                out[1] += f * y;
                out[2] += f * y * y;
            }
            return out;
        }
        let sq = sq();
        let sp = sp();
        let d = [sq[0] - sp[0], sq[1] - sp[1], sq[2] - sp[2]];
        [d[0], d[1] - p * d[0], d[2] - 2.0 * p * d[1] + p * p * d[0]]
    }

    /// Cumulative moments `[S0, S1, S2](x) = ∫_0^x s^k w(s) ds` about the toe
    /// (docs/model.md §2), with `x` clipped to `[0, D]`. Units m², m³, m⁴.
    #[inline]
    pub fn moments(&self, x: f64) -> [f64; 3] {
        let d = self.depth();
        let x = x.clamp(0.0, d);
        match *self {
            Shape::SolidRectangle { l, .. } => band(l, 0.0, x),
            Shape::HollowRectangle { b, l, t } => {
                // Webs of width 2t over the whole depth, plus the flanges' extra
                // (l - 2t) over [0, t] and [b - t, b].
                let web = band(2.0 * t, 0.0, x);
                let toe = band(l - 2.0 * t, 0.0, x.min(t));
                let heel = if x > b - t {
                    band(l - 2.0 * t, b - t, x)
                } else {
                    [0.0; 3]
                };
                [0, 1, 2].map(|k| web[k] + toe[k] + heel[k])
            }
            Shape::SolidCircle { ro } => disc_moments(ro, 0.0, x),
            Shape::HollowCircle { ro, ri } => {
                let outer = disc_moments(ro, 0.0, x);
                let inner = disc_moments(ri, ro - ri, x);
                [0, 1, 2].map(|k| outer[k] - inner[k])
            }
        }
    }
}

/// 8-point Gauss-Legendre nodes and weights on [-1, 1].
const GAUSS8: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_3, 0.101_228_536_290_376_26),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (-0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (0.960_289_856_497_536_3, 0.101_228_536_290_376_26),
];

/// Chord `2 sqrt(r² - u²)` of a circle of radius `r` at offset `u` from its centre.
fn chord(r: f64, u: f64) -> f64 {
    if u.abs() >= r {
        0.0
    } else {
        2.0 * ((r - u) * (r + u)).sqrt()
    }
}

/// Moments `∫_p^q s^k c ds` of a band of constant width `c`.
#[inline]
fn band(c: f64, p: f64, q: f64) -> [f64; 3] {
    [
        c * (q - p),
        c * (q * q - p * p) / 2.0,
        c * (q * q * q - p * p * p) / 3.0,
    ]
}

/// Toe moments `∫_0^x s^k w(s) ds` of a disc of radius `r` whose leftmost
/// point is at `s = e` (so its centre is at `e + r`).
///
/// With `y = s - e = r (1 - cos φ)` the width is `2 r sin φ` and
/// `∫ y^k w ds = 2 r^(k+2) G_k(β)`, `G_k(β) = ∫_0^β (1 - cos φ)^k sin²φ dφ`,
/// where `β = 2 asin(sqrt(y/2r))`. This is docs/model.md §2's circle formula in
/// the variable `φ`, which keeps full relative precision for thin segments
/// (large rotations): the `u Q + R² asin(u/R) + π R²/2` form loses digits to
/// cancellation there. Moments about `s = 0` follow by the binomial shift
/// `s = e + y`, a sum of non-negative terms.
#[inline]
fn disc_moments(r: f64, e: f64, x: f64) -> [f64; 3] {
    let y = (x - e).clamp(0.0, 2.0 * r);
    if y <= 0.0 {
        return [0.0; 3];
    }
    let q = y / (2.0 * r);
    let g = segment_integrals(q);
    let r2 = r * r;
    let t0 = 2.0 * r2 * g[0];
    let t1 = 2.0 * r2 * r * g[1];
    let t2 = 2.0 * r2 * r2 * g[2];
    [t0, e * t0 + t1, e * e * t0 + 2.0 * e * t1 + t2]
}

/// Trigonometric-polynomial coefficients `c_j` of the integrands
/// `(1 - cos φ)^k sin²φ = Σ_j c_j cos(jφ)`, k = 0, 1, 2.
const TRIG: [[f64; 5]; 3] = [
    [0.5, 0.0, -0.5, 0.0, 0.0],
    [0.5, -0.25, -0.5, 0.25, 0.0],
    [0.625, -0.5, -0.5, 0.5, -0.125],
];

/// Number of Taylor terms used below `β < SERIES_BETA`.
const SERIES_TERMS: usize = 16;
/// Below this half-angle the integrals are summed as Taylor series in β
/// (all low orders cancel exactly in the closed form); above it the closed
/// form's terms are no larger than the result, so no digits are lost.
const SERIES_BETA: f64 = 1.3;

/// Taylor coefficients of `G_k(β) = Σ_n T[k][n] β^(2(n+k+1)+1)`:
/// `T = (-1)^m Σ_j c_j j^(2m) / (2m+1)!` with `m = n + k + 1` (lower orders
/// vanish since the integrand is `O(φ^(2k+2))`).
const SERIES: [[f64; SERIES_TERMS]; 3] = series_coefficients();

const fn series_coefficients() -> [[f64; SERIES_TERMS]; 3] {
    let mut out = [[0.0; SERIES_TERMS]; 3];
    let mut k = 0;
    while k < 3 {
        let mut n = 0;
        while n < SERIES_TERMS {
            let m = n + k + 1;
            // (2m+1)!
            let mut fact = 1.0;
            let mut i = 2;
            while i <= 2 * m + 1 {
                fact *= i as f64;
                i += 1;
            }
            let mut sum = 0.0;
            let mut j = 1;
            while j < 5 {
                let mut p = 1.0;
                let mut e = 0;
                while e < 2 * m {
                    p *= j as f64;
                    e += 1;
                }
                sum += TRIG[k][j] * p;
                j += 1;
            }
            out[k][n] = if m % 2 == 0 { sum / fact } else { -sum / fact };
            n += 1;
        }
        k += 1;
    }
    out
}

/// `[G_0, G_1, G_2](β)` for the segment of relative height `q = y/(2r)`,
/// `β = 2 asin(sqrt q)`.
#[inline]
fn segment_integrals(q: f64) -> [f64; 3] {
    let q = q.clamp(0.0, 1.0);
    let sh = q.sqrt(); // sin(β/2)
    let beta = 2.0 * sh.asin();
    if beta < SERIES_BETA {
        let b2 = beta * beta;
        let b4 = b2 * b2;
        let b8 = b4 * b4;
        let b16 = b8 * b8;
        // Estrin's scheme: short dependency chains for the three series
        let estrin = |c: &[f64; SERIES_TERMS]| {
            let p: [f64; 8] = std::array::from_fn(|i| c[2 * i] + c[2 * i + 1] * b2);
            let q: [f64; 4] = std::array::from_fn(|i| p[2 * i] + p[2 * i + 1] * b4);
            let r = [q[0] + q[1] * b8, q[2] + q[3] * b8];
            r[0] + r[1] * b16
        };
        // leading powers β^3, β^5, β^7
        let l0 = beta * b2;
        [
            estrin(&SERIES[0]) * l0,
            estrin(&SERIES[1]) * l0 * b2,
            estrin(&SERIES[2]) * l0 * b4,
        ]
    } else {
        let s1 = 2.0 * (q * (1.0 - q)).sqrt(); // sin β
        let c1 = 1.0 - 2.0 * q; // cos β
        let s2 = 2.0 * s1 * c1;
        let c2 = c1 * c1 - s1 * s1;
        let s3 = s2 * c1 + c2 * s1;
        let c3 = c2 * c1 - s2 * s1;
        let s4 = s3 * c1 + c3 * s1;
        let sj = [beta, s1, s2 / 2.0, s3 / 3.0, s4 / 4.0];
        let mut out = [0.0; 3];
        for (k, c) in TRIG.iter().enumerate() {
            out[k] = c.iter().zip(sj.iter()).map(|(c, s)| c * s).sum();
        }
        out
    }
}
