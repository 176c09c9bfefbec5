//! The outputs (docs/model.md §5) against the trajectory itself: `theta''`, and
//! the support forces `Fx = m (ag + xG'')`, `Fz = m (g + zG'')` against
//! 5-point central differences (error O(dt^4)) of `xG = s (b - R0 sin(alpha - phi))`,
//! `zG = R0 cos(alpha - phi)` sampled along the motion; for the rigid law
//! the balance of moments about G (Newton-Euler, written here, not taken
//! from the code); at rest `Fx = m ag`, `Fz = W`.

mod dyncommon;

use dyncommon::rigid_block;
use rocking::dynamics::{GroundInput, Simulator, State};
use rocking::{Model, Params};

/// `(xG, zG)` of the rigid rotation about the active toe.
fn g_position(m: &Model, st: &State) -> (f64, f64) {
    let b = &m.body;
    let s = if st.theta != 0.0 {
        st.theta.signum()
    } else {
        st.omega.signum()
    };
    let phi = st.theta.abs();
    (
        s * (b.b - b.r0 * (b.alpha - phi).sin()),
        b.r0 * (b.alpha - phi).cos(),
    )
}

/// Samples every `dt` while the body rocks under a constant `ag`; checks the
/// outputs at each interior sample whose neighbours are on the same side.
fn check_forces(m: Model, theta0: f64, ag: f64, dt: f64, n: usize) -> (f64, f64, f64) {
    let sim = Simulator::new(m, 1e-12);
    let b = m.body;
    let input = GroundInput { ag, dag: 0.0 };
    let mut st = sim.initial_state(theta0, 0.0);
    let mut samples = vec![st];
    for k in 1..=n {
        sim.advance(&mut st, k as f64 * dt, input);
        assert!(!st.overturned);
        samples.push(st);
    }
    let (mut worst_dd, mut worst_fx, mut worst_fz) = (0.0f64, 0.0f64, 0.0f64);
    let mut checked = 0;
    for w in samples.windows(5) {
        let (c, ends) = (&w[2], [&w[0], &w[4]]);
        // same side, no impact in the window, and away from theta = 0,
        // where the flexible contact changes fast
        if ends[0].impacts != ends[1].impacts
            || w.iter().any(|s| s.theta * c.theta <= 0.0)
            || c.theta.abs() < 0.05 * b.alpha
        {
            continue;
        }
        checked += 1;
        let o = sim.outputs(c, ag);
        let fd = |f: &dyn Fn(&State) -> f64| {
            (-f(&w[0]) + 16.0 * f(&w[1]) - 30.0 * f(&w[2]) + 16.0 * f(&w[3]) - f(&w[4]))
                / (12.0 * dt * dt)
        };
        let theta_dd = fd(&|s| s.theta);
        let xg_dd = fd(&|s| g_position(&m, s).0);
        let zg_dd = fd(&|s| g_position(&m, s).1);
        worst_dd = worst_dd.max((o.theta_dd - theta_dd).abs());
        worst_fx = worst_fx.max((o.fx - b.mass * (ag + xg_dd)).abs() / b.weight);
        worst_fz = worst_fz.max((o.fz - b.mass * (b.g + zg_dd)).abs() / b.weight);
    }
    assert!(checked > n / 4, "only {checked} samples checked");
    (worst_dd, worst_fx, worst_fz)
}

#[test]
fn rigid_forces_match_finite_differences_of_the_trajectory() {
    for (b, h) in [(0.4, 4.0), (1.0, 2.0)] {
        let m = rigid_block(b, h);
        let alpha = m.body.alpha;
        for ag in [0.0, 0.1 * m.body.g * alpha.tan()] {
            let (dd, fx, fz) = check_forces(m, 0.3 * alpha, ag, 1e-3, 3000);
            eprintln!(
                "rigid alpha {alpha:.3}, ag {ag:.3}: |theta'' - FD| {dd:.1e} rad/s², |Fx - FD|/W {fx:.1e}, |Fz - FD|/W {fz:.1e}"
            );
            assert!(dd < 1e-6 && fx < 1e-7 && fz < 1e-7);
        }
    }
}

#[test]
fn flexible_forces_match_finite_differences_of_the_trajectory() {
    let m = Params {
        kn: 1e8,
        fm: 2e6,
        ..Params::default()
    }
    .build()
    .unwrap();
    let (dd, fx, fz) = check_forces(m, 0.6 * m.theta_ov, 0.0, 1e-3, 3000);
    eprintln!(
        "flexible: |theta'' - FD| {dd:.1e} rad/s², |Fx - FD|/W {fx:.1e}, |Fz - FD|/W {fz:.1e}"
    );
    assert!(dd < 1e-6 && fx < 1e-7 && fz < 1e-7);
}

#[test]
fn rigid_support_force_balances_the_moment_about_g() {
    // The support force acts at the toe (s b, 0); about G its moment drives
    // the rotation: -Ic theta'' = s R0 sin(alpha - phi) Fz + R0 cos(alpha - phi) Fx
    // (theta > 0 turns G toward +x, clockwise in (x, z)).
    let m = rigid_block(0.6, 3.0);
    let b = m.body;
    let sim = Simulator::new(m, 1e-10);
    let thr = b.g * b.alpha.tan();
    let mut st = sim.initial_state(0.0, 0.0);
    let mut worst = 0.0f64;
    let mut checked = 0;
    for k in 1..=4000 {
        let t0 = (k - 1) as f64 * 1e-3;
        let ag = -1.4 * thr * (std::f64::consts::PI * t0).sin();
        sim.advance(&mut st, k as f64 * 1e-3, GroundInput { ag, dag: 0.0 });
        if st.at_rest || st.overturned || st.theta == 0.0 {
            continue;
        }
        checked += 1;
        let o = sim.outputs(&st, ag);
        let s = st.theta.signum();
        let u = b.alpha - st.theta.abs();
        let lhs = -b.ic * o.theta_dd;
        let rhs = s * b.r0 * u.sin() * o.fz + b.r0 * u.cos() * o.fx;
        worst = worst.max((lhs - rhs).abs() / (b.weight * b.r0));
    }
    eprintln!("moment balance about G: {checked} states, worst {worst:.1e} W R0");
    assert!(checked > 1000);
    assert!(worst < 1e-12);
}

#[test]
fn at_rest_the_support_carries_the_weight_and_the_ground_inertia() {
    for m in [rigid_block(0.5, 2.5), Params::default().build().unwrap()] {
        let b = m.body;
        let sim = Simulator::new(m, 1e-9);
        let mut st = sim.initial_state(0.0, 0.0);
        // rigid: below the uplift threshold it stays at rest; flexible: at
        // rest while ag = 0
        let ag = if st.at_rest && m.interface.law() == rocking::Law::Rigid {
            0.5 * sim.uplift_acceleration()
        } else {
            0.0
        };
        sim.advance(&mut st, 1.0, GroundInput { ag, dag: 0.0 });
        assert!(st.at_rest, "{st:?}");
        let o = sim.outputs(&st, ag);
        assert_eq!(o.fz, b.weight);
        assert_eq!(o.fx, b.mass * ag);
        assert_eq!(o.theta_dd, 0.0);
        assert_eq!(o.mr, 0.0);
    }
}
