//! One-sided rocking (docs/model.md §7) against independent references:
//! the rigid free motion against the closed-form recursion
//! `V(A_{n+1}) = e² V(A_n)` with quadrature times (`support::exact`), the
//! half-cycle symmetry with two-sided rocking (the law is mirror-symmetric:
//! with `e = eta` and no ground motion `|theta(t)|` is the same, bit for
//! bit), the rest rules, and the parameter errors (§8).

mod support;

use rocking::dynamics::{GroundInput, Simulator, State};
use rocking::model::{LawKind, Restitution};
use rocking::{Model, Params, RestraintKind};
use support::exact::Exact;

fn block(law: LawKind, eta: f64, one_sided: Option<(i32, f64)>, theta0: f64) -> Params {
    let (restraint, side, e) = match one_sided {
        Some((s, e)) => (RestraintKind::OneSided, s, e),
        None => (RestraintKind::None, 1, 1.0),
    };
    Params {
        b: 0.4,
        h: 2.0,
        interface: law,
        restitution: Restitution::Given,
        eta,
        restraint,
        side,
        e_restraint: e,
        theta0,
        ..Params::default()
    }
}

fn build(p: Params) -> Model {
    p.build().unwrap()
}

#[test]
fn rigid_free_one_sided_rocking_against_the_closed_form() {
    for side in [1, -1] {
        for e in [0.5, 0.7, 0.93] {
            let probe = build(block(LawKind::Rigid, 0.9, None, 0.0));
            let theta0 = side as f64 * 0.5 * probe.body.alpha;
            let m = build(block(LawKind::Rigid, 0.9, Some((side, e)), theta0));
            let exact = Exact {
                eta: e,
                ..Exact::new(&m)
            };
            let want = exact.impacts(theta0.abs(), 12);
            let sim = Simulator::new(m, 1e-12);
            let mut st = sim.initial_state(theta0, 0.0);
            let mut k = 0;
            while k < want.len() {
                let before = st.impacts;
                sim.advance_to_event(&mut st, 100.0, GroundInput::default());
                assert!(
                    side as f64 * st.theta >= 0.0,
                    "theta {} on the restrained side",
                    st.theta
                );
                if st.impacts == before {
                    continue;
                }
                let (tw, aw) = want[k];
                assert!(
                    (st.t - tw).abs() <= 1e-10,
                    "side {side} e {e}: impact {k} at {}, closed form {tw}",
                    st.t
                );
                // after the impact the body moves back into its own side
                assert!(side as f64 * st.omega > 0.0);
                let amp = exact.amplitude(0.5 * m.body.io * st.omega * st.omega);
                assert!(
                    (amp - aw).abs() <= 1e-9 * aw,
                    "side {side} e {e}: amplitude {amp}, closed form {aw}"
                );
                k += 1;
            }
        }
    }
}

/// `|theta|`, `|omega|` every 10 ms for 3 s.
fn trace(m: Model, theta0: f64) -> Vec<(u64, u64, u64)> {
    let sim = Simulator::new(m, 1e-10);
    let mut st: State = sim.initial_state(theta0, 0.0);
    (1..=300)
        .map(|k| {
            sim.advance(&mut st, k as f64 * 0.01, GroundInput::default());
            (
                st.theta.abs().to_bits(),
                st.omega.abs().to_bits(),
                st.zero_crossings,
            )
        })
        .collect()
}

#[test]
fn half_cycle_symmetry_bit_for_bit() {
    for law in [LawKind::Rigid, LawKind::ElastoPlastic, LawKind::Elastic] {
        let probe = build(block(law, 0.8, None, 0.0));
        let theta0 = 0.5 * probe.theta_ov;
        let two = trace(build(block(law, 0.8, None, theta0)), theta0);
        for side in [1, -1] {
            let th = side as f64 * theta0;
            let one = trace(build(block(law, 0.8, Some((side, 0.8)), th)), th);
            assert_eq!(one, two, "{law:?} side {side}");
        }
    }
}

#[test]
fn flexible_rest_rules() {
    let probe = build(block(LawKind::ElastoPlastic, 0.9, None, 0.0));
    let theta0 = 0.3 * probe.theta_ov;
    let m = build(block(LawKind::ElastoPlastic, 0.9, Some((1, 0.6)), theta0));
    let sim = Simulator::new(m, 1e-10);
    let mut st = sim.initial_state(theta0, 0.0);
    // pushed into the restraint (side ag > 0): the bounces accumulate
    let push = GroundInput { ag: 0.5, dag: 0.0 };
    let mut rested = None;
    for k in 1..=500 {
        let ev = sim.advance(&mut st, k as f64 * 0.01, push);
        assert!(st.theta >= 0.0);
        if ev.came_to_rest {
            rested = Some(st.t);
            break;
        }
    }
    assert!(
        rested.is_some() && st.at_rest,
        "no rest under a push into the restraint"
    );
    // stays there while pushed, however hard
    let t = st.t;
    sim.advance(&mut st, t + 1.0, GroundInput { ag: 50.0, dag: 0.0 });
    assert!(st.at_rest && st.theta == 0.0);
    // leaves as soon as the ground pulls away (side ag < 0), on its side
    let t = st.t;
    sim.advance(&mut st, t + 0.05, GroundInput { ag: -0.5, dag: 0.0 });
    assert!(!st.at_rest && st.theta > 0.0, "theta {}", st.theta);
    // without ground motion no finite-time rest: each bounce is e times the last
    let m = build(block(LawKind::ElastoPlastic, 0.9, Some((1, 0.6)), 0.0));
    let sim = Simulator::new(m, 1e-10);
    let mut st = sim.initial_state(0.0, 0.05);
    let ev = sim.advance(&mut st, 0.3, GroundInput::default());
    assert!(ev.impacts >= 2, "{} restraint impacts", ev.impacts);
}

#[test]
fn rigid_rest_and_uplift_against_the_restraint() {
    let m = build(block(LawKind::Rigid, 0.9, Some((1, 0.0)), 0.0));
    let b = m.body;
    let thr = b.g * b.b / b.hg;
    let sim = Simulator::new(m, 1e-12);
    let mut st = sim.initial_state(0.0, 0.0);
    // a push toward the restraint never lifts it
    sim.advance(
        &mut st,
        1.0,
        GroundInput {
            ag: 10.0 * thr,
            dag: 0.0,
        },
    );
    assert!(st.at_rest && st.theta == 0.0);
    // away from it, at g tan(alpha): ag = -k t
    let ev = sim.advance_to_event(&mut st, 10.0, GroundInput { ag: 0.0, dag: -1.0 });
    assert!(
        ev.uplift && (st.t - 1.0 - thr).abs() <= 1e-13 * (1.0 + thr),
        "uplift at {}",
        st.t
    );
    // e = 0: the first return to the restraint stops it dead
    let m = build(block(LawKind::Rigid, 0.9, Some((1, 0.0)), 0.1));
    let sim = Simulator::new(m, 1e-12);
    let mut st = sim.initial_state(0.1, 0.0);
    let ev = sim.advance(&mut st, 5.0, GroundInput::default());
    assert!(ev.came_to_rest && ev.impacts == 1 && st.at_rest);
}

#[test]
fn start_moving_into_the_restraint_is_an_impact_at_t0() {
    let m = build(block(LawKind::Rigid, 0.9, Some((-1, 0.5)), 0.0));
    let sim = Simulator::new(m, 1e-12);
    let st = sim.initial_state(0.0, 0.2);
    assert_eq!((st.omega, st.impacts, st.zero_crossings), (-0.1, 1, 1));
}

#[test]
fn parameter_errors_name_the_variable() {
    let cases = [
        (
            Params {
                side: 0,
                ..block(LawKind::Rigid, 0.9, Some((1, 0.5)), 0.0)
            },
            "side",
        ),
        (
            block(LawKind::Rigid, 0.9, Some((1, 1.5)), 0.0),
            "eRestraint",
        ),
        (
            block(LawKind::Rigid, 0.9, Some((1, -0.1)), 0.0),
            "eRestraint",
        ),
        (block(LawKind::Rigid, 0.9, Some((1, 0.5)), -0.01), "theta"),
    ];
    for (p, name) in cases {
        let e = p.build().unwrap_err();
        assert_eq!(e.variable, name, "{e}");
    }
    let e = block(LawKind::Rigid, 0.9, Some((1, 0.5)), -0.01)
        .build()
        .unwrap_err();
    assert!(e.condition.contains("restraintViolated"), "{e}");
}
