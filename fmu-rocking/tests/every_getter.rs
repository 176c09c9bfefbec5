//! Every getter of the variable table, walked from the table (not from a
//! list written here), answers with a finite value: `fmi2GetReal` of every
//! Real and `fmi2GetRealOutputDerivatives` of every continuous Real output
//! up to the declared `maxOutputDerivativeOrder`, for each law and
//! formulation, at rest and rocking, with and without a vertical input and
//! its derivative, and where the base carries no compression (`Fz <= 0`).
//! Where the model's value is `+inf` the FMU reports `1e60`
//! (docs/model.md §5, "Values that stand for infinity").
//!
//! `omegaW`'s first derivative against `der(omegaW)`: the jets of
//! `omega sqrt(I(phi, N)/I(phi, W))` (with `av`'s derivative) against the
//! power form's right-hand side, which needs none (docs/model-exchange.md).

mod host;

use host::enums::{COSTA, ELASTIC, ELASTO_PLASTIC, RIGID, SHIFTING_PIVOT};
use host::*;

/// The documented stand-in for `+inf` (Modelica's `Modelica.Constants.inf`).
const INF: f64 = 1e60;

/// A co-simulation instance of `law` and `formulation` on a soft bed, so
/// that the flexible laws open and crush within a few steps.
fn instance(law: i32, formulation: i32) -> Host {
    let h = Host::new();
    assert_eq!(h.setup(Some(1e-10), 0.0, None), fmi2OK);
    for (n, x) in [("interface", law), ("formulation", formulation)] {
        assert_eq!(h.set_integer(n, x), fmi2OK);
    }
    for (n, x) in [("kn", 2e8), ("fm", 4e5)] {
        assert_eq!(h.set_real(n, x), fmi2OK);
    }
    assert_eq!(h.enter_init(), fmi2OK);
    assert_eq!(h.exit_init(), fmi2OK, "{:?}", h.messages());
    h
}

/// Every getter answers `fmi2OK` with a finite value; `what` names the case.
fn all_finite(h: &Host, what: &str) {
    for (name, s, x) in h.every_real() {
        assert!(s == fmi2OK && x.is_finite(), "{what}: {name} = {x} ({s})");
    }
    let rates = h.every_output_derivative();
    assert!(
        rates.len() >= 2 * 14,
        "{what}: {} output derivatives",
        rates.len()
    );
    for (name, k, s, x) in rates {
        assert!(
            s == fmi2OK && x.is_finite(),
            "{what}: d^{k}/dt^{k} {name} = {x} ({s}): {:?}",
            h.messages()
        );
    }
}

/// The output derivative of `name` of order `k`.
fn derivative(h: &Host, name: &str, k: i32) -> f64 {
    let found = h.every_output_derivative();
    let (_, _, s, x) = found.iter().find(|d| d.0 == name && d.1 == k).unwrap();
    assert_eq!(*s, fmi2OK);
    *x
}

#[test]
fn every_getter_is_finite_at_rest_rocking_and_under_av() {
    let g = 9.80665;
    for law in [RIGID, ELASTIC, ELASTO_PLASTIC] {
        for formulation in [COSTA, SHIFTING_PIVOT] {
            let what = |s: &str| format!("law {law}, formulation {formulation}, {s}");
            let h = instance(law, formulation);
            all_finite(&h, &what("at rest"));
            let mut t = 0.0;
            for (ag, av, dag, dav) in [
                (0.5 * g, 0.0, 0.0, 0.0),
                (-0.3 * g, 0.2 * g, 2.0, 0.0),
                (0.4 * g, -0.3 * g, -3.0, 4.0),
            ] {
                assert_eq!(h.set_real("ag", ag), fmi2OK);
                assert_eq!(h.set_real("av", av), fmi2OK);
                assert_eq!(h.set_input_derivative("ag", 1, dag), fmi2OK);
                assert_eq!(h.set_input_derivative("av", 1, dav), fmi2OK);
                for _ in 0..20 {
                    assert_eq!(h.do_step(t, 0.01), fmi2OK, "{:?}", h.messages());
                    t += 0.01;
                }
                assert!(h.real("theta") != 0.0, "{}", what("rocking"));
                all_finite(&h, &what(&format!("ag {ag}, av {av}, dav {dav}")));
            }
        }
    }
}

#[test]
fn theta_c_of_a_law_that_never_crushes_is_1e60() {
    for (law, crushes) in [(RIGID, false), (ELASTIC, false), (ELASTO_PLASTIC, true)] {
        let h = instance(law, SHIFTING_PIVOT);
        let theta_c = h.real("thetaC");
        assert_eq!(theta_c == INF, !crushes, "law {law}: thetaC = {theta_c}");
        assert!(theta_c.is_finite() && theta_c > 0.0);
    }
    // fm = inf: no crushing on the elastoPlastic law either
    let h = Host::new();
    assert_eq!(h.setup(None, 0.0, None), fmi2OK);
    assert_eq!(h.set_real("fm", f64::INFINITY), fmi2OK);
    assert_eq!(h.initialize(), fmi2OK);
    assert_eq!(h.real("thetaC"), INF);
}

/// A vertical input below `-g` leaves the base without compression: the
/// demand `|Fx|/Fz` is unbounded, reported as 1e60 with derivatives 0.
#[test]
fn friction_demand_without_compression_is_1e60() {
    for law in [RIGID, ELASTIC, ELASTO_PLASTIC] {
        let h = instance(law, SHIFTING_PIVOT);
        assert_eq!(h.set_real("ag", 1.0), fmi2OK);
        assert_eq!(h.set_real("av", -1.5 * 9.80665), fmi2OK);
        assert_eq!(h.set_input_derivative("av", 1, 1.0), fmi2OK);
        assert!(h.real("Fz") <= 0.0, "law {law}: Fz = {}", h.real("Fz"));
        assert_eq!(h.real("frictionDemand"), INF, "law {law}");
        for k in [1, 2] {
            assert_eq!(derivative(&h, "frictionDemand", k), 0.0, "law {law}");
        }
        all_finite(&h, &format!("law {law}, Fz <= 0"));
    }
}

/// `d omegaW/dt` from the output derivatives (the jet of `omega r`, which
/// takes `av`'s derivative) against `der(omegaW)`, Model Exchange's
/// right-hand side evaluated at co-simulation's state (the power form,
/// which needs no derivative of `av`): equal for any `dav`.
#[test]
fn omega_w_rate_is_the_power_forms_right_hand_side() {
    let g = 9.80665;
    let (mut worst, mut checked) = (0.0f64, 0);
    for law in [ELASTIC, ELASTO_PLASTIC] {
        let h = instance(law, SHIFTING_PIVOT);
        let mut t = 0.0f64;
        for step in 0..60 {
            let ag = 0.3 * g * (std::f64::consts::TAU * 1.5 * t).sin();
            let av = 0.3 * g * (0.7 * t).cos();
            assert_eq!(h.set_real("ag", ag), fmi2OK);
            assert_eq!(h.set_real("av", av), fmi2OK);
            assert_eq!(h.do_step(t, 0.01), fmi2OK, "{:?}", h.messages());
            t += 0.01;
            if step % 6 != 5 || h.real("theta") == 0.0 {
                continue;
            }
            let rhs = h.real("der(omegaW)");
            for dav in [0.0, 5.0, -40.0] {
                assert_eq!(h.set_input_derivative("av", 1, dav), fmi2OK);
                let d1 = derivative(&h, "omegaW", 1);
                let err = (d1 - rhs).abs() / rhs.abs().max(1e-9);
                worst = worst.max(err);
                checked += 1;
                assert!(
                    err < 1e-9,
                    "law {law}, t {t}, dav {dav}: {d1} against {rhs}"
                );
            }
        }
    }
    println!("omegaW' against der(omegaW): {checked} cases, worst relative difference {worst:.1e}");
    assert!(checked >= 40, "{checked} cases");
}
