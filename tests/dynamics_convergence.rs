//! Convergence on a forced flexible case: a block on an elasto-plastic
//! interface (`kn = 1e8 Pa/m`, crushing) lifted by a triangular ground pulse,
//! rocking with impacts for 4 s.
//!
//! - Against the same code at a tolerance 1e-4 times tighter: the error
//!   falls in proportion to `rtol`, and against the work at the order of the
//!   method (8 for DOP853, 5 for DP5) within the spread of the events.
//! - Against a second integrator (`support::rk4`, also the benchmark's):
//!   fixed-step classical RK4 on the equation of motion of docs/model.md §3
//!   (from `contact` and `levers`), impacts located by bisection on the RK4
//!   step, Richardson-checked.

mod support;

use rocking::dynamics::{GroundInput, Method, Simulator, State};
use rocking::Model;
use support::crushing_block;
use support::rk4::{flexible_accel, Rk4};

const T_END: f64 = 4.0;

/// The pulse: linear pieces `(t0, t1, ag0, ag1)`, then zero.
fn pulse(m: &Model) -> Vec<(f64, f64, f64, f64)> {
    let a = -1.2 * m.body.g * m.body.alpha.tan();
    vec![
        (0.0, 0.2, 0.0, a),
        (0.2, 0.6, a, -a),
        (0.6, 0.8, -a, 0.0),
        (0.8, T_END, 0.0, 0.0),
    ]
}

/// Runs one call per linear piece; returns the final state and the
/// right-hand-side evaluations.
fn run(m: &Model, rtol: f64, method: Method) -> (State, u32) {
    let sim = Simulator::with_method(*m, rtol, method);
    let mut st = sim.initial_state(0.0, 0.0);
    let mut evals = 0;
    for (t0, t1, a0, a1) in pulse(m) {
        let ev = sim.advance(
            &mut st,
            t1,
            GroundInput {
                ag: a0,
                dag: (a1 - a0) / (t1 - t0),
            },
        );
        evals += ev.stats.evals;
        assert!(!st.overturned);
    }
    (st, evals)
}

/// Fixed-step RK4 with step `h` (a divisor of the pieces), started on the
/// toe the pulse pushes the body to.
fn rk4(m: &Model, h: f64) -> State {
    let pieces = pulse(m);
    let ag = |t: f64| {
        let &(t0, t1, a0, a1) = pieces.iter().find(|p| t <= p.1).unwrap_or(&pieces[3]);
        a0 + (a1 - a0) / (t1 - t0) * (t - t0)
    };
    let accel =
        |t: f64, theta: f64, omega: f64, side: f64| flexible_accel(m, ag(t), theta, omega, side);
    let out = Rk4 {
        accel: &accel,
        eta: m.eta,
        theta_ov: m.theta_ov,
        h,
        max_impacts: usize::MAX,
    }
    .run([0.0, 0.0], -pieces[0].3.signum(), T_END);
    let mut st = Simulator::new(*m, 1e-9).initial_state(out.end[0], out.end[1]);
    st.t = T_END;
    st.impacts = out.impacts.len() as u64;
    st
}

/// Error of `(theta, omega)` at `T_END` in the scaled norm of the motion.
fn err(m: &Model, a: &State, b: &State) -> f64 {
    let p = (m.body.weight * m.body.r0 / m.body.io).sqrt();
    let scale = m.theta_ov;
    ((a.theta - b.theta).abs() / scale).max((a.omega - b.omega).abs() / (p * scale))
}

#[test]
fn error_falls_with_the_tolerance_at_the_order_of_the_method() {
    let m = crushing_block();
    for (method, order) in [(Method::Dop853, 8.0), (Method::Dp5, 5.0)] {
        let mut rows = Vec::new();
        for k in 5..=10 {
            let rtol = 10f64.powi(-k);
            let (st, evals) = run(&m, rtol, method);
            let (reference, _) = run(&m, rtol * 1e-4, method);
            assert_eq!(st.impacts, reference.impacts);
            rows.push((rtol, err(&m, &st, &reference), evals as f64));
        }
        for r in &rows {
            eprintln!(
                "{method:?} rtol {:.0e}: error {:.2e} ({:.2} rtol), evaluations {}",
                r.0,
                r.1,
                r.1 / r.0,
                r.2
            );
        }
        // tolerance proportionality: error within [1e-3, 100] x rtol
        for r in &rows {
            assert!(r.1 < 100.0 * r.0 && r.1 > 1e-3 * r.0, "{method:?}: {r:?}");
        }
        // order: least-squares slope of log(error) against log(work)
        let n = rows.len() as f64;
        let xs: Vec<f64> = rows.iter().map(|r| r.2.ln()).collect();
        let ys: Vec<f64> = rows.iter().map(|r| r.1.ln()).collect();
        let mx = xs.iter().sum::<f64>() / n;
        let my = ys.iter().sum::<f64>() / n;
        let slope = xs
            .iter()
            .zip(&ys)
            .map(|(x, y)| (x - mx) * (y - my))
            .sum::<f64>()
            / xs.iter().map(|x| (x - mx).powi(2)).sum::<f64>();
        eprintln!("{method:?}: error ~ work^{slope:.2} (method order {order})");
        assert!(
            -slope > 0.6 * order && -slope < 1.5 * order,
            "{method:?}: slope {slope}"
        );
    }
}

#[test]
fn agrees_with_an_independent_fixed_step_rk4() {
    let m = crushing_block();
    let fine = rk4(&m, 2.5e-5);
    let coarse = rk4(&m, 5e-5);
    // Richardson: the fine RK4's own error is about |fine - coarse| / 15
    let rk4_err = err(&m, &fine, &coarse) / 15.0;
    let (ours, _) = run(&m, 1e-12, Method::Dop853);
    let diff = err(&m, &ours, &fine);
    eprintln!(
        "RK4 (h = 2.5e-5): {} impacts, own error ~{rk4_err:.1e}; DOP853 at 1e-12: {} impacts, difference {diff:.1e}",
        fine.impacts, ours.impacts
    );
    assert_eq!(fine.impacts, ours.impacts);
    assert!(diff < 10.0 * rk4_err + 1e-10, "difference {diff:.2e}");
}
