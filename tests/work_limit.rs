//! The work limit of one call (`Simulator::work_limit`): calls that would run
//! for minutes stop at their budget with a consistent state, from which
//! shorter calls go on; calls within the budget are unchanged by it.

use rocking::dynamics::{Events, GroundInput, Simulator, State, WorkLimit};
use rocking::model::LawKind;
use rocking::{Params, Restitution};

const PER_CALL: u64 = WorkLimit::DEFAULT_PER_CALL;

fn limited(p: Params) -> Simulator {
    let mut sim = Simulator::new(p.build().unwrap(), 1e-9);
    sim.work_limit = Some(WorkLimit { per_call: PER_CALL });
    sim
}

/// The call stopped at its limit: before `t_end`, past its start, at the time
/// `Events::limited` reports, with the work at the budget (the check runs
/// before each step: at most one step and its event's redone steps over).
fn assert_stopped(st: &State, ev: &Events, t0: f64, t_end: f64, span: f64) {
    let l = ev.limited.expect("the call must stop at its work limit");
    assert_eq!(l.budget, WorkLimit { per_call: PER_CALL }.budget(span));
    assert!(
        ev.work() >= l.budget && ev.work() <= l.budget + 8,
        "work {} budget {}",
        ev.work(),
        l.budget
    );
    assert_eq!(st.t, l.t);
    assert!(st.t > t0 && st.t < t_end, "t = {}", st.t);
    assert!(
        st.theta.is_finite() && st.omega.is_finite() && st.h > 0.0,
        "{st:?}"
    );
    assert!(!l.cause().is_empty());
}

/// From the stopped state, a call of `dt` finishes (no limit) and stays finite.
fn assert_goes_on(sim: &Simulator, st: &State, dt: f64, input: GroundInput) {
    let mut s = *st;
    let ev = sim.advance(&mut s, st.t + dt, input);
    assert!(
        ev.limited.is_none(),
        "a call of {dt} s after the limit: {ev:?}"
    );
    assert_eq!(s.t, st.t + dt);
    assert!(s.theta.is_finite() && s.omega.is_finite());
}

#[test]
fn a_very_stiff_interface_stops_at_the_limit_and_goes_on_in_shorter_calls() {
    // kn 1e18 Pa/m shaken below uplift: explicit steps of ~1e-7 s, the
    // 1 s call would take minutes
    let sim = limited(Params {
        kn: 1e18,
        ..Params::default()
    });
    let input = GroundInput { ag: 1.0, dag: 0.0 };
    let mut st = sim.initial_state(0.0, 0.0);
    let ev = sim.advance(&mut st, 1.0, input);
    assert_stopped(&st, &ev, 0.0, 1.0, 1.0);
    assert!(ev.limited.unwrap().steps > ev.limited.unwrap().zero_crossings);
    assert_goes_on(&sim, &st, 1e-3, input);
}

#[test]
fn a_communication_step_of_1e300_s_stops_at_one_and_a_half_times_the_limit() {
    // an elastic joint under a constant ag oscillates about its tilted
    // equilibrium for ever, and a rigid body with eta = 1 rocks for ever
    let elastic = limited(Params {
        interface: LawKind::Elastic,
        ..Params::default()
    });
    let input = GroundInput { ag: 1.0, dag: 0.0 };
    let mut st = elastic.initial_state(0.0, 0.0);
    let ev = elastic.advance(&mut st, 1e300, input);
    assert_stopped(&st, &ev, 0.0, 1e300, 1e300);
    assert_eq!(ev.limited.unwrap().budget, PER_CALL * 3 / 2);
    assert_goes_on(&elastic, &st, 1e-3, input);

    let rigid = limited(Params {
        interface: LawKind::Rigid,
        restitution: Restitution::Given,
        eta: 1.0,
        ..Params::default()
    });
    let mut st = rigid.initial_state(0.05, 0.0);
    let ev = rigid.advance(&mut st, 1e300, GroundInput::default());
    assert_stopped(&st, &ev, 0.0, 1e300, 1e300);
    // impacts in closed form: each is a zero crossing, no step
    let l = ev.limited.unwrap();
    assert!(l.zero_crossings > l.steps, "{l:?}");
    assert_eq!(st.zero_crossings, ev.zero_crossings as u64);
    assert_goes_on(&rigid, &st, 1e-3, GroundInput::default());
}

#[test]
fn a_limit_that_is_not_reached_changes_nothing() {
    // rocking with impacts and crushing, 100 calls of 10 ms, with and
    // without the limit: bit for bit the same states
    let p = Params {
        kn: 1e12,
        ..Params::default()
    };
    let free = Simulator::new(p.build().unwrap(), 1e-9);
    let capped = limited(p);
    let (mut a, mut b) = (free.initial_state(0.1, 0.0), capped.initial_state(0.1, 0.0));
    for k in 0..100 {
        let input = GroundInput {
            ag: 0.5 * (k as f64 * 0.1).sin(),
            dag: 0.0,
        };
        let t = (k + 1) as f64 * 0.01;
        let ea = free.advance(&mut a, t, input);
        let eb = capped.advance(&mut b, t, input);
        assert!(eb.limited.is_none());
        assert_eq!(ea, eb);
        assert_eq!(a, b);
    }
    assert!(a.zero_crossings > 0);
}

#[test]
fn the_budget_is_per_call_up_to_1_s_and_at_most_one_and_a_half_times_that_beyond() {
    let w = WorkLimit { per_call: 1000 };
    assert_eq!(w.budget(1e-6), 1000);
    assert_eq!(w.budget(1.0), 1000);
    assert_eq!(w.budget(1.25), 1250);
    assert_eq!(w.budget(1.5), 1500);
    assert_eq!(w.budget(1e300), 1500);
    assert_eq!(WorkLimit { per_call: 0 }.budget(1.0), 1);
}
