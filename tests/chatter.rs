//! A rigid body chattering to rest under a ground motion: every impact of
//! the sequence, whether the call runs to its end (`advance`) or stops at
//! each event (`advance_to_event`). The second is the reference: it starts
//! a fresh step at every event, so no event can fall at the very start of a
//! step. A crossing that a step ends a hair short of (the tilt 1e-23 rad on
//! the near side, moving toward it) lies at the start of the next step; it
//! is the impact there, not a spurious event.

use rocking::dynamics::{GroundInput, Simulator, State};
use rocking::model::{LawKind, MassKind, ShapeKind};
use rocking::Params;

fn drum() -> Simulator {
    let p = Params {
        shape: ShapeKind::SolidCircle,
        ro: 0.5,
        mass_model: MassKind::Prism,
        h: 3.0,
        rho: 2000.0,
        interface: LawKind::Rigid,
        ..Params::default()
    };
    Simulator::new(p.build().unwrap(), 1e-12)
}

/// A ground motion below the uplift threshold (g tan(alpha) = 3.27 m/s²),
/// slowly varying, m/s².
fn ag(t: f64) -> f64 {
    0.8 * (2.0 * std::f64::consts::PI * 0.7 * t).sin()
        + 0.3 * (2.0 * std::f64::consts::PI * 1.9 * t).cos()
}

const DT: f64 = 0.005;

fn input(st: &State, k: usize) -> GroundInput {
    let (t0, t1) = (k as f64 * DT, (k + 1) as f64 * DT);
    let dag = (ag(t1) - ag(t0)) / DT;
    GroundInput {
        ag: ag(t0) + dag * (st.t - t0),
        dag,
    }
}

#[test]
fn a_call_finds_every_impact_of_a_chatter_that_stopping_at_each_finds() {
    let sim = drum();
    let mut worst = 0.0f64;
    let mut cases = 0;
    for (theta0, omega0) in [
        (1e-3, 0.0),
        (2e-4, 0.01),
        (-5e-4, 0.0),
        (3e-3, -0.02),
        (1e-5, 0.0),
    ] {
        let (mut a, mut b) = (
            sim.initial_state(theta0, omega0),
            sim.initial_state(theta0, omega0),
        );
        for k in 0..400 {
            let t1 = (k + 1) as f64 * DT;
            let inp = input(&a, k);
            sim.advance(&mut a, t1, inp);
            let mut guard = 0;
            while b.t < t1 {
                let inp = input(&b, k);
                sim.advance_to_event(&mut b, t1, inp);
                guard += 1;
                assert!(guard < 100_000);
            }
            worst = worst.max((a.theta - b.theta).abs());
            assert_eq!(
                a.impacts, b.impacts,
                "theta0 {theta0}, omega0 {omega0}: t = {t1}"
            );
        }
        assert!(a.at_rest && b.at_rest, "the chatter ends at rest");
        assert!(a.impacts >= 20, "a chatter: {} impacts", a.impacts);
        cases += 1;
    }
    eprintln!("{cases} chatters: worst |theta| gap {worst:e} rad");
    assert!(worst <= 1e-12);
}
