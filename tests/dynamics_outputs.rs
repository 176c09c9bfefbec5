//! The outputs (docs/model.md §5) against the trajectory itself: `theta''`, and
//! the support forces `Fx = m (ag + xG'')`, `Fz = m (g + zG'')` against
//! 5-point central differences (error O(dt^4)) of the position of G sampled
//! along the motion: for the rigid law G turns about the toe,
//! `xG = s (b - R0 sin(alpha - phi))`, `zG = R0 cos(alpha - phi)`; for the
//! flexible laws G moves as the equation of motion implies (G turning about
//! the interface resultant, `xG' = hg omega`, `zG' = s hW omega`), so
//! `xG = s ∫_0^phi hg`, `zG = hG + ∫_0^phi hW`, here by quadrature of the
//! levers written from `af` (not the code's derivatives). For the rigid law
//! also the closed form of G turning about the toe and the balance of
//! moments about G (Newton-Euler, written here, not taken from the code).
//! At rest `Fx = m ag`, `Fz = W`; a body at rest that `ag` sets moving gets
//! the `theta''` it starts with (against `omega(h) / h`).

mod support;

use rocking::dynamics::{GroundInput, Simulator, State};
use rocking::model::LawKind;
use rocking::{Law, Model, Params};
use support::{crushing_block, moment_breaks, quad_adaptive, rigid_block};

/// The side of the motion: the sign of `theta`, at `theta = 0` of `omega`.
fn side(st: &State) -> f64 {
    if st.theta != 0.0 {
        st.theta.signum()
    } else {
        st.omega.signum()
    }
}

/// `(xG, zG)` of the rigid rotation about the active toe.
fn g_position(m: &Model, st: &State) -> (f64, f64) {
    let b = &m.body;
    let phi = st.theta.abs();
    (
        side(st) * (b.b - b.r0 * (b.alpha - phi).sin()),
        b.r0 * (b.alpha - phi).cos(),
    )
}

/// The levers `(hg, hW)` at `phi`, written from the reaction's position `af`.
fn levers_from_af(m: &Model, phi: f64) -> (f64, f64) {
    let b = &m.body;
    let af = m.interface.contact(phi).af;
    (
        b.r0 * (b.alpha - phi).cos() - af * phi.sin(),
        b.r0 * (b.alpha - phi).sin() - af * phi.cos(),
    )
}

/// `(xG, zG)` of G moving as the equation of motion implies:
/// `xG = s ∫_0^phi hg`, `zG = hG + ∫_0^phi hW` (quadrature between the
/// non-smooth points of the contact).
fn g_position_flexible(m: &Model, breaks: &[f64], st: &State) -> (f64, f64) {
    let phi = st.theta.abs();
    let mut pts = vec![0.0];
    pts.extend(breaks.iter().copied().filter(|&x| x > 0.0 && x < phi));
    pts.push(phi);
    let (mut x, mut z) = (0.0, m.body.hg);
    for w in pts.windows(2) {
        x += quad_adaptive(&|p| levers_from_af(m, p).0, w[0], w[1], 1e-13);
        z += quad_adaptive(&|p| levers_from_af(m, p).1, w[0], w[1], 1e-13);
    }
    (side(st) * x, z)
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
    let rigid = m.interface.law() == Law::Rigid;
    let breaks = moment_breaks(&m, m.theta_ov);
    // the position of G at every sample
    let positions: Vec<(f64, f64)> = samples
        .iter()
        .map(|s| {
            if rigid {
                g_position(&m, s)
            } else {
                g_position_flexible(&m, &breaks, s)
            }
        })
        .collect();
    for i in 2..samples.len() - 2 {
        let w = &samples[i - 2..=i + 2];
        let (c, ends) = (&w[2], [&w[0], &w[4]]);
        // same side, no crossing in the window, and away from theta = 0,
        // where the flexible contact changes fast
        if ends[0].zero_crossings != ends[1].zero_crossings
            || w.iter().any(|s| s.theta * c.theta <= 0.0)
            || c.theta.abs() < 0.05 * b.alpha
        {
            continue;
        }
        checked += 1;
        let o = sim.outputs(c, ag);
        let fd = |f: &dyn Fn(usize) -> f64| {
            (-f(i - 2) + 16.0 * f(i - 1) - 30.0 * f(i) + 16.0 * f(i + 1) - f(i + 2))
                / (12.0 * dt * dt)
        };
        let theta_dd = fd(&|k| samples[k].theta);
        let xg_dd = fd(&|k| positions[k].0);
        let zg_dd = fd(&|k| positions[k].1);
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
    let m = crushing_block();
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

#[test]
fn rigid_support_forces_are_g_turning_about_the_toe() {
    // Closed form of G turning rigidly about the toe, written here:
    // xG'' = R0 (cos(alpha - phi) theta'' + s sin(alpha - phi) omega²),
    // zG'' = R0 (s sin(alpha - phi) theta'' - cos(alpha - phi) omega²).
    let m = rigid_block(0.6, 3.0);
    let b = m.body;
    let sim = Simulator::new(m, 1e-10);
    let thr = sim.uplift_acceleration();
    let mut st = sim.initial_state(0.0, 0.0);
    let (mut worst, mut checked) = (0.0f64, 0);
    for k in 1..=4000 {
        let t0 = (k - 1) as f64 * 1e-3;
        let ag = -1.4 * thr * (std::f64::consts::PI * t0).sin();
        sim.advance(&mut st, k as f64 * 1e-3, GroundInput { ag, dag: 0.0 });
        if st.at_rest || st.overturned {
            continue;
        }
        checked += 1;
        let o = sim.outputs(&st, ag);
        let s = side(&st);
        let u = b.alpha - st.theta.abs();
        let w2 = st.omega * st.omega;
        let xg_dd = b.r0 * (u.cos() * o.theta_dd + s * u.sin() * w2);
        let zg_dd = b.r0 * (s * u.sin() * o.theta_dd - u.cos() * w2);
        worst = worst
            .max((o.fx - b.mass * (ag + xg_dd)).abs() / b.weight)
            .max((o.fz - b.mass * (b.g + zg_dd)).abs() / b.weight);
    }
    eprintln!("rigid: Fx, Fz against G about the toe: {checked} states, worst {worst:.1e} W");
    assert!(checked > 1000);
    assert!(worst < 1e-13);
}

/// `(theta''(0), omega(h) / h)` of a body at rest at `t = 0` under a
/// constant `ag`, `h` the last of a halving sequence where the forward
/// difference has converged (`omega(h) = theta''(0) h + O(h²)`).
fn start_from_rest(m: Model, ag: f64) -> (f64, f64) {
    let sim = Simulator::new(m, 1e-13);
    let st = sim.initial_state(0.0, 0.0);
    let dd = sim.outputs(&st, ag).theta_dd;
    let mut h = 1e-3;
    let mut prev = f64::NAN;
    for _ in 0..30 {
        let mut s = st;
        sim.advance(&mut s, h, GroundInput { ag, dag: 0.0 });
        let fd = s.omega / h;
        if (fd - prev).abs() <= 1e-7 * fd.abs() {
            return (dd, fd);
        }
        prev = fd;
        h *= 0.5;
    }
    (dd, prev)
}

#[test]
fn a_body_at_rest_that_ag_moves_starts_with_the_equation_of_motion() {
    let flexible = |law| {
        Params {
            interface: law,
            ..Params::default()
        }
        .build()
        .unwrap()
    };
    let rigid = rigid_block(0.5, 2.5);
    let thr = Simulator::new(rigid, 1e-9).uplift_acceleration();
    let cases = [
        ("elastic", flexible(LawKind::Elastic), 1.0),
        ("elastoPlastic", flexible(LawKind::ElastoPlastic), -1.0),
        ("rigid below uplift", rigid, 0.9 * thr),
        ("rigid above uplift", rigid, 1.1 * thr),
        ("rigid above uplift, ag < 0", rigid, -1.1 * thr),
    ];
    for (name, m, ag) in cases {
        let b = m.body;
        let (dd, fd) = start_from_rest(m, ag);
        let st = Simulator::new(m, 1e-9).initial_state(0.0, 0.0);
        let o = Simulator::new(m, 1e-9).outputs(&st, ag);
        eprintln!("{name}, ag = {ag:.3}: theta''(0) = {dd:.6e}, omega(h)/h = {fd:.6e}");
        assert!(
            (dd - fd).abs() <= 1e-6 * fd.abs().max(1e-12),
            "{name}: {dd} vs {fd}"
        );
        // flexible: any ag moves the body (theta'' = -m ag hG / I(0)); rigid
        // only beyond g tan(alpha)
        let moves = m.interface.law() != Law::Rigid || ag.abs() > thr;
        assert_eq!(dd != 0.0, moves, "{name}");
        if moves {
            // the side ag pushes it to
            assert_eq!(dd.signum(), -ag.signum(), "{name}");
        }
        // the support: at omega = 0, Fx = m (ag + hg theta''),
        // Fz = W + m s hW theta'', hg(0) = hG, hW(0) = 0 (flexible) or b
        // (rigid, on its toe)
        let hw0 = if m.interface.law() == Law::Rigid && moves {
            b.b
        } else {
            0.0
        };
        let s = -ag.signum();
        assert!((o.fx - b.mass * (ag + b.hg * dd)).abs() <= 1e-12 * b.weight);
        assert!((o.fz - (b.weight + b.mass * s * hw0 * dd)).abs() <= 1e-12 * b.weight);
    }
}
