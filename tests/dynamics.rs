//! Rigid free rocking (Housner) against its exact solution (docs/model.md §3).
//!
//! Between impacts the energy `E = IO omega²/2 + V(phi)`,
//! `V(phi) = W R0 (cos(alpha - phi) - cos(alpha))`, is conserved; each impact
//! multiplies it by `eta²`, so the peak amplitudes satisfy
//! `V(phi_{n+1}) = eta² V(phi_n)` and the time from a peak `phi` to the next
//! impact is the quadrature `T(phi) = ∫_0^phi dpsi / omega(psi)`, computed here
//! by Gauss-Legendre after the substitution `psi = phi sin(u)` that removes the
//! turning-point singularity. None of this uses the code under test.

mod support;

use rocking::dynamics::{GroundInput, Simulator, State, DEFAULT_RTOL};
use support::exact::Exact;
use support::rigid_block;

/// Runs impact by impact; returns `(time, amplitude from the post-impact energy)`.
fn simulate_impacts(sim: &Simulator, ex: &Exact, theta0: f64, n: usize) -> Vec<(f64, f64)> {
    let mut st = sim.initial_state(theta0, 0.0);
    let mut out = Vec::new();
    while out.len() < n {
        let ev = sim.advance_to_event(&mut st, 1e3, GroundInput::default());
        assert!(!st.overturned && !st.at_rest, "{st:?}");
        if ev.impacts > 0 {
            assert_eq!(st.theta, 0.0);
            let e = 0.5 * ex.io * st.omega * st.omega;
            out.push((st.t, ex.amplitude(e)));
        }
    }
    out
}

fn check_free_rocking(b: f64, h: f64, theta0_over_alpha: f64) {
    let m = rigid_block(b, h);
    let ex = Exact::new(&m);
    let theta0 = theta0_over_alpha * ex.alpha;
    let exact = ex.impacts(theta0, 20);
    let sim = Simulator::new(m, DEFAULT_RTOL);
    let got = simulate_impacts(&sim, &ex, theta0, 20);
    let mut worst = (0.0f64, 0.0f64);
    for (i, (&(te, pe), &(tg, pg))) in exact.iter().zip(&got).enumerate() {
        let dt = (tg - te).abs() / te;
        let dp = (pg - pe).abs() / pe;
        worst = (worst.0.max(dt), worst.1.max(dp));
        assert!(
            dt < 1e-9 && dp < 1e-9,
            "alpha = {}: impact {}: t {tg} vs {te} ({dt:.1e}), amplitude {pg} vs {pe} ({dp:.1e})",
            ex.alpha,
            i + 1
        );
    }
    eprintln!(
        "alpha = {:.3}, eta = {:.3}: worst relative error over 20 impacts: time {:.1e}, amplitude {:.1e}",
        ex.alpha, ex.eta, worst.0, worst.1
    );
}

#[test]
fn rigid_free_rocking_slender_matches_exact_solution() {
    check_free_rocking(0.4, 4.0, 0.8);
}

#[test]
fn rigid_free_rocking_stocky_matches_exact_solution() {
    check_free_rocking(1.0, 2.0, 0.8);
}

#[test]
fn rigid_energy_conserved_between_impacts() {
    for (b, h) in [(0.4, 4.0), (1.0, 2.0)] {
        let m = rigid_block(b, h);
        let ex = Exact::new(&m);
        let sim = Simulator::new(m, DEFAULT_RTOL);
        let theta0 = 0.9 * ex.alpha;
        let mut st = sim.initial_state(theta0, 0.0);
        let mut e_segment = ex.v(theta0);
        let mut impacts = 0;
        let energy = |st: &State| 0.5 * ex.io * st.omega * st.omega + ex.v(st.theta.abs());
        let mut worst = 0.0f64;
        // outputs every 0.25 s (longer than the natural steps) over the first 10 impacts
        let mut k = 0;
        while impacts < 10 {
            k += 1;
            let ev = sim.advance(&mut st, k as f64 * 0.25, GroundInput::default());
            if ev.impacts > 0 {
                impacts += ev.impacts;
                e_segment *= ex.eta.powi(2 * ev.impacts as i32);
                continue; // the sample may straddle the impact: skip it
            }
            let rel = (energy(&st) - e_segment).abs() / e_segment;
            worst = worst.max(rel);
        }
        eprintln!(
            "alpha = {:.3}: energy drift between impacts {worst:.1e}",
            ex.alpha
        );
        assert!(worst < 1e-9, "energy drift {worst:.2e}");
    }
}

#[test]
fn rigid_chattering_ends_in_rest_at_the_accumulation_time() {
    // stocky block, eta = 0.7: the impacts accumulate at
    // t_inf = T(phi0) + 2 sum_n T(phi_n), a convergent series.
    let m = rigid_block(1.0, 2.0);
    let ex = Exact::new(&m);
    let theta0 = 0.5 * ex.alpha;
    let sim = Simulator::new(m, DEFAULT_RTOL);
    let exact = ex.impacts(theta0, 400);
    let (t_last, phi_last) = exact[exact.len() - 1];
    let t_inf = t_last + 2.0 * ex.fall_time(phi_last);
    let mut st = sim.initial_state(theta0, 0.0);
    let mut t_rest = f64::NAN;
    let mut t = 0.0;
    while t < 20.0 {
        t += 0.01;
        let before = st.t;
        let ev = sim.advance_to_event(&mut st, t, GroundInput::default());
        if ev.came_to_rest {
            t_rest = st.t;
            break;
        }
        if st.t < t {
            t -= 0.01; // stopped at an impact: continue to the same t
        }
        assert!(st.t > before || ev.impacts > 0);
    }
    assert!(st.at_rest, "not at rest: {st:?}");
    let err = (t_rest - t_inf).abs() / t_inf;
    eprintln!(
        "rest at {t_rest} after {} impacts, accumulation time {t_inf}: relative {err:.1e}",
        st.impacts
    );
    // The rest criterion (docs/dynamics.md) snaps to rest after an impact
    // with |omega+| <= rtol p alpha; the chattering it skips lasts at most
    // sum_k 2 |omega+| eta^k / g_eff = 2 |omega+| / ((1 - eta) g_eff), with
    // g_eff = W b / IO the deceleration at theta = 0; plus the integration
    // error of the time, rtol t.
    let b = &m.body;
    let p = (b.weight * b.r0 / b.io).sqrt();
    let g_eff = b.weight * b.b / b.io;
    let bound = 2.0 * DEFAULT_RTOL * p * ex.alpha / ((1.0 - ex.eta) * g_eff) + DEFAULT_RTOL * t_inf;
    assert!(
        (t_rest - t_inf).abs() <= bound,
        "rest at {t_rest}, accumulation at {t_inf}, bound {bound:.1e}"
    );
    // and it stays at rest under zero input, O(1) per call
    let ev = sim.advance(&mut st, 1e6, GroundInput::default());
    assert!(st.at_rest && st.t == 1e6 && ev.stats.evals == 0);
}

#[test]
fn uplift_starts_just_above_g_tan_alpha_toward_the_side_ag_pushes() {
    let m = rigid_block(0.5, 2.5);
    let sim = Simulator::new(m, DEFAULT_RTOL);
    let thr = m.body.g * m.body.b / m.body.hg; // g tan(alpha)
    assert!((sim.uplift_acceleration() / thr - 1.0).abs() < 1e-15);
    // below the threshold: at rest, no work
    let mut st = sim.initial_state(0.0, 0.0);
    let ev = sim.advance(
        &mut st,
        10.0,
        GroundInput {
            ag: 0.999 * thr,
            dag: 0.0,
        },
    );
    assert!(st.at_rest && ev.stats.evals == 0 && !ev.uplift);
    // negative ag lifts toward theta > 0, positive toward theta < 0
    for (ag, sign) in [(-1.01 * thr, 1.0), (1.01 * thr, -1.0)] {
        let mut st = sim.initial_state(0.0, 0.0);
        let ev = sim.advance(&mut st, 0.1, GroundInput { ag, dag: 0.0 });
        assert!(ev.uplift && !st.at_rest);
        assert_eq!(st.theta.signum(), sign, "ag = {ag}: {st:?}");
    }
    // a ramp crossing the threshold at t* = 0.5 s: uplift found there
    let mut st = sim.initial_state(0.0, 0.0);
    let ev = sim.advance_to_event(
        &mut st,
        1.0,
        GroundInput {
            ag: 0.0,
            dag: -2.0 * thr,
        },
    );
    assert!(ev.uplift);
    assert!((st.t - 0.5).abs() < 1e-15, "uplift at {}", st.t);
}

#[test]
fn save_and_restore_reproduce_a_run_bit_for_bit() {
    let flexible = rocking::Params::default().build().unwrap();
    for m in [rigid_block(0.5, 2.5), flexible] {
        let sim = Simulator::new(m, DEFAULT_RTOL);
        let thr = sim.uplift_acceleration();
        let input = |k: usize| {
            let t = k as f64 * 0.01;
            let ag = |t: f64| -1.1 * thr * (6.0 * t).sin() * (-0.3 * t).exp();
            GroundInput {
                ag: ag(t),
                dag: (ag(t + 0.01) - ag(t)) / 0.01,
            }
        };
        let mut st = sim.initial_state(0.0, 0.0);
        for k in 0..300 {
            sim.advance(&mut st, (k + 1) as f64 * 0.01, input(k));
        }
        let saved = st;
        let mut a = Vec::new();
        for k in 300..1500 {
            sim.advance(&mut st, (k + 1) as f64 * 0.01, input(k));
            a.push(st);
        }
        let mut st = saved;
        for (i, k) in (300..1500).enumerate() {
            sim.advance(&mut st, (k + 1) as f64 * 0.01, input(k));
            assert_eq!(st, a[i]);
            assert_eq!(st.theta.to_bits(), a[i].theta.to_bits());
            assert_eq!(st.omega.to_bits(), a[i].omega.to_bits());
        }
        let last = a.last().unwrap();
        assert!(last.impacts > 0 && !last.overturned, "{last:?}");
    }
}

#[test]
fn quiet_rigid_rocking_in_long_calls_matches_event_by_event() {
    // Without ground motion, whole half-cycles inside a call are taken in
    // closed form; the result must match the event-by-event run and the
    // exact solution.
    for (b, h) in [(0.4, 4.0), (1.0, 2.0)] {
        let m = rigid_block(b, h);
        let ex = Exact::new(&m);
        let theta0 = 0.8 * ex.alpha;
        let sim = Simulator::new(m, DEFAULT_RTOL);
        let exact = ex.impacts(theta0, 12);
        // end halfway between impacts 11 and 12
        let t_end = 0.5 * (exact[10].0 + exact[11].0);
        let mut long = sim.initial_state(theta0, 0.0);
        let ev = sim.advance(&mut long, t_end, GroundInput::default());
        let mut stepwise = sim.initial_state(theta0, 0.0);
        while stepwise.t < t_end {
            sim.advance_to_event(&mut stepwise, t_end, GroundInput::default());
        }
        // rigid: every zero crossing is an impact, in the closed-form
        // half-cycles too
        assert_eq!(long.impacts, 11);
        assert_eq!(stepwise.impacts, 11);
        assert_eq!(long.zero_crossings, 11);
        assert_eq!(stepwise.zero_crossings, 11);
        assert!(ev.stats.evals < 200, "{:?}", ev.stats);
        let d = (long.theta - stepwise.theta).abs() / ex.alpha
            + (long.omega - stepwise.omega).abs() / (ex.alpha * (ex.w_r0 / ex.io).sqrt());
        eprintln!(
            "alpha {:.3}: one call {} evaluations, state differs from event by event by {d:.1e}",
            ex.alpha, ev.stats.evals
        );
        assert!(d < 1e-8);
    }
    // chattering to rest inside one call: the rest time as event by event
    let m = rigid_block(1.0, 2.0);
    let sim = Simulator::new(m, DEFAULT_RTOL);
    let mut a = sim.initial_state(0.5 * m.body.alpha, 0.0);
    let mut b = a;
    let ev = sim.advance(&mut a, 20.0, GroundInput::default());
    assert!(a.at_rest && ev.came_to_rest);
    let mut t_rest = 0.0;
    while !b.at_rest {
        let ev = sim.advance_to_event(&mut b, 20.0, GroundInput::default());
        if ev.came_to_rest {
            t_rest = b.t;
        }
    }
    assert_eq!(a.impacts, b.impacts);
    assert_eq!(a.zero_crossings, a.impacts);
    assert_eq!(b.zero_crossings, b.impacts);
    eprintln!(
        "rest after {} impacts at {t_rest}; one call: {:?}",
        a.impacts, ev.stats
    );
    assert!(ev.stats.evals < 300);
}

#[test]
fn rigid_free_rocking_counts_every_crossing_as_an_impact() {
    // In output steps of 0.01 s (shorter than a half-cycle: the integrator,
    // not the closed form): at every output time both counts are the
    // number of exact impact times before it.
    let m = rigid_block(0.5, 2.5);
    let ex = Exact::new(&m);
    let theta0 = 0.6 * ex.alpha;
    let exact = ex.impacts(theta0, 12);
    let sim = Simulator::new(m, 1e-10);
    let mut st = sim.initial_state(theta0, 0.0);
    let mut checked = 0;
    let mut k = 0;
    while st.t < exact[11].0 {
        k += 1;
        sim.advance(&mut st, k as f64 * 0.01, GroundInput::default());
        if exact.iter().any(|(ti, _)| (ti - st.t).abs() < 1e-6) {
            continue;
        }
        let n = exact.iter().filter(|(ti, _)| *ti < st.t).count() as u64;
        assert_eq!(st.impacts, n, "t = {}", st.t);
        assert_eq!(st.zero_crossings, n, "t = {}", st.t);
        checked += 1;
    }
    assert_eq!(st.impacts, 12);
    assert!(checked > 100);
}

#[test]
fn rigid_forced_rocking_counts_every_crossing_as_an_impact() {
    // Shaking just above uplift for 60 s: many short chattering excursions,
    // some of which leave theta = 0 and return within one integration
    // step (both step ends at 0); each is still an impact (thetaJo = 0).
    let m = rigid_block(0.5, 2.5);
    let sim = Simulator::new(m, DEFAULT_RTOL);
    let thr = sim.uplift_acceleration();
    let ag = |t: f64| {
        1.05 * thr * (0.6 * (7.0 * t).sin() + 0.3 * (17.3 * t).sin() + 0.1 * (41.9 * t).sin())
    };
    let mut st = sim.initial_state(0.0, 0.0);
    for k in 0..6000 {
        let t = k as f64 * 0.01;
        let input = GroundInput {
            ag: ag(t),
            dag: (ag(t + 0.01) - ag(t)) / 0.01,
        };
        sim.advance(&mut st, t + 0.01, input);
        assert!(!st.overturned);
    }
    eprintln!(
        "60 s: {} zero crossings, {} impacts",
        st.zero_crossings, st.impacts
    );
    assert!(st.zero_crossings > 100);
    assert_eq!(st.impacts, st.zero_crossings);
}
