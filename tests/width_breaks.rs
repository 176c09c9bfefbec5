//! The breaks of a hollow section's width under a vertical input
//! (docs/model.md §6.4): the contact edge `a` and the plastic edge `xp`
//! reaching a flange edge or the inner circle are events, located from the
//! explicit bed resultant at `N`, as they are kinks at fixed rotations
//! without `av`.
//!
//! References: the body under a constant `av` is the body under
//! `g' = g + av` (the same apparent weight), whose fixed kinks are the
//! rotations at which the contact solve puts the edges at the breaks; the
//! contact solved at `(phi, N)` for the signs of Model Exchange's
//! indicators; a run at rtol 1e-13 for the accuracy at a looser tolerance.

mod support;

use rocking::dynamics::continuous::KINK_SLOTS;
use rocking::dynamics::Simulator;
use rocking::model::{LawKind, MassKind, ShapeKind};
use rocking::{Model, Params};
use support::reduced_gravity::rock_both;

const G: f64 = 9.81;

/// A box section (depth 0.5 m, walls 0.1 m) on a crushing bed, under
/// gravity `g`.
fn hollow_box(g: f64) -> Params {
    Params {
        shape: ShapeKind::HollowRectangle,
        b: 0.5,
        l: 1.0,
        t: 0.1,
        interface: LawKind::ElastoPlastic,
        kn: 1e8,
        fm: 1e6,
        g,
        ..Params::default()
    }
}

/// The Dharahara tower (docs/dharahara.md) on its F85_fm2 foundation
/// (kn = 85 MPa/m, fm = 2 MPa), under gravity `g` (the weight scales).
fn tower(g: f64) -> Params {
    Params {
        shape: ShapeKind::HollowCircle,
        ro: 3.99,
        ri: 2.12,
        mass_model: MassKind::Lumped,
        w: 24003940.0 * g / G,
        hg: 30.202496990460777,
        ic: 756496606.9897003,
        interface: LawKind::ElastoPlastic,
        kn: 8.5e7,
        fm: 2e6,
        g,
        ..Params::default()
    }
}

/// The breaks of `m`'s width.
fn breaks(m: &Model) -> [f64; 2] {
    m.interface.shape().width_breaks().unwrap()
}

/// Free rocking from `0.6 thetaOv` under a constant `av` and under
/// `g' = g + av` without it, at rtol 1e-10: the same impacts to 1e-7 s and
/// within 5 % of the same work. Both motions carry the contact edge past a
/// break of the width (checked). Measured: impacts apart by at most 5.4e-10
/// s (box) and 6.2e-8 s (tower), work -3 % to +3 %; with the breaks not
/// located under `av` (the steps across them left to the error control),
/// 8.3e-7 s and 4.3e-6 s, work -10 % to +10 %.
#[test]
fn width_breaks_under_a_constant_av_are_the_kinks_under_reduced_gravity() {
    for (name, params) in [("box", hollow_box as fn(f64) -> Params), ("tower", tower)] {
        for av in [-0.3 * G, 0.25 * G] {
            let m = params(G + av).build().unwrap();
            let theta0 = 0.6 * m.theta_ov;
            let a0 = m.interface.contact(theta0).a;
            assert!(
                breaks(&m).iter().any(|&x| a0 < x),
                "{name}, av {av}: the contact edge passes no break (a = {a0})"
            );
            rock_both(&params, G, av, theta0, 1e-10)
                .assert_alike(&format!("{name}, av {av}"), 1.05);
        }
    }
}

/// Model Exchange's indicators for the breaks of the width (the slots
/// after joint opening and crushing onset, in the order of
/// `Interface::moving_thresholds`) under `av`: on each of 30 rotations
/// below `thetaOv`, as `N` sweeps 0.3 W to 1.7 W, each changes sign
/// exactly where the contact solved at `(phi, N)` carries its edge across
/// the break (`a` or `a - fm/(kn phi)` against the break, points within
/// 1e-9 D of it left out); and every indicator keeps its sign at `av = 0`
/// when `av` leaves 0 (`+-1e-9 m/s²`), so a host sees no event that did
/// not happen.
#[test]
fn model_exchange_break_indicators_change_sign_where_the_solved_edge_crosses() {
    use rocking::interface::Threshold;
    for (name, m) in
        [("box", hollow_box(G)), ("tower", tower(G))].map(|(n, p)| (n, p.build().unwrap()))
    {
        let sim = Simulator::new(m, 1e-9);
        let it = &m.interface;
        let (kn, fm) = match it.law() {
            rocking::Law::ElastoPlastic { kn, fm } => (kn, fm),
            _ => unreachable!(),
        };
        let thresholds = it.moving_thresholds();
        let d = it.depth();
        let mut flips = 0;
        for j in 1..=30 {
            let phi = m.theta_ov * j as f64 / 31.0;
            let state = sim.continuous(phi, 0.01, 0.0);
            let z0 = sim.event_indicators_vertical(&state, 0.0, 0.0);
            for av in [1e-9, -1e-9] {
                let z = sim.event_indicators_vertical(&state, 0.0, av);
                for k in 0..z.len() {
                    assert_eq!(
                        z0[k].signum(),
                        z[k].signum(),
                        "{name}, phi {phi}, av {av}: indicator {k} is {} at av = 0, {} under av",
                        z0[k],
                        z[k]
                    );
                }
            }
            // per break slot: (indicator > 0) == (edge past the break) on every N, or != on every N
            let mut agree: [Option<bool>; KINK_SLOTS] = [None; KINK_SLOTS];
            let mut seen = [[false; 2]; KINK_SLOTS];
            for q in 0..=70 {
                let av = G * (-0.7 + 0.02 * q as f64);
                let n = m.body.weight + m.body.mass * av;
                let (c, _) = m.contact_loaded(phi, n);
                let z = sim.event_indicators_vertical(&state, 0.0, av);
                for (i, t) in thresholds.iter().enumerate().skip(2) {
                    let (edge, x) = match *t {
                        Some(Threshold::Contact(x)) => (c.a, x),
                        Some(Threshold::Plastic(x)) => (c.a - fm / (kn * phi), x),
                        None => continue,
                    };
                    if (edge - x).abs() <= 1e-9 * d {
                        continue;
                    }
                    let past = edge > x;
                    seen[i][past as usize] = true;
                    let same = (z[3 + i] > 0.0) == past;
                    let first = *agree[i].get_or_insert(same);
                    assert_eq!(
                        first,
                        same,
                        "{name}, phi {phi}, N/W {}: slot {} ({t:?}) is {} with the edge at {edge}",
                        n / m.body.weight,
                        3 + i,
                        z[3 + i]
                    );
                }
            }
            flips += seen.iter().filter(|s| s[0] && s[1]).count();
        }
        // the sweeps carry edges across breaks (measured: 5 on the box, 57
        // on the tower)
        assert!(flips >= 4, "{name}: {flips} crossings seen");
    }
}
