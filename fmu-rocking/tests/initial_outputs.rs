//! The outputs at the start of a run, through the C API: a body at rest at
//! `t = 0` that the ground acceleration `ag` sets moving (any `ag` on a
//! flexible interface; `|ag| > g tan(alpha)` on a rigid one) reports the
//! `angularAcceleration` it starts with, not 0. The check is independent of
//! the output's code: the forward difference `omega(h) / h` of actual
//! `fmi2DoStep` calls from `t = 0` (`omega(h) = theta''(0) h + O(h²)`),
//! over a halving sequence of `h` until it has converged. And the
//! modelDescription declares that dependency at initialization
//! (`ModelStructure/InitialUnknowns`: `angularAcceleration` depends on `ag`).

mod host;

use host::*;

/// `(angularAcceleration at t = 0, lim omega(h) / h)` of a body at rest
/// under `ag` set before the first step; `(Fx, Fz)` at t = 0 too.
fn start(interface: i32, ag: impl Fn(&Host) -> f64) -> (f64, f64, f64, f64, Host) {
    let h = Host::new();
    assert_eq!(h.setup(Some(1e-12), 0.0, None), fmi2OK);
    assert_eq!(h.set_integer("interface", interface), fmi2OK);
    assert_eq!(h.enter_init(), fmi2OK);
    assert_eq!(h.exit_init(), fmi2OK, "{:?}", h.messages());
    let a = ag(&h);
    assert_eq!(h.set_real("ag", a), fmi2OK);
    let dd = h.real("angularAcceleration");
    let (fx, fz) = (h.real("Fx"), h.real("Fz"));
    // the contact outputs do not depend on ag (their declared dependencies
    // do not include it): as under ag = 0
    let contact = ["af", "contactLength", "MR"].map(|n| h.real(n));
    let regime = h.integer("regime");
    assert_eq!(h.set_real("ag", 0.0), fmi2OK);
    assert_eq!(contact, ["af", "contactLength", "MR"].map(|n| h.real(n)));
    assert_eq!(regime, h.integer("regime"));
    assert_eq!(h.set_real("ag", a), fmi2OK);
    let mut s0 = h.get_state();
    let mut step = 1e-3;
    let mut prev = f64::NAN;
    let mut fd = f64::NAN;
    for _ in 0..40 {
        assert_eq!(h.set_state(s0), fmi2OK);
        assert_eq!(h.do_step(0.0, step), fmi2OK, "{:?}", h.messages());
        fd = h.real("omega") / step;
        if (fd - prev).abs() <= 1e-7 * fd.abs() || (fd == 0.0 && prev == 0.0) {
            break;
        }
        prev = fd;
        step *= 0.5;
    }
    assert_eq!(h.set_state(s0), fmi2OK);
    assert_eq!(h.free_state(&mut s0), fmi2OK);
    (dd, fd, fx, fz, h)
}

#[test]
fn angular_acceleration_at_start_is_the_limit_of_the_first_steps() {
    use enums::{ELASTIC, ELASTO_PLASTIC, RIGID};
    let uplift = |h: &Host| h.real("g") * h.real("alpha").tan();
    // (case, interface, ag: a multiple of 1 m/s2 or of the uplift acceleration)
    let cases = [
        ("elastic, ag = 1", ELASTIC, 1.0, false),
        ("elastic, ag = -1", ELASTIC, -1.0, false),
        ("elastoPlastic, ag = 1", ELASTO_PLASTIC, 1.0, false),
        ("rigid below uplift", RIGID, 0.9, true),
        ("rigid above uplift", RIGID, 1.1, true),
        ("rigid above uplift, ag < 0", RIGID, -1.1, true),
    ];
    for (name, interface, factor, of_uplift) in cases {
        let ag = move |h: &Host| factor * if of_uplift { uplift(h) } else { 1.0 };
        let (dd, fd, fx, fz, h) = start(interface, ag);
        let a = h.real("ag");
        let (m, w, thr) = (h.real("mass"), h.real("weight"), uplift(&h));
        eprintln!("{name}: angularAcceleration(0) = {dd:.7e} rad/s2, omega(h)/h -> {fd:.7e}");
        assert!(
            (dd - fd).abs() <= 1e-6 * fd.abs().max(1e-12),
            "{name}: {dd} vs {fd}"
        );
        let moves = interface != RIGID || a.abs() > thr;
        assert_eq!(dd != 0.0, moves, "{name}");
        // the horizontal support force carries the ground inertia and
        // the start of the rotation; at rest it is m ag and Fz = W
        if !moves {
            assert_eq!((fx, fz), (m * a, w), "{name}");
        } else {
            assert!((fx - m * a).abs() > 1e-9 * w, "{name}: Fx = {fx}");
        }
        h.free();
    }
}

#[test]
fn angular_acceleration_depends_on_ag_at_initialization() {
    let xml = fmu_rocking::MODEL_DESCRIPTION_XML;
    let block =
        &xml[xml.find("<InitialUnknowns>").unwrap()..xml.find("</InitialUnknowns>").unwrap()];
    let index = |n: &str| ROCKING_BLOCK.index_of(n).unwrap();
    let key = format!(
        "<Unknown index=\"{}\" dependencies=\"",
        index("angularAcceleration")
    );
    let at = block
        .find(&key)
        .expect("angularAcceleration is an initial unknown")
        + key.len();
    let deps: Vec<usize> = block[at..at + block[at..].find('"').unwrap()]
        .split_whitespace()
        .map(|d| d.parse().unwrap())
        .collect();
    assert!(deps.contains(&index("ag")), "{deps:?}");
}
