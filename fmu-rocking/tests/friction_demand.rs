//! `frictionDemand = |Fx| / Fz` and the sliding check `mu` (docs/model.md
//! §5, "Friction demand") through the C API, against closed forms:
//!
//! - a rigid block held at rest by a constant `ag` below uplift has
//!   `Fx = m ag`, `Fz = W`: a demand of `|ag| / g`;
//! - at uplift, `|ag| = g tan(alpha)`, the demand is `tan(alpha)`, from
//!   either side of the threshold (just above it `theta''` starts from 0);
//! - a body on a flexible bed at rest turns at once under `ag`, with
//!   `theta'' = -m ag hG / (Ic + m hG²)`, so `Fx = m ag Ic / (Ic + m hG²)`
//!   and `Fz = W`: a demand of `(|ag|/g) Ic / (Ic + m hG²)`;
//! - `mu` below the demand warns once (`fmi2Warning` from the step, one
//!   `logStatusWarning` message naming the demand, `mu` and the time); `mu`
//!   above it never warns; `mu < 0` or NaN is refused, naming `mu`.

mod host;

use host::enums::{ELASTIC, LUMPED, RIGID};
use host::*;

/// A rigid lumped block (W = 1e5 N, hG = 1.25 m, B = 0.5 m) initialized
/// with `mu`.
fn rigid_block(mu: f64) -> Host {
    let h = Host::new();
    assert_eq!(h.setup(Some(1e-12), 0.0, None), fmi2OK);
    assert_eq!(h.set_integer("interface", RIGID), fmi2OK);
    assert_eq!(h.set_real("mu", mu), fmi2OK);
    assert_eq!(h.enter_init(), fmi2OK);
    assert_eq!(h.exit_init(), fmi2OK, "{:?}", h.messages());
    h
}

fn uplift(h: &Host) -> f64 {
    h.real("g") * h.real("alpha").tan()
}

#[test]
fn a_rigid_block_held_at_rest_needs_ag_over_g() {
    let h = rigid_block(0.0);
    let g = h.real("g");
    let mut t = 0.0;
    for factor in [0.0, 0.3, -0.3, 0.9, -0.9] {
        let ag = factor * uplift(&h);
        assert_eq!(h.set_real("ag", ag), fmi2OK);
        for _ in 0..3 {
            assert_eq!(h.do_step(t, 0.01), fmi2OK, "{:?}", h.messages());
            t += 0.01;
            let d = h.real("frictionDemand");
            assert!(
                (d - ag.abs() / g).abs() <= 1e-14 * (ag.abs() / g).max(1e-300),
                "ag = {ag}: demand {d} against {}",
                ag.abs() / g
            );
        }
        assert_eq!(h.real("theta"), 0.0, "the block stays put");
    }
}

#[test]
fn at_uplift_the_demand_is_tan_alpha() {
    for side in [1.0, -1.0] {
        for eps in [-1e-9, 1e-9] {
            let h = rigid_block(0.0);
            let ag = side * uplift(&h) * (1.0 + eps);
            assert_eq!(h.set_real("ag", ag), fmi2OK);
            let d = h.real("frictionDemand");
            let tan_alpha = h.real("alpha").tan();
            assert!(
                (d - tan_alpha).abs() <= 3e-9 * tan_alpha,
                "ag = {ag}: {d} against tan(alpha) = {tan_alpha}"
            );
        }
    }
}

#[test]
fn a_flexible_bed_at_rest_lowers_the_demand_by_the_rotary_inertia() {
    let h = Host::new();
    assert_eq!(h.setup(Some(1e-12), 0.0, None), fmi2OK);
    assert_eq!(h.set_integer("interface", ELASTIC), fmi2OK);
    assert_eq!(h.set_integer("massModel", LUMPED), fmi2OK);
    let (w, hg, ic) = (2e5, 1.5, 3e4);
    for (n, x) in [("W", w), ("hG", hg), ("Ic", ic)] {
        assert_eq!(h.set_real(n, x), fmi2OK);
    }
    assert_eq!(h.enter_init(), fmi2OK);
    assert_eq!(h.exit_init(), fmi2OK, "{:?}", h.messages());
    let g = h.real("g");
    let m = w / g;
    for ag in [0.5, -2.0] {
        assert_eq!(h.set_real("ag", ag), fmi2OK);
        let expected = ag.abs() / g * ic / (ic + m * hg * hg);
        let d = h.real("frictionDemand");
        assert!(
            (d - expected).abs() <= 1e-13 * expected,
            "ag = {ag}: {d} against {expected}"
        );
    }
}

/// `(status of each of 20 steps of 0.01 s, warning messages)` of a rigid
/// block under `ag = 0.6 g tan(alpha)` (held at rest: demand 0.6 tan(alpha))
/// checked against `mu = factor tan(alpha)`.
fn sliding_run(factor: f64) -> (Vec<fmi2Status>, Vec<String>) {
    let probe = rigid_block(0.0);
    let tan_alpha = probe.real("alpha").tan();
    let ag = 0.6 * uplift(&probe);
    let h = rigid_block(factor * tan_alpha);
    assert_eq!(h.set_real("ag", ag), fmi2OK);
    h.clear_log();
    let statuses = (0..20).map(|k| h.do_step(k as f64 * 0.01, 0.01)).collect();
    let warnings = h
        .messages()
        .into_iter()
        .filter(|m| m.status == fmi2Warning)
        .map(|m| m.text)
        .collect();
    (statuses, warnings)
}

#[test]
fn a_demand_above_mu_warns_once_with_the_time() {
    let (statuses, warnings) = sliding_run(0.5);
    assert_eq!(statuses[0], fmi2Warning);
    assert!(statuses[1..].iter().all(|s| *s == fmi2OK), "{statuses:?}");
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    let w = &warnings[0];
    assert!(
        w.contains("frictionDemand") && w.contains("mu") && w.contains("t = 0.01"),
        "{w}"
    );
    let (statuses, warnings) = sliding_run(0.7);
    assert!(statuses.iter().all(|s| *s == fmi2OK), "{statuses:?}");
    assert!(warnings.is_empty(), "{warnings:?}");
}

#[test]
fn a_negative_or_nan_mu_is_refused_naming_it() {
    for mu in [-0.1, f64::NAN] {
        let h = Host::new();
        assert_eq!(h.setup(None, 0.0, None), fmi2OK);
        assert_eq!(h.set_real("mu", mu), fmi2OK);
        assert_eq!(h.enter_init(), fmi2OK);
        assert_eq!(h.exit_init(), fmi2Error);
        assert!(
            h.errors().iter().any(|m| m.contains("mu = ")),
            "{:?}",
            h.messages()
        );
    }
}
