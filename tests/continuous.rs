//! The Model Exchange interface of the physics (`rocking::dynamics::continuous`)
//! driven by a host written here: classical RK4 at a fixed step, every sign
//! change of an event indicator located by bisection on the step length, the
//! event update applied there. Checked against the exact rigid free-rocking
//! solution (independent of the code under test), and against the
//! co-simulation integrator (a second host of the same equations) for the
//! flexible laws, uplift and overturning.

mod support;

use rocking::dynamics::continuous::{Continuous, EVENT_INDICATORS};
use rocking::dynamics::{GroundInput, Simulator, DEFAULT_RTOL};
use rocking::{Model, Params};
use support::exact::Exact;
use support::pulse::pulse;
use support::{crushing_block, rigid_block};

/// Records of a run.
#[derive(Default, Debug)]
struct Run {
    crossings: Vec<f64>,
    events: usize,
    rest_at: Option<f64>,
    overturned_at: Option<f64>,
}

/// The host: RK4 with step `h` from `c.state.t` to `t_end` under `ag(t)`.
struct Host<'a> {
    sim: &'a Simulator,
    ag: &'a dyn Fn(f64) -> f64,
    h: f64,
}

/// `z` changed sign between `a` and `b` (leaving 0 is not a crossing).
fn crossed(a: &[f64; EVENT_INDICATORS], b: &[f64; EVENT_INDICATORS]) -> bool {
    a.iter()
        .zip(b)
        .any(|(&x, &y)| (x > 0.0 && y <= 0.0) || (x < 0.0 && y >= 0.0))
}

impl Host<'_> {
    fn rk4(&self, c: &Continuous, dt: f64) -> Continuous {
        let f = |t: f64, y: [f64; 2]| {
            let mut s = *c;
            s.state.t = t;
            s.state.theta = y[0];
            s.state.omega = y[1];
            self.sim.derivatives(&s, (self.ag)(t))
        };
        let (t, y) = (c.state.t, [c.state.theta, c.state.omega]);
        let add = |k: [f64; 2], a: f64| [y[0] + a * k[0], y[1] + a * k[1]];
        let k1 = f(t, y);
        let k2 = f(t + dt / 2.0, add(k1, dt / 2.0));
        let k3 = f(t + dt / 2.0, add(k2, dt / 2.0));
        let k4 = f(t + dt, add(k3, dt));
        let mut out = *c;
        out.state.t = t + dt;
        for i in 0..2 {
            let d = dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            if i == 0 {
                out.state.theta += d;
            } else {
                out.state.omega += d;
            }
        }
        out
    }

    fn z(&self, c: &Continuous) -> [f64; EVENT_INDICATORS] {
        self.sim.event_indicators(c, (self.ag)(c.state.t))
    }

    /// Runs to `t_end`, to overturning or until `stop(run)`.
    fn run(&self, c: &mut Continuous, t_end: f64, stop: &dyn Fn(&Run) -> bool) -> Run {
        let mut r = Run::default();
        let mut z0 = self.z(c);
        while c.state.t < t_end && !stop(&r) {
            let dt = self.h.min(t_end - c.state.t);
            let mut next = self.rk4(c, dt);
            if crossed(&z0, &self.z(&next)) {
                // bisection on the step length: [lo, hi] brackets the first change
                let (mut lo, mut hi) = (0.0, dt);
                while hi - lo > 1e-15 * (1.0 + c.state.t) {
                    let mid = 0.5 * (lo + hi);
                    if mid <= lo || mid >= hi {
                        break;
                    }
                    if crossed(&z0, &self.z(&self.rk4(c, mid))) {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                next = self.rk4(c, hi);
                *c = next;
                self.sim.completed_step(c);
                let u = self.sim.event_update(c, (self.ag)(c.state.t));
                r.events += 1;
                if u.crossing {
                    r.crossings.push(c.state.t);
                }
                if u.came_to_rest {
                    r.rest_at = Some(c.state.t);
                }
                if u.overturned {
                    r.overturned_at = Some(c.state.t);
                    return r;
                }
            } else {
                *c = next;
                if self.sim.completed_step(c) {
                    panic!("a crossing without a sign change at t = {}", c.state.t);
                }
            }
            z0 = self.z(c);
        }
        r
    }
}

fn no_input(_: f64) -> f64 {
    0.0
}

impl<'a> Host<'a> {
    /// Free rocking, RK4 steps of 1 ms.
    fn unforced(sim: &'a Simulator) -> Host<'a> {
        Host {
            sim,
            ag: &no_input,
            h: 1e-3,
        }
    }
}

/// A rigid 0.25 m x 1 m block at the default tolerance, its exact
/// solution, and the release rotation `fraction` alpha, rad.
fn released(fraction: f64) -> (Simulator, Exact, f64) {
    let m = rigid_block(0.25, 1.0);
    let ex = Exact::new(&m);
    let theta0 = fraction * ex.alpha;
    (Simulator::new(m, DEFAULT_RTOL), ex, theta0)
}

#[test]
fn rigid_free_rocking_matches_exact_impact_times() {
    let (sim, ex, theta0) = released(0.5);
    let exact = ex.impacts(theta0, 10);
    let host = Host::unforced(&sim);
    let mut c = sim.continuous(theta0, 0.0, 0.0);
    let r = host.run(&mut c, 100.0, &|r| r.crossings.len() >= 10);
    assert_eq!(r.crossings.len(), 10, "{r:?}");
    let mut worst = 0.0f64;
    for (i, (&(te, _), &tg)) in exact.iter().zip(&r.crossings).enumerate() {
        let e = (tg - te).abs() / te;
        worst = worst.max(e);
        assert!(e < 1e-9, "impact {}: {tg} vs exact {te} ({e:.1e})", i + 1);
    }
    eprintln!("ME, RK4 h = 1e-3: worst relative impact-time error over 10 impacts {worst:.1e}");
    assert_eq!(c.state.impacts, 10);
    assert_eq!(c.state.zero_crossings, 10);
}

#[test]
fn rigid_block_from_0_9_alpha_comes_to_rest_after_a_bounded_number_of_events() {
    let (sim, ex, theta0) = released(0.9);
    let host = Host::unforced(&sim);
    let mut c = sim.continuous(theta0, 0.0, 0.0);
    let r = host.run(&mut c, 1e3, &|r| r.rest_at.is_some());
    let t_rest = r.rest_at.expect("comes to rest");
    // each impact multiplies |omega| by eta; rest is declared once |omega|
    // is below rtol times its scale, which the first one is not above
    let bound = (DEFAULT_RTOL.ln() / ex.eta.ln()).ceil() as usize + 2;
    assert!(r.events <= bound, "{} events, bound {bound}", r.events);
    // the exact accumulation time: the impacts' times converge geometrically
    let exact = ex.impacts(theta0, 2000);
    let t_acc = exact[exact.len() - 1].0;
    assert!(
        (t_rest - t_acc).abs() < 1e-6 * t_acc,
        "rest at {t_rest}, exact accumulation {t_acc}"
    );
    eprintln!(
        "ME rest: {} events (bound {bound}), rest at {t_rest:.9} s, exact {t_acc:.9} s",
        r.events
    );
    // and it stays there
    let r2 = host.run(&mut c, t_rest + 5.0, &|_| false);
    assert_eq!(r2.events, 0);
    assert!(c.state.at_rest && c.state.theta == 0.0 && c.state.omega == 0.0);
}

/// Co-simulation of the same model under piecewise-linear `ag` on a grid of
/// `dt`; returns `theta` at each grid point and the overturning time.
fn cosim(sim: &Simulator, ag: &dyn Fn(f64) -> f64, dt: f64, n: usize) -> (Vec<f64>, Option<f64>) {
    let mut st = sim.initial_state(0.0, 0.0);
    let mut out = vec![st.theta];
    for k in 0..n {
        let (t0, t1) = (k as f64 * dt, (k + 1) as f64 * dt);
        let input = GroundInput {
            ag: ag(t0),
            dag: (ag(t1) - ag(t0)) / dt,
        };
        let ev = sim.advance(&mut st, t1, input);
        if let Some(t) = ev.overturned_at {
            return (out, Some(t));
        }
        out.push(st.theta);
    }
    (out, None)
}

/// ME under the pulse, sampled on the co-simulation grid.
fn me(sim: &Simulator, ag: &dyn Fn(f64) -> f64, dt: f64, n: usize) -> (Vec<f64>, Run) {
    let host = Host {
        sim,
        ag,
        h: dt / 20.0,
    };
    let mut c = sim.continuous(0.0, 0.0, ag(0.0));
    let mut out = vec![c.state.theta];
    let mut all = Run::default();
    for k in 0..n {
        let r = host.run(&mut c, (k + 1) as f64 * dt, &|_| false);
        all.events += r.events;
        all.crossings.extend(r.crossings);
        if r.overturned_at.is_some() {
            all.overturned_at = r.overturned_at;
            return (out, all);
        }
        out.push(c.state.theta);
    }
    (out, all)
}

fn compare(m: Model, a_over_uplift: f64, tp: f64, n: usize, tol: f64) -> Run {
    let sim = Simulator::new(m, 1e-10);
    let dt = 0.01;
    let ag = pulse(-a_over_uplift * sim.uplift_acceleration(), tp, dt);
    let (cs, cs_ov) = cosim(&sim, &ag, dt, n);
    let (me_theta, run) = me(&sim, &ag, dt, n);
    let scale = sim.model.theta_ov;
    let worst = cs
        .iter()
        .zip(&me_theta)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    eprintln!(
        "{:?}: {} samples, max |theta_ME - theta_CS| / thetaOv = {:.1e}, {} events, overturned CS {cs_ov:?} ME {:?}",
        sim.model.interface.law(),
        cs.len().min(me_theta.len()),
        worst / scale,
        run.events,
        run.overturned_at
    );
    assert!(worst <= tol * scale, "{worst:e}");
    assert_eq!(cs.len(), me_theta.len());
    match (cs_ov, run.overturned_at) {
        (Some(a), Some(b)) => assert!((a - b).abs() < 1e-6, "overturning {a} vs {b}"),
        (None, None) => {}
        other => panic!("overturning differs: {other:?}"),
    }
    run
}

#[test]
fn rigid_uplift_rocking_and_overturning_match_co_simulation() {
    // rocks and survives
    let r = compare(rigid_block(0.25, 1.0), 1.3, 0.25, 300, 1e-7);
    assert!(r.crossings.len() >= 2, "{r:?}");
    // overturns
    let r = compare(rigid_block(0.25, 1.0), 3.0, 1.0, 300, 1e-7);
    assert!(r.overturned_at.is_some());
}

#[test]
fn elastic_and_crushing_interfaces_match_co_simulation() {
    let elastic = Params {
        kn: 1e8,
        interface: rocking::model::LawKind::Elastic,
        ..Params::default()
    }
    .build()
    .unwrap();
    let r = compare(elastic, 1.5, 0.5, 300, 1e-6);
    assert!(!r.crossings.is_empty());
    let r = compare(crushing_block(), 1.5, 0.5, 300, 1e-6);
    assert!(!r.crossings.is_empty());
}

/// Explicit Euler at a fixed step, indicators checked at step ends only (as
/// fmpy's Euler does): the state events come late, and the chattering
/// settles into impacts every few steps whose speed does not decay. The
/// event update must still bring the block to rest after a bounded number
/// of events.
#[test]
fn rigid_rest_under_explicit_euler_ends_the_chattering() {
    let m = rigid_block(0.25, 1.0);
    let ex = Exact::new(&m);
    let sim = Simulator::new(m, DEFAULT_RTOL);
    let h = 1e-3;
    let mut c = sim.continuous(0.9 * ex.alpha, 0.0, 0.0);
    let mut z0 = sim.event_indicators(&c, 0.0);
    let mut events = 0;
    while !c.state.at_rest {
        assert!(c.state.t < 60.0, "no rest after {events} events: {c:?}");
        let d = sim.derivatives(&c, 0.0);
        c.state.t += h;
        c.state.theta += h * d[0];
        c.state.omega += h * d[1];
        let step_event = sim.completed_step(&mut c);
        let z = sim.event_indicators(&c, 0.0);
        if step_event || crossed(&z0, &z) {
            events += 1;
            sim.event_update(&mut c, 0.0);
        }
        z0 = sim.event_indicators(&c, 0.0);
    }
    let t_acc = ex.impacts(0.9 * ex.alpha, 2000)[1999].0;
    eprintln!(
        "Euler h = {h}: rest at {:.4} s after {events} events (exact accumulation {t_acc:.4} s)",
        c.state.t
    );
    assert!(events < 400, "{events}");
    assert!((c.state.t - t_acc).abs() < 0.05 * t_acc);
}
