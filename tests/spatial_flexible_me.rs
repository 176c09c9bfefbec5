//! Model Exchange of the round body in space on the flexible and crushing
//! beds (docs/model.md §11.5): the derivatives, indicators and event
//! update (`rocking::spatial::continuous`) integrated by a host written
//! in `support::model_exchange` (RK4 with step doubling, each event
//! located by bisection to 1e-14 s) against co-simulation
//! (`Spatial::advance`, DOP853 with its own event location and restarts at
//! the contact's kinks) and, along `x`, against the planar model.

use rocking::dynamics::{GroundInput, Simulator, VerticalInput};
use rocking::model::{Formulation, Restitution};
use rocking::spatial::{PlanInput, Spatial, SpatialState};
use rocking::Params;

mod support;
use support::drum::{drum, on_bed, pulse_train, vertical, DT};
use support::model_exchange::{
    assert_same_discrete_states, compare, cs_run, me_run, Input, HOLD_AV, OMEGA_STATE,
};

const RTOL: f64 = 1e-12;

/// Both components and `av` from rest on the elastic and the crushing bed,
/// and a planar motion along an oblique azimuth with `av`, against
/// co-simulation (rtol 1e-12): the same impacts (applications of the
/// restitution rule), rest and overturning at every sample, the same
/// motion (theta within 1e-8 rad, psi 1e-7 rad). The host's tolerance is
/// 1e-11, checked converged against 1e-12 (their gap below 2e-9 rad).
///
/// `av` is linear between samples, as co-simulation takes it. `costa`'s
/// equation has no `dN/dt`; `shiftingPivot`'s has (the resultant sliding
/// along the base as `N` changes), which Model Exchange, given no input
/// derivatives, does not know: the host integrates `omegaW`, whose rate
/// has none (docs/model.md §11.5). `shiftingPivot` with `av` held over
/// each sample (both runs then have `dN/dt = 0`) too. Integrating
/// `omega` with `dN/dt` taken as 0 instead (`Spatial::derivatives`, the
/// host's `OMEGA_STATE`) moves the tilt by 1e-3 of its peak at least.
#[test]
fn on_a_flexible_bed_model_exchange_follows_co_simulation() {
    let two_av = |t: f64| {
        (
            [pulse_train(t), 0.7 * pulse_train(1.37 * t + 0.2)],
            vertical(t),
        )
    };
    let oblique_av = |t: f64| {
        let (s, c) = 0.7f64.sin_cos();
        ([c * pulse_train(t), s * pulse_train(t)], vertical(t))
    };
    let t_end = 4.0;
    let (mut exact_worst, mut omega_w_worst) = (0.0f64, 0.0f64);
    let mut left_out = vec![];
    let inputs: [(&str, &Input); 2] = [("two components", &two_av), ("oblique plane", &oblique_av)];
    for crushing in [false, true] {
        for (input, f) in inputs {
            for (formulation, hold, omega_state) in [
                (Formulation::Costa, false, false),
                (Formulation::ShiftingPivot, false, false),
                (Formulation::ShiftingPivot, true, true),
                (Formulation::ShiftingPivot, false, true),
            ] {
                HOLD_AV.set(hold);
                OMEGA_STATE.set(omega_state);
                let p = on_bed(crushing, formulation);
                let body = Spatial::new(&p, None, RTOL).unwrap();
                let st0 = SpatialState::at_rest();
                let cs = cs_run(&body, st0, f, t_end);
                let (me, events) = me_run(&body, st0, f, t_end, 1e-11);
                let (th, psi, x, peak) = compare(&cs, &me);
                let name = format!(
                    "{input}, crushing {crushing} {formulation:?} av held {hold} omega state {omega_state}"
                );
                let (a, b) = (cs.last().unwrap(), me.last().unwrap());
                let host = if hold || !omega_state {
                    let (fine, _) = me_run(&body, st0, f, t_end, 1e-12);
                    compare(&me, &fine).0
                } else {
                    f64::NAN
                };
                eprintln!(
                    "{name}: peak {peak:.4} rad, impacts {} / {}, {events} events; |dtheta| {th:.2e} rad, \
                     |dpsi| {psi:.2e} rad, |dxG| {x:.2e} m; host 1e-11 vs 1e-12 {host:.2e} rad",
                    a.impacts, b.impacts
                );
                assert!(peak > 0.05, "{name}: the run must rock");
                // in a plane the rule applies at each crossing; off it the
                // contact runs round the rim with the heel open
                assert!(
                    input != "oblique plane" || a.impacts >= 3,
                    "{name}: the rule must apply"
                );
                if crushing {
                    let theta_c = p.build().unwrap().interface.theta_c();
                    assert!(peak > 10.0 * theta_c, "{name}: crushes ({theta_c})");
                }
                if omega_state && !hold {
                    left_out.push(th / peak);
                    continue;
                }
                assert_same_discrete_states(&name, &cs, &me);
                assert!(host <= 2e-9, "{name}: the host is not converged ({host:e})");
                assert!(th <= 1e-8, "{name}: theta {th:e}");
                assert!(psi <= 1e-7, "{name}: psi {psi:e}");
                exact_worst = exact_worst.max(th);
                if formulation == Formulation::ShiftingPivot && !hold {
                    omega_w_worst = omega_w_worst.max(th);
                }
            }
        }
    }
    HOLD_AV.set(false);
    OMEGA_STATE.set(false);
    eprintln!(
        "dN/dt taken as 0: |dtheta|/peak {left_out:?}; omegaW {omega_w_worst:.2e} rad; \
         all others {exact_worst:.2e} rad"
    );
    assert_eq!(left_out.len(), 4);
    for g in left_out {
        assert!(g > 1e-3, "{g:e}");
    }
}

/// Overturning on the crushing bed under a strong two-component input:
/// at the same time as co-simulation (to 1e-9 s), the same impacts before.
#[test]
fn on_a_crushing_bed_model_exchange_overturns_with_co_simulation() {
    let strong = |t: f64| ([2.2 * pulse_train(t), 1.2 * pulse_train(t + 0.1)], 0.0);
    for formulation in [Formulation::Costa, Formulation::ShiftingPivot] {
        let body = Spatial::new(&on_bed(true, formulation), None, RTOL).unwrap();
        let st0 = SpatialState::at_rest();
        let cs = cs_run(&body, st0, &strong, 3.0);
        let (me, events) = me_run(&body, st0, &strong, 3.0, 1e-11);
        let (th, _, _, peak) = compare(&cs, &me);
        let (a, b) = (cs.last().unwrap(), me.last().unwrap());
        eprintln!(
            "{formulation:?}: overturned {} / {} at {:.9} / {:.9} s, impacts {} / {}, {events} events, |dtheta| {th:.2e} rad (peak {peak:.3})",
            a.overturned, b.overturned, a.t, b.t, a.impacts, b.impacts
        );
        assert!(a.overturned && b.overturned);
        assert!((a.t - b.t).abs() <= 1e-9, "{} / {}", a.t, b.t);
        assert_eq!(a.impacts, b.impacts);
    }
}

/// Free rocking in full contact on the elastic bed (from 1e-3 rad along
/// 0.7 rad, inside `thetaJo` = 1.2e-3 rad) settles: the rule at each
/// crossing, then rest (docs/model.md §11.3, the amplitude below `rtol
/// thetaOv`, rtol 1e-10 here), after the same number of rules and at the
/// same sample as co-simulation.
#[test]
fn on_a_flexible_bed_model_exchange_comes_to_rest_with_co_simulation() {
    let still = |_: f64| ([0.0, 0.0], 0.0);
    let body = Spatial::new(&on_bed(false, Formulation::ShiftingPivot), None, 1e-10).unwrap();
    let st0 = SpatialState::tilted(&body, 1e-3, 0.7, [0.0; 3]);
    let cs = cs_run(&body, st0, &still, 20.0);
    let (me, events) = me_run(&body, st0, &still, 20.0, 1e-11);
    let rest = |r: &[SpatialState]| r.iter().position(|s| s.at_rest);
    let (a, b) = (cs.last().unwrap(), me.last().unwrap());
    eprintln!(
        "rest at sample {:?} / {:?}, impacts {} / {}, {events} events",
        rest(&cs),
        rest(&me),
        a.impacts,
        b.impacts
    );
    assert!(a.at_rest && b.at_rest);
    assert_eq!(rest(&cs), rest(&me));
    assert_eq!(a.impacts, b.impacts);
}

/// Along `x`, Model Exchange is the planar model (co-simulation of
/// `rocking::Simulator`, explicit pair, rtol 1e-12) on both beds: the same
/// zero crossings at every sample, the tilt within 1e-8 rad, nothing off
/// the plane; with and without `av` (the planar model has the whole
/// `dN/dt` in co-simulation).
#[test]
fn along_x_model_exchange_on_a_flexible_bed_is_the_planar_model() {
    for crushing in [false, true] {
        for (formulation, with_av) in [
            (Formulation::Costa, true),
            (Formulation::ShiftingPivot, false),
            (Formulation::ShiftingPivot, true),
        ] {
            let p = on_bed(crushing, formulation);
            let f = move |t: f64| {
                (
                    [pulse_train(t), 0.0],
                    if with_av { vertical(t) } else { 0.0 },
                )
            };
            let body = Spatial::new(&p, None, RTOL).unwrap();
            let (me, events) = me_run(&body, SpatialState::at_rest(), &f, 4.0, 1e-11);
            let mut planar = Simulator::new(p.build().unwrap(), RTOL);
            planar.stiff_mode = false;
            let mut a = planar.initial_state(0.0, 0.0);
            let (mut worst, mut peak) = (0.0f64, 0.0f64);
            for (k, b) in me.iter().enumerate() {
                let (t0, t1) = (k as f64 * DT, (k + 1) as f64 * DT);
                let ((a0, v0), (a1, v1)) = (f(t0), f(t1));
                let ga = GroundInput {
                    ag: a0[0],
                    dag: (a1[0] - a0[0]) / DT,
                };
                let v = VerticalInput {
                    av: v0,
                    dav: (v1 - v0) / DT,
                };
                planar.advance_vertical(&mut a, t1, ga, v);
                worst = worst.max((a.theta - b.e[0].asin()).abs());
                peak = peak.max(a.theta.abs());
                assert_eq!(b.e[1], 0.0, "off its plane");
                assert_eq!(b.omega[0], 0.0);
                assert_eq!(b.omega[2], 0.0);
                assert_eq!(a.zero_crossings, b.impacts, "crossings at t = {t1}");
            }
            eprintln!(
                "crushing {crushing} {formulation:?} av {with_av}: peak {peak:.4} rad, {} crossings, {events} events, |dtheta| {worst:.2e} rad",
                a.zero_crossings
            );
            assert!(peak > 0.05 && a.zero_crossings >= 3);
            assert!(worst <= 1e-8, "{worst:e} rad");
        }
    }
}

/// Model Exchange runs on every bed with either formulation. Its velocity
/// state `omegaW` is `omega` bit for bit, and its rates `omega`'s, where
/// the model makes them so: `costa`, the rigid bed, and `shiftingPivot` on
/// a flexible bed at `av = 0`; elsewhere the transform inverts to
/// round-off.
#[test]
fn model_exchange_runs_every_bed_with_omega_w_omega_where_n_is_w() {
    let ag = [0.7, -0.4];
    let tilted = |body: &Spatial| {
        let mut st = SpatialState::tilted(body, 0.03, 0.7, [0.2, -0.5, 0.9]);
        st.pivot = st.contact_direction();
        st
    };
    for formulation in [Formulation::Costa, Formulation::ShiftingPivot] {
        let rigid = Params {
            formulation,
            ..drum(Restitution::Housner, false)
        };
        for (bed, p) in [
            ("rigid", rigid),
            ("elastic", on_bed(false, formulation)),
            ("crushing", on_bed(true, formulation)),
        ] {
            let body = Spatial::new(&p, None, RTOL).unwrap();
            let st = tilted(&body);
            for av in [0.0, 2.0, -3.0] {
                let w = body.to_weight_referred(st, av);
                let identity = !body.weight_referred() || av == 0.0;
                assert_eq!(
                    identity,
                    w.omega == st.omega,
                    "{bed} {formulation:?} av {av}"
                );
                if identity {
                    assert_eq!(
                        body.derivatives_weight_referred(&w, ag, av),
                        body.derivatives(&st, ag, av)
                    );
                    continue;
                }
                let back = body.from_weight_referred(w, av);
                for i in 0..3 {
                    assert!((back.omega[i] - st.omega[i]).abs() <= 1e-15, "{bed} {av}");
                }
            }
        }
    }
}

/// The rate of `omegaW` (`Spatial::derivatives_weight_referred`) is the
/// rate of `omegaW` along a co-simulation run, whose equation has the
/// whole `dN/dt` (`av` linear over each sample): a five-point central
/// difference of `Spatial::to_weight_referred` at steps of 0.5 ms inside
/// each sample, stencils with an impact or a change of the contact side
/// left out; both components and `av`, elastic and crushing,
/// `shiftingPivot`. The rate of `omega` at `dN/dt = 0`
/// (`Spatial::derivatives`) against the difference of `omega` misses the
/// term, which the check is shown to see.
#[test]
fn the_rate_of_omega_w_is_its_difference_along_co_simulation() {
    let f = |t: f64| {
        (
            [pulse_train(t), 0.7 * pulse_train(1.37 * t + 0.2)],
            vertical(t),
        )
    };
    const SUB: usize = 20;
    let h = DT / SUB as f64;
    for crushing in [false, true] {
        let body = Spatial::new(&on_bed(crushing, Formulation::ShiftingPivot), None, RTOL).unwrap();
        let mut st = SpatialState::at_rest();
        let (mut scale, mut missed, mut stencils) = (0.0f64, 0.0f64, 0);
        let mut errors = vec![];
        for k in 0..200 {
            let t0 = k as f64 * DT;
            let ((a0, v0), (a1, v1)) = (f(t0), f(t0 + DT));
            let (da, dav) = ([(a1[0] - a0[0]) / DT, (a1[1] - a0[1]) / DT], (v1 - v0) / DT);
            let at = |t: f64| {
                let s = t - t0;
                ([a0[0] + da[0] * s, a0[1] + da[1] * s], v0 + dav * s)
            };
            let mut run = vec![st];
            for j in 1..=SUB {
                let (a, av) = at(st.t);
                body.advance(
                    &mut st,
                    t0 + j as f64 * h,
                    PlanInput { a, da },
                    VerticalInput { av, dav },
                );
                run.push(st);
            }
            for c in 2..=SUB - 2 {
                let w = &run[c - 2..=c + 2];
                if w.iter()
                    .any(|s| s.at_rest || s.impacts != w[0].impacts || s.pivot != w[0].pivot)
                {
                    continue;
                }
                let referred = |s: &SpatialState| body.to_weight_referred(*s, at(s.t).1).omega;
                let five = |g: &dyn Fn(&SpatialState) -> [f64; 3], i: usize| {
                    (-g(&w[4])[i] + 8.0 * g(&w[3])[i] - 8.0 * g(&w[1])[i] + g(&w[0])[i])
                        / (12.0 * h)
                };
                let (ag, av) = at(w[2].t);
                let rate =
                    body.derivatives_weight_referred(&body.to_weight_referred(w[2], av), ag, av);
                let plain = body.derivatives(&w[2], ag, av);
                for i in 0..3 {
                    errors.push((five(&referred, i) - rate[2 + i]).abs());
                    missed = missed.max((five(&|s| s.omega, i) - plain[2 + i]).abs());
                    scale = scale.max(rate[2 + i].abs());
                }
                stencils += 1;
            }
        }
        errors.sort_by(f64::total_cmp);
        let (p99, worst) = (errors[errors.len() * 99 / 100], errors[errors.len() - 1]);
        eprintln!(
            "crushing {crushing}: {stencils} stencils, |omegaW' - difference| {p99:.2e} rad/s² \
             at 99 %, {worst:.2e} at most (rates to {scale:.3} rad/s²); omega' at dN/dt = 0 \
             misses {missed:.2e} rad/s²"
        );
        assert!(stencils > 1000);
        assert!(p99 <= 1e-6 * scale, "{p99:e}");
        assert!(missed >= 1e2 * worst, "{missed:e}");
    }
}
