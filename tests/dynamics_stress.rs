//! Stress: the corners of the parameter space and of the way the FMU drives
//! the integrator. `kn` from 1e6 to 1e15 Pa/m (raised where `kn Is > W hG`
//! requires it), `fm` from `1.01 W/A` to none, slenderness 0.01 to 0.6,
//! sizes 0.1 m to 100 m, communication steps 1e-5 s to 1 s, records up to
//! 1000 s, both formulations and every shape.
//!
//! Every run must end (each call reaches `t_end`, or stops at overturning
//! with `overturned_at` set), stay finite, never stall (a cap on the work of
//! any one call), and, in the quiet tail of the record (no ground motion),
//! never gain energy: `E = I(0) omega²/2` at successive zero crossings never
//! grows (`shiftingPivot` and rigid; `costa` is not conservative).

mod support;

use rocking::dynamics::{GroundInput, Simulator, State};
use rocking::model::{Formulation, LawKind, MassKind, Restitution, ShapeKind};
use rocking::{Law, Model, Params};
use std::time::Instant;
use support::lcg::Lcg;

#[derive(Clone, Copy, Debug)]
struct Case {
    shape: ShapeKind,
    /// height of the prism, m
    size: f64,
    alpha: f64,
    law: LawKind,
    kn: f64,
    /// fm as a multiple of W/A (infinite: no crushing)
    fm_ratio: f64,
    formulation: Formulation,
    /// ground motion peak over the uplift acceleration g tan(alpha)
    shaking: f64,
    /// shaking lasts this long, then the record is quiet
    shake_time: f64,
    record: f64,
    dt: f64,
}

/// A prism of height `size` and slenderness `alpha` on `shape`.
fn build(c: &Case) -> Model {
    let depth = c.size * c.alpha.tan(); // D / H = tan(alpha)
    let mut p = Params {
        shape: c.shape,
        mass_model: MassKind::Prism,
        h: c.size,
        rho: 2000.0,
        interface: c.law,
        kn: c.kn,
        formulation: c.formulation,
        restitution: Restitution::Housner,
        ..Params::default()
    };
    match c.shape {
        ShapeKind::SolidRectangle => {
            p.b = depth;
            p.l = depth;
        }
        ShapeKind::HollowRectangle => {
            p.b = depth;
            p.l = depth;
            p.t = 0.2 * depth;
        }
        ShapeKind::SolidCircle => p.ro = depth / 2.0,
        ShapeKind::HollowCircle => {
            p.ro = depth / 2.0;
            p.ri = 0.3 * depth;
        }
    }
    // kn Is > W hG (docs/model.md §2): raise kn where needed
    if c.law != LawKind::Rigid {
        let rigid = Params {
            interface: LawKind::Rigid,
            ..p
        }
        .build()
        .unwrap();
        let is = rigid.interface.shape().second_moment();
        let kn_min = rigid.body.weight * rigid.body.hg / is;
        p.kn = p.kn.max(3.0 * kn_min);
        let w_over_a = rigid.body.weight / rigid.interface.shape().area();
        p.fm = c.fm_ratio * w_over_a;
    }
    p.build().unwrap()
}

/// A deterministic multi-frequency ground motion around the body's own
/// frequency, enveloped over `shake_time`.
fn ground(m: &Model, c: &Case) -> impl Fn(f64) -> f64 {
    let p = (m.body.weight * m.body.r0 / m.body.io).sqrt();
    let amp = c.shaking * m.body.g * m.body.alpha.tan();
    let shake = c.shake_time;
    move |t: f64| {
        if t >= shake {
            return 0.0;
        }
        let env = (std::f64::consts::PI * t / shake).sin();
        let x = p * t;
        -amp * env
            * (0.6 * (0.7 * x).sin() + 0.3 * (1.9 * x + 1.0).sin() + 0.2 * (4.3 * x + 2.0).sin())
    }
}

#[derive(Debug, Default)]
struct Outcome {
    overturned: bool,
    impacts: u64,
    evals: u64,
    max_call_evals: u32,
    energy_checks: u32,
    seconds: f64,
}

fn run_case(c: &Case) -> Outcome {
    let m = build(c);
    let sim = Simulator::new(m, 1e-9);
    let ag = ground(&m, c);
    let b = m.body;
    let rigid = m.interface.law() == Law::Rigid;
    let i0 = if rigid {
        b.io
    } else {
        b.ic + b.mass * b.hg * b.hg
    };
    let conservative = rigid || m.formulation == Formulation::ShiftingPivot;
    let mut st: State = sim.initial_state(0.0, 0.0);
    let mut out = Outcome::default();
    let start = Instant::now();
    let n = (c.record / c.dt).round() as usize;
    let mut last_energy = f64::INFINITY;
    for k in 0..n {
        let t0 = k as f64 * c.dt;
        let t1 = (k + 1) as f64 * c.dt;
        let (a0, a1) = (ag(t0), ag(t1));
        let input = GroundInput {
            ag: a0,
            dag: (a1 - a0) / c.dt,
        };
        let quiet = a0 == 0.0 && a1 == 0.0;
        if quiet && conservative {
            // event by event, to see E at every crossing
            while st.t < t1 && !st.overturned {
                let ev = sim.advance_to_event(&mut st, t1, GroundInput::default());
                out.evals += ev.stats.evals as u64;
                out.max_call_evals = out.max_call_evals.max(ev.stats.evals);
                if ev.zero_crossings > 0 {
                    let e = 0.5 * i0 * st.omega * st.omega;
                    assert!(
                        e <= last_energy * (1.0 + 1e-7) + 1e-300,
                        "{c:?}: energy grew at t = {}: {e} after {last_energy}",
                        st.t
                    );
                    last_energy = e;
                    out.energy_checks += 1;
                }
            }
        } else {
            let ev = sim.advance(&mut st, t1, input);
            out.evals += ev.stats.evals as u64;
            out.max_call_evals = out.max_call_evals.max(ev.stats.evals);
            if st.overturned {
                let t_ov = ev.overturned_at.expect("overturned_at");
                assert!(t_ov > t0 - 1e-12 && t_ov <= t1, "{c:?}: t_ov {t_ov}");
                assert_eq!(st.t, t_ov);
            }
        }
        assert!(
            st.theta.is_finite() && st.omega.is_finite() && st.h.is_finite(),
            "{c:?}: {st:?}"
        );
        assert!(
            out.max_call_evals < 20_000_000,
            "{c:?}: a call took {} evaluations",
            out.max_call_evals
        );
        if st.overturned {
            out.overturned = true;
            assert!(st.theta.abs() == m.theta_ov);
            break;
        }
        assert_eq!(st.t, t1, "{c:?}");
        assert!(st.theta.abs() < m.theta_ov, "{c:?}: {st:?}");
    }
    out.impacts = st.impacts;
    out.seconds = start.elapsed().as_secs_f64();
    out
}

/// Runs the case (its checks are [`run_case`]'s) and reports what it did.
fn check(name: &str, c: &Case) {
    let o = run_case(c);
    eprintln!(
        "{name}: {:?} H {:.3} alpha {:.3} {:?} kn {:.0e} fm/(W/A) {:.3} {:?} shaking {:.2} record {} s dt {}: \
         overturned {} impacts {} evals {} (max/call {}) energy checks {} in {:.3} s",
        c.shape,
        c.size,
        c.alpha,
        c.law,
        c.kn,
        c.fm_ratio,
        c.formulation,
        c.shaking,
        c.record,
        c.dt,
        o.overturned,
        o.impacts,
        o.evals,
        o.max_call_evals,
        o.energy_checks,
        o.seconds
    );
}

const BASE: Case = Case {
    shape: ShapeKind::SolidRectangle,
    size: 2.5,
    alpha: 0.2,
    law: LawKind::ElastoPlastic,
    kn: 5e9,
    fm_ratio: 100.0,
    formulation: Formulation::ShiftingPivot,
    shaking: 1.5,
    shake_time: 5.0,
    record: 20.0,
    dt: 0.01,
};

#[test]
fn runs_end_finite_and_gain_no_energy_for_kn_from_1e6_to_1e15() {
    for kn in [1e6, 1e8, 1e10, 1e12, 1e13, 1e14, 1e15] {
        for (shaking, law) in [
            (0.5, LawKind::Elastic),
            (1.5, LawKind::Elastic),
            (1.5, LawKind::ElastoPlastic),
        ] {
            let c = Case {
                kn,
                law,
                shaking,
                fm_ratio: if law == LawKind::Elastic {
                    f64::INFINITY
                } else {
                    20.0
                },
                ..BASE
            };
            check("kn", &c);
        }
    }
}

#[test]
fn runs_end_finite_and_gain_no_energy_for_fm_from_barely_carrying_the_weight_to_none() {
    for fm_ratio in [1.01, 1.1, 2.0, 10.0, 1e3, f64::INFINITY] {
        let c = Case {
            fm_ratio,
            law: if fm_ratio.is_finite() {
                LawKind::ElastoPlastic
            } else {
                LawKind::Elastic
            },
            ..BASE
        };
        check("fm", &c);
    }
}

#[test]
fn runs_end_finite_and_gain_no_energy_for_slenderness_0_01_to_0_6_and_sizes_0_1_to_100_m() {
    for alpha in [0.01, 0.05, 0.2, 0.6] {
        for size in [0.1, 2.5, 100.0] {
            for law in [LawKind::Rigid, LawKind::ElastoPlastic] {
                let c = Case {
                    alpha,
                    size,
                    law,
                    // a 100 m body rocks slowly: a longer record
                    record: 20.0 * size.sqrt().max(1.0),
                    shake_time: 5.0 * size.sqrt().max(1.0),
                    ..BASE
                };
                check("alpha/size", &c);
            }
        }
    }
}

#[test]
fn runs_end_finite_and_gain_no_energy_for_communication_steps_from_1e_5_to_1_s() {
    for (dt, record) in [
        (1e-5, 1.0),
        (1e-4, 5.0),
        (1e-3, 20.0),
        (0.1, 20.0),
        (1.0, 20.0),
    ] {
        for law in [LawKind::Rigid, LawKind::ElastoPlastic] {
            let c = Case {
                dt,
                record,
                shake_time: record.min(5.0),
                law,
                ..BASE
            };
            check("dt", &c);
        }
    }
}

#[test]
fn runs_of_1000_s_records_end_finite_and_gain_no_energy() {
    for (law, kn) in [
        (LawKind::Rigid, 0.0),
        (LawKind::ElastoPlastic, 5e9),
        (LawKind::Elastic, 1e15),
    ] {
        for (shaking, shake_time) in [(1.5, 30.0), (0.5, 1000.0)] {
            let c = Case {
                law,
                kn,
                shaking,
                shake_time,
                record: 1000.0,
                dt: 0.01,
                fm_ratio: if law == LawKind::Elastic {
                    f64::INFINITY
                } else {
                    BASE.fm_ratio
                },
                ..BASE
            };
            check("1000 s", &c);
        }
    }
}

#[test]
fn runs_end_finite_and_gain_no_energy_for_random_parameters() {
    let mut r = Lcg(0x5eed_0003);
    for i in 0..60 {
        let law = r.pick(&[LawKind::Rigid, LawKind::Elastic, LawKind::ElastoPlastic]);
        let dt = r.pick(&[1e-3, 0.01, 0.05, 0.3, 1.0]);
        let c = Case {
            shape: r.pick(&[
                ShapeKind::SolidRectangle,
                ShapeKind::HollowRectangle,
                ShapeKind::SolidCircle,
                ShapeKind::HollowCircle,
            ]),
            size: r.log_uniform(0.1, 100.0),
            alpha: r.log_uniform(0.01, 0.6),
            law,
            kn: r.log_uniform(1e6, 1e15),
            fm_ratio: if law == LawKind::Elastic {
                f64::INFINITY
            } else {
                1.01 + r.log_uniform(0.01, 1e3)
            },
            formulation: r.pick(&[Formulation::ShiftingPivot, Formulation::Costa]),
            shaking: 3.0 * r.next(),
            shake_time: r.log_uniform(1.0, 20.0),
            record: 40.0,
            dt,
        };
        check(&format!("random {i}"), &c);
    }
}
