//! First and second time derivatives of every output
//! (`Simulator::output_rates`) against independent references:
//!
//! - `Interface::second_derivatives` (`af''`, `a''`) against central
//!   differences of the contact solve's `af'` and `a` in `phi`, for every
//!   shape in every regime away from its kinks;
//! - every output's orders 1 and 2 against 5-point central differences
//!   (error O(h^4)) of the outputs sampled along actual trajectories, under
//!   a ground acceleration that is a line in time (`dag != 0`), for the
//!   rigid, elastic and crushing laws, both formulations, moving and at
//!   rest, at samples with no impact, regime change or rest in the stencil.
//!   The sampled values are those of `Simulator::outputs` for `theta`,
//!   `omega`, `theta''`, `af`, `contactLength`, `MR`; `Fx`, `Fz` are
//!   written here from their definition (docs/model.md §5), `Fx = m (ag +
//!   hg theta'' + s hg' omega²)`, `Fz = m (g + s hW theta'' + hW' omega²)`,
//!   with the levers of `Model::levers` and `hg' = hW - af' sin(phi)`,
//!   `hW' = -hg - af' cos(phi)`.
//!
//! Errors are relative to the largest magnitude of the same derivative
//! along the run; the tables print the measured worst cases.

mod support;

use rocking::dynamics::{GroundInput, Jet, Simulator, State};
use rocking::interface::Interface;
use rocking::{Formulation, Law, Params, Regime, Shape};
use support::{base, output_jets};

// ---------------------------------------------------------------- interface

/// Relative errors of `(af'', a'')` against 5-point central differences
/// (error O(h^4)) of `af'` and `a` in `phi` at `phi`, step `h = 1e-3 phi`,
/// each less the differences' own uncertainty (their change from step `2h`
/// to `h`: where `af'` is tiny, near full plasticity, the solve's rounding
/// in `af'` dominates the difference quotient); `None` near a kink (the
/// regime differs within the stencil, or the contact edge `a` or the
/// plastic edge `xp` is within `D/100` of a corner of the width: there the
/// contact solve's own `af'` carries rounding noise, ~1e-9 relative, that
/// the difference quotient amplifies).
fn curvature_error(it: &Interface, phi: f64) -> Option<(f64, f64)> {
    let d = it.depth();
    let corners: &[f64] = match *it.shape() {
        Shape::HollowRectangle { b, t, .. } => &[t, b - t],
        Shape::HollowCircle { ro, ri } => &[ro - ri, ro + ri],
        _ => &[],
    };
    let c = it.contact(phi);
    let xp = match it.law() {
        Law::ElastoPlastic { kn, fm } => c.a - fm / (kn * phi),
        _ => -1.0,
    };
    if corners
        .iter()
        .any(|&x| (c.a - x).abs() < 0.01 * d || (xp - x).abs() < 0.01 * d)
    {
        return None;
    }
    let fd = |h: f64| {
        let cs: Vec<_> = (-2..=2).map(|j| it.contact(phi + j as f64 * h)).collect();
        let d1 = |y: [f64; 5]| (-y[4] + 8.0 * y[3] - 8.0 * y[1] + y[0]) / (12.0 * h);
        let d2 =
            |y: [f64; 5]| (-y[4] + 16.0 * y[3] - 30.0 * y[2] + 16.0 * y[1] - y[0]) / (12.0 * h * h);
        let same = cs.iter().all(|x| x.regime == cs[2].regime);
        (
            same,
            d1(std::array::from_fn(|j| cs[j].daf)),
            d2(std::array::from_fn(|j| cs[j].a)),
        )
    };
    let h = 1e-3 * phi;
    let (same, af2_fd, a2_fd) = fd(h);
    let (same2, af2_fd2, a2_fd2) = fd(2.0 * h);
    if !(same && same2) {
        return None;
    }
    let (af2, a2) = it.second_derivatives(&c);
    let rel = |x: f64, r: f64, r2: f64, scale: f64| {
        ((x - r).abs() - (r - r2).abs()).max(0.0) / scale.max(f64::MIN_POSITIVE)
    };
    // scales: af'' against af'/phi, a'' against a/phi²
    Some((
        rel(af2, af2_fd, af2_fd2, c.daf.abs() / phi + af2_fd.abs()),
        if c.regime == Regime::FullContact || c.regime == Regime::FullCrushing {
            0.0
        } else {
            rel(a2, a2_fd, a2_fd2, c.a / (phi * phi) + a2_fd.abs())
        },
    ))
}

#[test]
fn second_derivatives_of_the_contact_match_differences() {
    let mut failures = Vec::new();
    println!("shape            law           regime   n  af'' err  a'' err");
    for (_, shape) in base::shapes() {
        let w = 2.0e4;
        let area = shape.area();
        let laws = [
            Law::Elastic { kn: 5e9 },
            Law::ElastoPlastic {
                kn: 5e9,
                fm: 3.0 * w / area,
            },
            Law::ElastoPlastic {
                kn: 5e9,
                fm: 1.3 * w / area,
            },
        ];
        for law in laws {
            let it = Interface::new(shape, law, w);
            let mut worst = [(0usize, 0.0f64, 0.0f64); 4];
            // log-spaced rotations through every regime up to 0.2 rad
            let first = 1e-3 * it.theta_jo().min(it.theta_c());
            let n = 400;
            for k in 0..=n {
                let phi = first * (0.2 / first).powf(k as f64 / n as f64);
                if let Some((e_af, e_a)) = curvature_error(&it, phi) {
                    let e = &mut worst[it.contact(phi).regime as usize];
                    e.0 += 1;
                    e.1 = e.1.max(e_af);
                    e.2 = e.2.max(e_a);
                }
            }
            for (r, (n, e_af, e_a)) in worst.iter().enumerate().filter(|x| x.1 .0 > 0) {
                let shape_name = format!("{shape:?}");
                let law_name = match law {
                    Law::Elastic { .. } => "elastic".to_string(),
                    Law::ElastoPlastic { fm, .. } => format!("fm = {:.1} W/A", fm * area / w),
                    Law::Rigid => "rigid".into(),
                };
                println!(
                    "{:<16} {law_name:<13} {r:6} {n:3}  {e_af:8.1e}  {e_a:8.1e}",
                    shape_name.split(' ').next().unwrap(),
                );
                // measured: <= 2e-9 (af''), 1e-9 (a'')
                if !(*e_af < 1e-7 && *e_a < 1e-7) {
                    failures.push(format!(
                        "{shape:?} {law:?} regime {r}: af'' error {e_af:e}, a'' error {e_a:e}"
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

// ---------------------------------------------------------------- trajectories

/// `Fx`, `Fz` from their definition (docs/model.md §5) at `st`, with
/// `theta''` from `Simulator::outputs`.
fn support_forces(sim: &Simulator, st: &State, ag: f64, theta_dd: f64) -> (f64, f64) {
    let m = &sim.model;
    let b = &m.body;
    if st.at_rest {
        return (b.mass * ag, b.weight);
    }
    let rigid = m.interface.law() == Law::Rigid;
    let s = if st.theta != 0.0 {
        st.theta.signum()
    } else if st.omega != 0.0 {
        st.omega.signum()
    } else {
        -ag.signum()
    };
    let phi = if rigid { s * st.theta } else { st.theta.abs() };
    let c = m.interface.contact(if rigid {
        phi.max(f64::MIN_POSITIVE)
    } else {
        phi
    });
    let l = m.levers(phi, &c);
    let (sp, cp) = phi.sin_cos();
    let dhg = l.hw - c.daf * sp;
    let dhw = -l.hg - c.daf * cp;
    let w2 = st.omega * st.omega;
    (
        b.mass * (ag + l.hg * theta_dd + s * dhg * w2),
        b.mass * (b.g + s * l.hw * theta_dd + dhw * w2),
    )
}

const NAMES: [&str; 8] = [
    "theta",
    "omega",
    "theta''",
    "af",
    "contactLength",
    "MR",
    "Fx",
    "Fz",
];

fn values(sim: &Simulator, st: &State, ag: f64) -> [f64; 8] {
    let o = sim.outputs(st, ag);
    let (fx, fz) = support_forces(sim, st, ag, o.theta_dd);
    [
        st.theta,
        st.omega,
        o.theta_dd,
        o.af,
        o.contact_length,
        o.mr,
        fx,
        fz,
    ]
}

/// `[order 1, order 2]` of every output.
type Orders12 = [[f64; 2]; 8];

#[derive(Clone, Copy)]
struct Case {
    name: &'static str,
    params: Params,
    /// Ground acceleration `ag0 + dag t`, m/s², m/s³.
    ag0: f64,
    dag: f64,
    /// Run length, s; finite-difference step, s.
    t_end: f64,
    h: f64,
}

/// Worst relative errors `[order 1, order 2]` per output along the run,
/// and the number of samples checked.
fn run_case(c: &Case) -> ([[f64; 2]; 8], usize, [usize; 4]) {
    let model = c.params.build().unwrap();
    let sim = Simulator::new(model, 1e-12);
    let ag = |t: f64| c.ag0 + c.dag * t;
    let mut st = sim.initial_state(c.params.theta0, c.params.omega0);
    let mut err = [[0.0f64; 2]; 8];
    let mut scale = [[0.0f64; 2]; 8];
    let mut regimes = [0; 4];
    let mut vmax = [0.0f64; 8];
    // (differences, analytic jets) per sample
    let mut diffs: Vec<(Orders12, [Jet; 8])> = Vec::new();
    let centres = 40;
    for k in 1..=centres {
        let tc = c.t_end * k as f64 / (centres + 1) as f64;
        let mut pts: Vec<(State, [f64; 8])> = Vec::new();
        for j in -2..=2 {
            let t = tc + j as f64 * c.h;
            let a0 = ag(st.t);
            sim.advance(&mut st, t, GroundInput { ag: a0, dag: c.dag });
            pts.push((st, values(&sim, &st, ag(t))));
        }
        if st.overturned {
            break;
        }
        let s0 = &pts[2].0;
        let regime = sim.outputs(s0, ag(tc)).regime;
        let clean = pts.iter().all(|(p, _)| {
            p.impacts == s0.impacts
                && p.at_rest == s0.at_rest
                && p.theta.signum() == s0.theta.signum()
                && sim.outputs(p, ag(p.t)).regime == regime
        });
        if !clean {
            continue;
        }
        regimes[(regime as usize).min(3)] += 1;
        let r = sim.output_rates(
            s0,
            GroundInput {
                ag: ag(tc),
                dag: c.dag,
            },
        );
        let a = output_jets(&r);
        let mut fd = [[0.0; 2]; 8];
        for (i, f) in fd.iter_mut().enumerate() {
            let y: Vec<f64> = pts.iter().map(|p| p.1[i]).collect();
            f[0] = (-y[4] + 8.0 * y[3] - 8.0 * y[1] + y[0]) / (12.0 * c.h);
            f[1] = (-y[4] + 16.0 * y[3] - 30.0 * y[2] + 16.0 * y[1] - y[0]) / (12.0 * c.h * c.h);
            // the values themselves are those sampled (Fx, Fz: the definition)
            assert!(
                (a[i][0] - y[2]).abs() <= 1e-9 * y[2].abs(),
                "{}: {} value {} against {}",
                c.name,
                NAMES[i],
                a[i][0],
                y[2]
            );
            vmax[i] = vmax[i].max(y[2].abs());
            for o in 0..2 {
                scale[i][o] = scale[i][o].max(a[i][o + 1].abs()).max(f[o].abs());
            }
        }
        diffs.push((fd, a));
    }
    // a floor for outputs that do not change (at rest): 1e-3 of the value per s^order
    for i in 0..8 {
        for sc in &mut scale[i] {
            *sc = sc.max(1e-3 * vmax[i]);
        }
    }
    for (fd, a) in &diffs {
        for i in 0..8 {
            for o in 0..2 {
                let sc = scale[i][o];
                let e = if sc > 0.0 {
                    (a[i][o + 1] - fd[i][o]).abs() / sc
                } else {
                    0.0
                };
                err[i][o] = err[i][o].max(e);
            }
        }
    }
    (err, diffs.len(), regimes)
}

fn block(law: rocking::model::LawKind, formulation: Formulation) -> Params {
    Params {
        interface: law,
        formulation,
        ..Params::default()
    }
}

#[test]
fn output_derivatives_match_differences_along_trajectories() {
    use rocking::model::LawKind::*;
    let mut cases = Vec::new();
    for f in [Formulation::ShiftingPivot, Formulation::Costa] {
        cases.push(Case {
            name: "rigid, moving",
            params: Params {
                theta0: 0.1,
                ..block(Rigid, f)
            },
            ag0: 0.3,
            dag: -0.4,
            t_end: 2.0,
            h: 1e-3,
        });
        cases.push(Case {
            name: "elastic, moving",
            params: Params {
                theta0: 0.08,
                ..block(Elastic, f)
            },
            ag0: 0.3,
            dag: -0.4,
            t_end: 2.0,
            h: 1e-5,
        });
        cases.push(Case {
            name: "crushing, partial",
            params: Params {
                theta0: 0.08,
                fm: 1e6,
                ..block(ElastoPlastic, f)
            },
            ag0: 0.3,
            dag: -0.4,
            t_end: 2.0,
            h: 1e-5,
        });
        cases.push(Case {
            name: "crushing, full",
            params: Params {
                theta0: 0.01,
                kn: 1e7,
                fm: 6e4,
                ..block(ElastoPlastic, f)
            },
            ag0: 0.1,
            dag: -0.1,
            t_end: 1.0,
            h: 1e-4,
        });
    }
    cases.push(Case {
        name: "rigid, at rest",
        params: block(Rigid, Formulation::ShiftingPivot),
        ag0: 0.5,
        dag: 0.7,
        t_end: 1.0,
        h: 1e-2,
    });
    let mut failures = Vec::new();
    for c in &cases {
        let (err, n, regimes) = run_case(c);
        println!(
            "{} ({:?}), h = {:e} s: {n} samples, regimes (full, partial, partial crushing, full crushing) {regimes:?}",
            c.name, c.params.formulation, c.h
        );
        for i in 0..8 {
            println!(
                "  {:<14} d1 {:8.1e}  d2 {:8.1e}",
                NAMES[i], err[i][0], err[i][1]
            );
            // measured worst: 2e-9 (order 1), 6e-7 (order 2), the
            // differences' own error (it falls as h^4 with the step, down
            // to the integration's and rounding's noise / h^order)
            if !(err[i][0] < 1e-8 && err[i][1] < 2e-6) {
                failures.push(format!("{}: {} errors {:?}", c.name, NAMES[i], err[i]));
            }
        }
        if n < 20 {
            failures.push(format!("{}: only {n} samples", c.name));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// A body at rest that `ag` sets moving: the rates at that instant are the
/// starting motion's. References: `outputs` for the values, and the motion
/// actually integrated from rest (`omega` and `Fx` 1 and 2 ms later) for
/// the derivatives, through the remainder of the jets' Taylor polynomials.
#[test]
fn rates_of_a_body_that_ag_sets_moving_from_rest() {
    use rocking::model::LawKind::*;
    for law in [Elastic, ElastoPlastic, Rigid] {
        let sim = Simulator::new(
            block(law, Formulation::ShiftingPivot).build().unwrap(),
            1e-13,
        );
        let ag = if law == Rigid {
            1.1 * sim.uplift_acceleration()
        } else {
            1.0
        };
        let input = GroundInput { ag, dag: 0.0 };
        let s0 = sim.initial_state(0.0, 0.0);
        assert!(s0.at_rest && !sim.held_at_rest(ag));
        let r = sim.output_rates(&s0, input);
        let o = sim.outputs(&s0, ag);
        assert_eq!(r.theta_dd[0], o.theta_dd, "{law:?}");
        assert_eq!((r.fx[0], r.fz[0]), (o.fx, o.fz), "{law:?}");
        assert!(o.theta_dd != 0.0);
        // theta' = omega = 0, omega' = theta'' at the start
        assert_eq!(r.theta[1], 0.0);
        assert_eq!(r.theta[2], o.theta_dd);
        assert_eq!(r.omega[1], o.theta_dd);
        let later = |h: f64| {
            let mut s = s0;
            sim.advance(&mut s, h, input);
            (s.omega, sim.outputs(&s, ag).fx)
        };
        // Taylor's polynomial of the jet against the integrated motion: the
        // remainder, relative to the polynomial's own terms, must be small
        // and grow like h² (absolute remainder O(h³): orders 1 and 2 right).
        let remainder = |h: f64| {
            let (w, f) = later(h);
            let w_jet = r.omega[0] + r.omega[1] * h + r.omega[2] * h * h / 2.0;
            let f_jet = r.fx[0] + r.fx[1] * h + r.fx[2] * h * h / 2.0;
            let w_terms = (r.omega[1] * h).abs() + (r.omega[2] * h * h / 2.0).abs();
            let f_terms = (r.fx[1] * h).abs() + (r.fx[2] * h * h / 2.0).abs();
            ((w - w_jet).abs() / w_terms, (f - f_jet).abs() / f_terms)
        };
        let (w1, f1) = remainder(1e-3);
        let (w2, f2) = remainder(2e-3);
        eprintln!("{law:?}: remainders omega {w1:e} {w2:e}, Fx {f1:e} {f2:e}");
        for (what, e1, e2) in [("omega", w1, w2), ("Fx", f1, f2)] {
            assert!(e1 < 1e-2, "{law:?}: {what} remainder {e1:e} at h = 1 ms");
            assert!(
                e2 / e1 > 3.0,
                "{law:?}: {what} remainder is not O(h^3): {e1:e}, {e2:e}"
            );
        }
    }
}
