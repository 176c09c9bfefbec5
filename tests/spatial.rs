//! The round body in space on a rigid bed (docs/model.md §10) against
//! independent references: the planar model in a plane, rotated inputs,
//! the closed form of steady wobbling, and the energy.

use rocking::dynamics::{GroundInput, Simulator, VerticalInput};
use rocking::model::Restitution;
use rocking::spatial::{PlanInput, Spatial, SpatialState};
use rocking::Params;

mod support;
use support::drum::{drum, pulse_train, vertical, DT};
use support::rotated::{assert_rotates, run_rotated};

const RTOL: f64 = 1e-12;

/// The planar run and the spatial run along `+x`, sampled every `DT`:
/// `(theta_planar, theta_spatial, |e_y| + |omega_x| + |omega_z|)`.
fn planar_and_spatial(p: &Params, with_av: bool, theta0: f64, t_end: f64) -> Vec<(f64, f64, f64)> {
    let planar = Simulator::new(p.build().unwrap(), RTOL);
    let spatial = Spatial::new(p, None, RTOL).unwrap();
    let mut a = planar.initial_state(theta0, 0.0);
    let mut b = SpatialState::tilted(&spatial, theta0, 0.0, [0.0; 3]);
    let av = |t: f64| if with_av { vertical(t) } else { 0.0 };
    let mut out = vec![];
    let n = (t_end / DT).round() as usize;
    for k in 0..n {
        let (t0, t1) = (k as f64 * DT, (k + 1) as f64 * DT);
        let dag = (pulse_train(t1) - pulse_train(t0)) / DT;
        let dav = (av(t1) - av(t0)) / DT;
        let v = VerticalInput { av: av(t0), dav };
        planar.advance_vertical(
            &mut a,
            t1,
            GroundInput {
                ag: pulse_train(t0),
                dag,
            },
            v,
        );
        let h = PlanInput {
            a: [pulse_train(t0), 0.0],
            da: [dag, 0.0],
        };
        spatial.advance(&mut b, t1, h, v);
        let off_plane = b.e[1].abs() + b.omega[0].abs() + b.omega[2].abs();
        out.push((a.theta, b.e[0].asin(), off_plane));
        assert_eq!(a.impacts, b.impacts, "impacts at t = {t1}");
        assert_eq!(a.overturned, b.overturned);
    }
    out
}

#[test]
fn in_a_plane_the_spatial_body_is_the_planar_rigid_model() {
    for restitution in [Restitution::Housner, Restitution::Given] {
        for with_av in [false, true] {
            for theta0 in [0.0, 0.15] {
                let p = drum(restitution, false);
                let run = planar_and_spatial(&p, with_av, theta0, 6.0);
                let worst = run
                    .iter()
                    .map(|(a, b, _)| (a - b).abs())
                    .fold(0.0, f64::max);
                let peak = run.iter().map(|(a, _, _)| a.abs()).fold(0.0, f64::max);
                let off = run.iter().map(|r| r.2).fold(0.0, f64::max);
                eprintln!("{restitution:?} av {with_av} theta0 {theta0}: worst {worst:.2e} rad, peak {peak:.3}");
                assert!(peak > 0.05, "the run must rock: peak {peak}");
                assert!(
                    worst <= 1e-10,
                    "{restitution:?} av {with_av}: {worst:e} rad"
                );
                assert_eq!(off, 0.0, "the motion stays in its plane exactly");
            }
        }
    }
}

#[test]
fn a_rotated_input_rotates_the_response() {
    let p = drum(Restitution::Housner, true);
    let spatial = Spatial::new(&p, None, RTOL).unwrap();
    let two = |t: f64| [pulse_train(t), 0.7 * pulse_train(1.37 * t + 0.2)];
    let planar = |t: f64| [pulse_train(t), 0.0];
    for (name, ag) in [
        ("planar", &planar as &dyn Fn(f64) -> [f64; 2]),
        ("two components", &two),
    ] {
        // no vertical input: `VerticalInput` zero, as on the rigid bed of §10
        let no_av = |_: f64| 0.0;
        let base = run_rotated(&spatial, SpatialState::at_rest(), (ag, &no_av), 0.0, 4.0);
        for beta in [0.3, 2.1, -1.0] {
            let turned = run_rotated(&spatial, SpatialState::at_rest(), (ag, &no_av), beta, 4.0);
            assert_rotates(name, beta, &base, &turned);
        }
    }
}

/// Steady wobbling with the centre of mass at rest (docs/model.md §10.5):
/// `omega = (Omega sin(theta)/R) r` and
/// `Omega² = m g R (hg sin - R cos) / (sin (C hg sin - A R cos))`.
#[test]
fn steady_wobbling_precesses_at_the_closed_form_rate() {
    for (hollow, h) in [(false, 3.0), (true, 3.0), (false, 1.2)] {
        let p = Params {
            h,
            ..drum(Restitution::Housner, hollow)
        };
        let spatial = Spatial::new(&p, None, RTOL).unwrap();
        let b = &spatial.model.body;
        let (m, g, r, hg, a, c) = (b.mass, b.g, spatial.radius, b.hg, b.ic, spatial.c_axial);
        for theta in [0.02f64, 0.1, 0.5 * b.alpha] {
            let (s, co) = theta.sin_cos();
            let rate2 = m * g * r * (hg * s - r * co) / (s * (c * hg * s - a * r * co));
            assert!(rate2 > 0.0);
            let rate = rate2.sqrt();
            // r = hg e3 - R e1 at azimuth 0
            let lever = [hg * s - r * co, 0.0, hg * co + r * s];
            let lam = rate * s / r;
            let omega = [lam * lever[0], lam * lever[1], lam * lever[2]];
            let mut st = SpatialState::tilted(&spatial, theta, 0.0, omega);
            let xg0 = st.xg;
            let period = 2.0 * std::f64::consts::PI / rate;
            let (mut psi, mut last, mut worst_tilt) = (0.0, 0.0, 0.0f64);
            let n = 400;
            for k in 1..=n {
                let t = 3.0 * period * k as f64 / n as f64;
                spatial.advance(&mut st, t, PlanInput::default(), VerticalInput::default());
                let az = st.e[1].atan2(st.e[0]);
                let mut step = az - last;
                step -= (step / (2.0 * std::f64::consts::PI)).round() * 2.0 * std::f64::consts::PI;
                psi += step;
                last = az;
                worst_tilt = worst_tilt.max((st.theta() - theta).abs());
            }
            let measured = psi / st.t;
            let rel = (measured - rate).abs() / rate;
            let drift = (st.xg[0] - xg0[0]).hypot(st.xg[1] - xg0[1]);
            eprintln!("h {h} hollow {hollow} theta {theta:.3}: rate {rate:.6} rad/s, rel {rel:.1e}, tilt {worst_tilt:.1e}, G moved {drift:.1e} m");
            assert!(rel <= 1e-8, "precession {measured} against {rate}");
            assert!(worst_tilt <= 1e-9 * theta, "tilt drift {worst_tilt:e}");
            assert!(drift <= 1e-9, "the centre of mass moved {drift:e} m");
            assert_eq!(st.impacts, 0);
        }
    }
}

#[test]
fn energy_is_conserved_between_impacts_and_the_impact_takes_housners_share() {
    // wobbling from a generic start, no input: no impact, E constant
    let p = drum(Restitution::Housner, false);
    let spatial = Spatial::new(&p, None, RTOL).unwrap();
    let mut st = SpatialState::tilted(&spatial, 0.2, 0.4, [0.1, -0.2, 2.0]);
    let e0 = spatial.energy(&st);
    let (mut worst, mut low, mut high) = (0.0f64, 1.0f64, 0.0f64);
    for k in 1..=300 {
        spatial.advance(
            &mut st,
            0.01 * k as f64,
            PlanInput::default(),
            VerticalInput::default(),
        );
        worst = worst.max((spatial.energy(&st) - e0).abs() / e0);
        (low, high) = (low.min(st.theta()), high.max(st.theta()));
    }
    let rolled = st.xg[0].hypot(st.xg[1]);
    eprintln!("free wobble: |dE|/E {worst:.1e}, tilt {low:.3}..{high:.3} rad, G rolled {rolled:.2} m, impacts {}", st.impacts);
    assert!(
        !st.overturned && low > 0.05 && high > 0.2 && rolled > 0.5,
        "a wobble that rolls"
    );
    assert_eq!(
        st.impacts, 0,
        "the start was chosen to wobble clear of upright"
    );
    assert!(worst <= 1e-9, "{worst:e}");

    // planar free rocking: each impact keeps eta² of the kinetic energy at upright
    let mut st = SpatialState::tilted(&spatial, 0.25, 0.9, [0.0; 3]);
    let upright = spatial.model.body.weight * spatial.model.body.hg;
    let eta = spatial.model.body.eta_housner();
    let mut before = spatial.energy(&st) - upright;
    let mut seen = 0;
    for k in 1..=1600 {
        let impacts = st.impacts;
        spatial.advance(
            &mut st,
            0.005 * k as f64,
            PlanInput::default(),
            VerticalInput::default(),
        );
        let now = spatial.energy(&st) - upright;
        if st.at_rest {
            break;
        }
        let n = (st.impacts - impacts) as i32;
        let expected = eta.powi(2 * n) * before;
        assert!(
            (now - expected).abs() <= 1e-9 * before,
            "{n} impacts: {now} vs {expected}"
        );
        seen += n;
        before = now;
    }
    eprintln!(
        "planar free rocking at azimuth 0.9: {seen} impacts, each kept eta² = {:.6} of the energy",
        eta * eta
    );
    assert!(seen >= 3, "impacts seen: {seen}, {}", st.impacts);
}

#[test]
fn a_step_limit_ends_the_call_early_and_the_run_resumes_where_it_stopped() {
    let p = drum(Restitution::Housner, false);
    let free = Spatial::new(&p, None, RTOL).unwrap();
    let mut limited = free.clone();
    limited.max_steps = Some(5);
    let start = SpatialState::tilted(&free, 0.2, 0.4, [0.1, -0.2, 2.0]);
    let (mut a, mut b) = (start, start);
    free.advance(&mut a, 1.0, PlanInput::default(), VerticalInput::default());
    let mut calls = 0;
    while b.t < 1.0 {
        let ev = limited.advance(&mut b, 1.0, PlanInput::default(), VerticalInput::default());
        assert!(ev.steps + ev.rejected <= 5);
        assert_eq!(ev.limited, b.t < 1.0);
        calls += 1;
    }
    assert!(calls > 1, "the limit must bite: {calls} call");
    // the run resumes where it stopped: the same motion to the tolerance (the
    // step after a rejection may grow at a call's start, so not to the bit)
    assert_eq!(a.impacts, b.impacts);
    let gap = (a.e[0] - b.e[0]).abs() + (a.e[1] - b.e[1]).abs();
    assert!(gap <= 1e-10, "{gap:e}");
}

#[test]
fn the_run_ends_where_the_vertical_input_lifts_the_body_off() {
    let p = drum(Restitution::Housner, false);
    let spatial = Spatial::new(&p, None, RTOL).unwrap();
    let mut st = SpatialState::tilted(&spatial, 0.1, 1.0, [0.0; 3]);
    // av falls linearly from 0 to -2 g over 1 s: g + av = 0 at t = 0.5 s
    let g = spatial.model.body.g;
    let v = VerticalInput {
        av: 0.0,
        dav: -2.0 * g,
    };
    let ev = spatial.advance(&mut st, 1.0, PlanInput::default(), v);
    let term = ev.terminal.expect("liftOff");
    assert_eq!(term.condition.name(), "liftOff");
    assert!((term.t - 0.5).abs() <= 1e-15, "{}", term.t);
    assert_eq!(st.t, term.t);
    assert!(g + term.av <= 0.0 && g + (-2.0 * g) * (term.t - f64::EPSILON) > 0.0);
    assert!(st.out_of_range);
    // the run is over: a later call does nothing
    let before = st;
    let ev = spatial.advance(&mut st, 2.0, PlanInput::default(), VerticalInput::default());
    assert_eq!((st, ev.steps), (before, 0));
}
