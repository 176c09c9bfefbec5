//! fm -> W/A: the crushing limit.

use rocking::model::LawKind;
use rocking::Params;

use crate::stiff_limit::slope;

/// `af(phi)` of a solid rectangle (depth D, width L) under weight W on an
/// elasto-plastic bed (kn, fm) with `W/A < fm < 2 W/A` (crushing starts in
/// full contact), in closed form from docs/model.md §2, written with
/// `q = W/L` (load per unit width) and `k = kn phi`:
/// - full contact, elastic (`phi <= thetaC = 2 (fm - W/A)/(kn D)`):
///   `af = D/2 - kn phi Is / W`, `Is = L D³/12`;
/// - full contact with crushing (`thetaC < phi <= thetaJo`): the stress is
///   fm on `[0, xp]` and falls linearly (slope k) to `fm - k u` at the heel,
///   `u = D - xp`. Vertical equilibrium `fm D - k u²/2 = q` gives
///   `u = sqrt(2 (fm D - q) / k)`; the moment is that of fm over D less the
///   missing triangle (area `k u²/2`, centroid `D - u/3`):
///   `af = [fm D²/2 - (fm D - q)(D - u/3)] / q`; the heel opens when
///   `k u = fm`: `thetaJo = fm² / (2 kn D (fm - W/A))`;
/// - partial contact with crushing (`phi > thetaJo`): docs/model.md's
///   `a1 = fm/k`, `alim = q/fm`, `a2 = alim - a1/2`,
///   `af = [a2²/2 + (a1/2)(a2 + a1/3)] / (a2 + a1/2) = alim/2 + a1²/(24 alim)`.
struct CrushingRectangle {
    d: f64,
    q: f64,
    kn: f64,
    fm: f64,
    is_over_w: f64,
}

impl CrushingRectangle {
    fn theta_c(&self) -> f64 {
        2.0 * (self.fm - self.q / self.d) / (self.kn * self.d)
    }
    fn theta_jo(&self) -> f64 {
        self.fm * self.fm / (2.0 * self.kn * self.d * (self.fm - self.q / self.d))
    }
    fn af(&self, phi: f64) -> f64 {
        let (d, q, fm) = (self.d, self.q, self.fm);
        let k = self.kn * phi;
        if phi <= self.theta_c() {
            d / 2.0 - k * self.is_over_w
        } else if phi <= self.theta_jo() {
            let u = (2.0 * (fm * d - q) / k).sqrt();
            (fm * d * d / 2.0 - (fm * d - q) * (d - u / 3.0)) / q
        } else {
            let a1 = fm / k;
            let alim = q / fm;
            let a2 = alim - a1 / 2.0;
            (a2 * a2 / 2.0 + (a1 / 2.0) * (a2 + a1 / 3.0)) / (a2 + a1 / 2.0)
        }
    }
    /// `b - af` in the full-contact crushing regime without cancellation:
    /// with `eps = 1 - q/(fm D)`, `b - af = eps (D/2 - u/3) / (1 - eps)`.
    fn lever(&self, phi: f64, eps: f64) -> f64 {
        if phi > self.theta_c() && phi <= self.theta_jo() {
            let u = (2.0 * self.fm * self.d * eps / (self.kn * phi)).sqrt();
            eps * (self.d / 2.0 - u / 3.0) / (1.0 - eps)
        } else {
            self.d / 2.0 - self.af(phi)
        }
    }
}

#[test]
fn the_capacity_vanishes_as_fm_tends_to_w_over_a() {
    // Default block: D = B = 0.5 m, L = 1 m, hG = 1.25 m, W/A = rho g H.
    // Solid rectangle: b - af_limit = D/2 - alim/2 = (D/2) eps exactly, with
    // eps = 1 - W/(fm A); MR = W hW, hW = (b - af) cos(phi) - hG sin(phi).
    // In full contact with crushing (where thetaOv lies once eps is small,
    // since thetaJo ~ 1/eps), with phi = eps psi and fm -> W/A:
    //   hW / eps -> D/2 - (1/3) sqrt(2 D (W/A) / (kn psi)) - hG psi,
    // so thetaOv ~ psi* eps (the root) and MR_peak ~ W g_max eps (the
    // maximum over psi >= 2 (W/A)/(kn D)): all three vanish linearly.
    let base = Params {
        interface: LawKind::ElastoPlastic,
        ..Params::default()
    };
    let (d, l, hg) = (base.b, base.l, base.h / 2.0);
    let w_over_a = base.rho * base.g * base.h;
    let weight = w_over_a * d * l;
    let kn = base.kn;
    let g_lim = |psi: f64| d / 2.0 - (2.0 * d * w_over_a / (kn * psi)).sqrt() / 3.0 - hg * psi;
    let psi_c = 2.0 * w_over_a / (kn * d);
    let psi_star = bisect(|psi| -g_lim(psi), psi_c, d / (2.0 * hg));
    let psi_m = ((2.0 * d * w_over_a / kn).sqrt() / (6.0 * hg))
        .powf(2.0 / 3.0)
        .max(psi_c);
    let mr_lim = weight * g_lim(psi_m);
    eprintln!("limits: thetaOv/eps -> {psi_star:.6}, MR_peak/eps -> {mr_lim:.4} N m (at phi/eps = {psi_m:.3e})");
    eprintln!("| eps = 1 - W/(fm A) | fm (Pa) | b - af_limit (m) | rel. error | thetaOv (rad) | rel. error | thetaOv/eps | MR peak (N m) | rel. error | MR peak/eps | thetaJo rel. error |");
    let epss = [1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6];
    let (mut ov, mut mr, mut lev) = (Vec::new(), Vec::new(), Vec::new());
    for &eps in &epss {
        let fm = w_over_a / (1.0 - eps);
        let m = Params { fm, ..base }.build().unwrap();
        let body = m.body;
        assert!((body.weight / weight - 1.0).abs() < 1e-15);
        let cf = CrushingRectangle {
            d,
            q: weight / l,
            kn,
            fm,
            is_over_w: l * d.powi(3) / 12.0 / weight,
        };
        // thresholds
        assert!(
            (m.interface.theta_c() / cf.theta_c() - 1.0).abs() < 1e-9,
            "{eps}"
        );
        // thetaJo (where the heel opens, far beyond thetaOv here: 0.09 rad
        // at eps 1e-4, 8.8 rad at 1e-6) loses digits as eps -> 0: the
        // engine solves N(a = D) = W for the plastic edge xp with the
        // elastic zone u = D - xp ~ 2 D eps, and its moments about xp cancel
        // to second order (measured 2.8e-8 at eps 1e-5, 7e-6 at 1e-6).
        let jo_err = (m.interface.theta_jo() / cf.theta_jo() - 1.0).abs();
        if eps >= 1e-4 {
            assert!(jo_err < 1e-9, "{eps}: thetaJo {jo_err:e}");
        }
        // the lever of the plastic limit
        let lever_engine = body.b - m.interface.af_limit();
        let lever_closed = d / 2.0 * eps;
        assert!(
            (lever_engine / lever_closed - 1.0).abs() < 1e-8,
            "{eps}: {lever_engine} {lever_closed}"
        );
        // thetaOv: the root of the closed-form hW
        let hw = |phi: f64| cf.lever(phi, eps) * phi.cos() - hg * phi.sin();
        let ov_closed = bisect(|phi| -hw(phi), cf.theta_c(), body.alpha);
        // The contact solve leaves af with an absolute error of a few
        // 1e-12 m (its last step is a Taylor shift); the lever b - af is
        // (D/2) eps, so the relative error grows like 1e-11/eps (measured
        // 1.8e-5 at eps 1e-6, 2e-11 at 1e-5).
        let tol = (5e-11 / eps).max(1e-9);
        assert!(
            (m.theta_ov / ov_closed - 1.0).abs() < tol,
            "{eps}: thetaOv {} vs {ov_closed}",
            m.theta_ov
        );
        // peak restoring moment: golden section on the closed form, the
        // engine's MR at the same rotation and its own maximum nearby
        let (mut a, mut b) = (cf.theta_c(), ov_closed);
        let r = 0.5 * (5f64.sqrt() - 1.0);
        for _ in 0..200 {
            let (x1, x2) = (b - r * (b - a), a + r * (b - a));
            if hw(x1) > hw(x2) {
                b = x2;
            } else {
                a = x1;
            }
        }
        let phi_peak = 0.5 * (a + b);
        let mr_closed = weight * hw(phi_peak);
        let mr_engine = m.restoring_moment(phi_peak).0;
        assert!(
            (mr_engine / mr_closed - 1.0).abs() < tol.max(1e-7),
            "{eps}: MR {mr_engine} vs {mr_closed}"
        );
        // no larger MR anywhere on a fine grid (the engine's own maximum)
        let grid_max = (1..=4000)
            .map(|i| m.restoring_moment(m.theta_ov * i as f64 / 4000.0).0)
            .fold(0.0, f64::max);
        assert!(
            grid_max <= mr_closed * (1.0 + tol.max(1e-7)),
            "{eps}: {grid_max} > {mr_closed}"
        );
        eprintln!(
            "| {eps:.0e} | {fm:.6e} | {lever_engine:.6e} | {:.1e} | {:.6e} | {:.1e} | {:.6} | {mr_engine:.6e} | {:.1e} | {:.2} | {jo_err:.1e} |",
            (lever_engine / lever_closed - 1.0).abs(),
            m.theta_ov,
            (m.theta_ov / ov_closed - 1.0).abs(),
            m.theta_ov / eps,
            (mr_engine / mr_closed - 1.0).abs(),
            mr_engine / eps
        );
        ov.push(m.theta_ov);
        mr.push(mr_engine);
        lev.push(lever_engine);
    }
    let n = epss.len();
    // rates and limits where the engine is accurate (eps 1e-3..1e-5)
    let rate = |y: &[f64]| slope(&epss[n - 4..n - 1], &y[n - 4..n - 1]);
    let (p_ov, p_mr, p_lev) = (rate(&ov), rate(&mr), rate(&lev));
    eprintln!("rates over eps 1e-3..1e-5: thetaOv eps^{p_ov:.4}, MR_peak eps^{p_mr:.4}, b - af_limit eps^{p_lev:.4}");
    for p in [p_ov, p_mr, p_lev] {
        assert!((p - 1.0).abs() < 1e-3, "rate {p}");
    }
    for w in ov.windows(2).chain(mr.windows(2)).chain(lev.windows(2)) {
        assert!(w[1] < w[0]);
    }
    // the asymptotic constants (the next term is O(eps))
    let k = n - 2;
    assert!(
        (ov[k] / epss[k] / psi_star - 1.0).abs() < 1e-4,
        "{}",
        ov[k] / epss[k]
    );
    assert!(
        (mr[k] / epss[k] / mr_lim - 1.0).abs() < 1e-4,
        "{}",
        mr[k] / epss[k]
    );
}

/// Root of an increasing `f` on `[lo, hi]` by bisection.
fn bisect(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    for _ in 0..2000 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if f(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    0.5 * (lo + hi)
}
