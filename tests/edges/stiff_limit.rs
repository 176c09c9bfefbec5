//! kn -> infinity: the flexible laws tend to rigid solutions.

use rocking::dynamics::{GroundInput, Simulator};
use rocking::Params;

use rocking::model::{LawKind, MassKind, ShapeKind};
use rocking::Model;

/// Turning points below this rotation (rad) are not recorded.
pub(crate) const PEAK_MIN: f64 = 1e-3;

/// What a run did: impacts (time, omega after), turning points of theta
/// (time, theta where omega = 0), overturning time.
#[derive(Debug, Default)]
pub(crate) struct Record {
    pub(crate) impacts: Vec<(f64, f64)>,
    pub(crate) peaks: Vec<(f64, f64)>,
    pub(crate) overturned: Option<f64>,
}

/// Runs `m` from `(theta0, 0)` to `t_end` under the ground motion `ag`
/// sampled every `dt` and linear in between (the FMU's input), event by
/// event; turning points by bisection on saved states.
pub(crate) fn trace(
    m: Model,
    rtol: f64,
    theta0: f64,
    ag: &dyn Fn(f64) -> f64,
    dt: f64,
    t_end: f64,
) -> Record {
    let sim = Simulator::new(m, rtol);
    let mut st = sim.initial_state(theta0, 0.0);
    let mut rec = Record::default();
    let n = (t_end / dt).round() as usize;
    for k in 0..n {
        let (ta, tb) = (k as f64 * dt, (k + 1) as f64 * dt);
        let (a0, a1) = (ag(ta), ag(tb));
        let dag = (a1 - a0) / dt;
        let input = |t: f64| GroundInput {
            ag: a0 + dag * (t - ta),
            dag,
        };
        while st.t < tb && !st.overturned {
            let prev = st;
            let now = input(st.t);
            let ev = sim.advance_to_event(&mut st, tb, now);
            // (not the trembling of a flexible body in its contact zone)
            if prev.omega * st.omega < 0.0 && prev.theta.abs().max(st.theta.abs()) > PEAK_MIN {
                // a turning point in (prev.t, st.t), before any impact
                let (mut lo, mut hi) = (prev.t, st.t);
                let mut at = prev;
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if mid <= lo || mid >= hi {
                        break;
                    }
                    let mut s = prev;
                    sim.advance(&mut s, mid, input(prev.t));
                    if s.omega * prev.omega > 0.0 {
                        lo = mid;
                        at = s;
                    } else {
                        hi = mid;
                    }
                }
                rec.peaks.push((at.t, at.theta));
            }
            if ev.zero_crossings > 0 {
                rec.impacts.push((st.t, st.omega));
            }
            if let Some(t) = ev.overturned_at {
                rec.overturned = Some(t);
            }
        }
        if st.overturned {
            break;
        }
    }
    rec
}

/// The default block (0.5 x 1 x 2.5 m, 1800 kg/m³) with a law.
pub(crate) fn block(law: LawKind, kn: f64, fm: f64) -> Params {
    Params {
        interface: law,
        kn,
        fm,
        ..Params::default()
    }
}

/// The rigid block that a rigid-plastic interface (kn -> inf at finite fm)
/// makes of `p`: for phi > 0 the reaction acts at `c = af_limit` from the
/// toe (docs/model.md §2: the weight carried at fm over [0, alim], af = alim/2),
/// so the body rocks rigidly about a pivot at c: half-width `b - c`, the
/// same `hG`, `Ic` and weight, `I = Ic + m ((b - c)² + hG²)` constant; the
/// restitution stays that of the real block.
pub(crate) fn rigid_plastic_equivalent(p: &Params) -> Params {
    let m = p.build().unwrap();
    let c = m.interface.af_limit();
    let b = &m.body;
    Params {
        shape: ShapeKind::SolidRectangle,
        b: 2.0 * (b.b - c),
        l: p.l,
        mass_model: MassKind::Lumped,
        w: b.weight,
        hg: b.hg,
        ic: b.ic,
        interface: LawKind::Rigid,
        restitution: rocking::Restitution::Given,
        eta: m.eta,
        ..*p
    }
}

/// The features compared: free rocking: the first and second impact
/// times and the turning points after the first and second impacts;
/// forced: the first turning point (rotation, time) and the first impact
/// time. Not the angular velocity at theta = 0:
/// a flexible interface passes theta = 0 about the point under G, with
/// `I(0) = Ic + m hG²` instead of `IO`, so even in the limit its omega
/// there is `sqrt(IO / I(0))` times the rigid one (1.5 % for this block)
/// at the same kinetic energy.
pub(crate) fn features(r: &Record, free: bool) -> Vec<f64> {
    let imp = |i: usize| r.impacts.get(i).map_or(f64::NAN, |x| x.0);
    let peak = |i: usize| r.peaks.get(i).copied().unwrap_or((f64::NAN, f64::NAN));
    if free {
        vec![imp(0), imp(1), peak(0).1, peak(1).1]
    } else {
        vec![peak(0).1, peak(0).0, imp(0)]
    }
}

pub(crate) fn difference(a: &Record, b: &Record, free: bool) -> f64 {
    features(a, free)
        .iter()
        .zip(features(b, free))
        .map(|(x, y)| ((x - y) / y).abs())
        .fold(0.0, |m, d| {
            if d.is_nan() || m.is_nan() {
                f64::NAN
            } else {
                m.max(d)
            }
        })
}

/// Least-squares slope of log(e) against log(kn).
pub(crate) fn slope(kn: &[f64], e: &[f64]) -> f64 {
    let x: Vec<f64> = kn.iter().map(|k| k.ln()).collect();
    let y: Vec<f64> = e.iter().map(|v| v.ln()).collect();
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(&y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx) * (a - mx)).sum();
    sxy / sxx
}

pub(crate) const RTOL_EDGE: f64 = 1e-11;

/// One-cycle sine pulse of 0.6 s, 2.5 g tan(alpha) of the default block
/// (the same for every law and reference).
pub(crate) fn pulse(t: f64) -> f64 {
    // tan(alpha) = b / hG = 0.25 / 1.25
    let amp = 2.5 * 9.81 * 0.2;
    if t < 0.6 {
        -amp * (2.0 * std::f64::consts::PI * t / 0.6).sin()
    } else {
        0.0
    }
}

pub(crate) fn run_case(p: &Params, free: bool) -> Record {
    let m = p.build().unwrap();
    if free {
        trace(m, RTOL_EDGE, 0.1, &|_| 0.0, 0.05, 3.0)
    } else {
        trace(m, RTOL_EDGE, 0.0, &pulse, 5e-3, 2.0)
    }
}

/// kn from 1e7 to 1e16 Pa/m on the default block, free rocking released at
/// 0.1 rad and a one-cycle sine pulse from rest:
/// - elastic: the difference to the rigid (Housner) solution falls
///   monotonically, like kn^-0.5 in free rocking (af ~ a/3 with
///   a ~ (kn theta)^-1/2) and like kn^-0.39 after the pulse (the flexible body
///   lifts off gradually);
/// - crushing at fm = 1 MPa: the limit is not Housner but the rigid block
///   rocking about c = af_limit (rigid-plastic interface); the difference to
///   it falls like kn^-1 in free rocking (af - c ~ a1² with a1 = fm/(kn
///   theta)), kn^-0.6 after the pulse, while the difference to Housner
///   levels off at that of the two rigid solutions (4 % and 7 %).
#[test]
pub(crate) fn stiff_interfaces_tend_to_rigid_solutions() {
    let kns = [1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16];
    let fm = 1e6;
    // (free, elastic rate range, final level; crushing rate range, final
    // level; Housner plateau of the crushing law)
    let expect = [
        (true, (0.45, 0.55), 1.5e-5, (0.95, 1.05), 2e-9, 0.03),
        (false, (0.33, 0.45), 1.5e-3, (0.5, 0.7), 1e-4, 0.06),
    ];
    for (free, el_rate, el_level, cr_rate, cr_level, plateau) in expect {
        let case = if free {
            "free rocking from 0.1 rad"
        } else {
            "one-cycle sine pulse 2.5 g tan(alpha), 0.6 s"
        };
        let rigid = run_case(&block(LawKind::Rigid, 0.0, 0.0), free);
        let equiv = run_case(
            &rigid_plastic_equivalent(&block(LawKind::ElastoPlastic, 1e9, fm)),
            free,
        );
        let (mut e_el, mut e_cr, mut e_cr_h) = (Vec::new(), Vec::new(), Vec::new());
        for &kn in &kns {
            let r = run_case(&block(LawKind::Elastic, kn, f64::INFINITY), free);
            e_el.push(difference(&r, &rigid, free));
            let r = run_case(&block(LawKind::ElastoPlastic, kn, fm), free);
            e_cr.push(difference(&r, &equiv, free));
            e_cr_h.push(difference(&r, &rigid, free));
        }
        let rigid_vs_equiv = difference(&equiv, &rigid, free);
        eprintln!(
            "{case}: rigid {:?}, rigid-plastic {:?}",
            features(&rigid, free),
            features(&equiv, free)
        );
        eprintln!("| kn (Pa/m) | elastic vs Housner | crushing 1 MPa vs rigid-plastic | crushing vs Housner |");
        for (i, kn) in kns.iter().enumerate() {
            eprintln!(
                "| {kn:.0e} | {:.2e} | {:.2e} | {:.2e} |",
                e_el[i], e_cr[i], e_cr_h[i]
            );
        }
        let n = kns.len();
        let (p_el, p_cr) = (
            -slope(&kns[n - 4..], &e_el[n - 4..]),
            -slope(&kns[n - 4..], &e_cr[n - 4..]),
        );
        eprintln!("rates over 1e13..1e16: elastic kn^-{p_el:.3}, crushing kn^-{p_cr:.3}; rigid-plastic vs Housner {rigid_vs_equiv:.3e}");
        for w in e_el.windows(2).chain(e_cr.windows(2)) {
            assert!(w[1] < w[0], "{case}: not monotone: {e_el:?} {e_cr:?}");
        }
        assert!(
            el_rate.0 < p_el && p_el < el_rate.1,
            "{case}: elastic rate {p_el}"
        );
        assert!(
            cr_rate.0 < p_cr && p_cr < cr_rate.1,
            "{case}: crushing rate {p_cr}"
        );
        assert!(e_el[n - 1] < el_level, "{case}: elastic {:e}", e_el[n - 1]);
        assert!(e_cr[n - 1] < cr_level, "{case}: crushing {:e}", e_cr[n - 1]);
        // not Housner at finite fm: the difference stays that of the two
        // rigid solutions
        assert!(rigid_vs_equiv > plateau, "{case}: {rigid_vs_equiv}");
        assert!(
            (e_cr_h[n - 1] - rigid_vs_equiv).abs() < 0.05 * rigid_vs_equiv,
            "{case}: {} vs {rigid_vs_equiv}",
            e_cr_h[n - 1]
        );
    }
}
