//! In-process tests through the exported C functions: what only the C API
//! shows (status codes, logged messages, the state after a refused step).
//! The physics is checked in `shear-frame/tests` and, through the packaged
//! FMU, in `fmpy-tests/test_shear_frame.py`.

use crate::description::vr;
use fmi2_export::test_host;
use fmi2_export::types::*;

use crate::*;

type Host = test_host::Host<crate::ShearFrameSlave>;

fn instantiate() -> Host {
    Host::named("frame")
}

fn set_real(c: fmi2Component, r: u32, x: f64) {
    assert_eq!(unsafe { fmi2SetReal(c, &r, 1, &x) }, fmi2OK);
}

fn set_integer(c: fmi2Component, r: u32, x: i32) {
    assert_eq!(unsafe { fmi2SetInteger(c, &r, 1, &x) }, fmi2OK);
}

fn real(c: fmi2Component, r: u32) -> f64 {
    let mut x = f64::NAN;
    assert_eq!(unsafe { fmi2GetReal(c, &r, 1, &mut x) }, fmi2OK);
    x
}

#[test]
fn every_bad_parameter_is_an_error_naming_it() {
    let cases: [(&dyn Fn(fmi2Component), &str); 6] = [
        (
            &|c| set_integer(c, vr::N, 0),
            "n = 0: the frame must have 1 to 20 storeys",
        ),
        (&|c| set_integer(c, vr::N, 21), "n = 21"),
        (
            &|c| set_real(c, vr::at(vr::M, 3), f64::INFINITY),
            "m[3] = inf kg",
        ),
        (&|c| set_real(c, vr::at(vr::K, 1), -5.0), "k[1] = -5 N/m"),
        (&|c| set_real(c, vr::ZETA, -0.01), "zeta = -0.01"),
        (&|c| set_real(c, vr::at(vr::U, 7), 0.1), "u[7] = 0.1 m"),
    ];
    for (set, message) in cases {
        let host = instantiate();
        set(host.c);
        assert_eq!(host.initialize(), fmi2Error, "{message}");
        assert!(host.logged(message), "{message}");
    }
    // an enumeration value outside DampingKind is refused when set
    let host = instantiate();
    let (r, x) = (vr::DAMPING, 9);
    assert_eq!(unsafe { fmi2SetInteger(host.c, &r, 1, &x) }, fmi2Error);
    assert!(host
        .errors()
        .iter()
        .any(|m| m.contains("damping") && m.contains('9')));
}

#[test]
fn a_step_that_overflows_is_refused_and_the_state_kept() {
    let host = instantiate();
    let c = host.c;
    set_integer(c, vr::N, 1);
    set_real(c, vr::at(vr::M, 1), 1e-3);
    set_real(c, vr::at(vr::K, 1), 1e-3);
    set_real(c, vr::at(vr::U, 1), 0.25);
    assert_eq!(host.initialize(), fmi2OK);
    set_real(c, vr::at(vr::FX, 1), 1e308);
    assert_eq!(unsafe { fmi2DoStep(c, 0.0, 1.0, 1) }, fmi2Error);
    assert!(host.logged("the step produced a non-finite state"));
    assert_eq!(real(c, vr::at(vr::U, 1)), 0.25);
}

#[test]
fn output_derivatives_only_of_outputs_and_orders_1_and_2() {
    let host = instantiate();
    let c = host.c;
    assert_eq!(host.initialize(), fmi2OK);
    let mut x = 0.0;
    unsafe {
        let r = vr::at(vr::U, 1);
        assert_eq!(fmi2GetRealOutputDerivatives(c, &r, 1, &1, &mut x), fmi2OK);
        assert_eq!(
            fmi2GetRealOutputDerivatives(c, &r, 1, &3, &mut x),
            fmi2Error
        );
        assert!(host.logged("derivative order 3"));
        assert_eq!(fmi2Reset(c), fmi2OK);
        assert_eq!(host.initialize(), fmi2OK);
        let r = vr::at(vr::PERIOD, 1);
        assert_eq!(
            fmi2GetRealOutputDerivatives(c, &r, 1, &1, &mut x),
            fmi2Error
        );
    }
}

#[test]
fn the_embedded_guid_is_the_xmls() {
    assert!(MODEL_DESCRIPTION_XML.contains(&format!("guid=\"{GUID}\"")));
    assert!(MODEL_DESCRIPTION_XML.contains("modelIdentifier=\"ShearFrame\""));
}

/// Every Real of the table and every output's derivatives up to the
/// declared order, walked from the table: `fmi2OK` and finite, before and
/// after steps under a ground acceleration and a floor force with rates.
#[test]
fn every_getter_is_finite_and_every_output_has_its_derivatives() {
    let host = instantiate();
    let c = host.c;
    assert_eq!(host.initialize(), fmi2OK);
    let check = |what: &str| {
        for (name, s, x) in host.every_real() {
            assert!(s == fmi2OK && x.is_finite(), "{what}: {name} = {x} ({s})");
        }
        let rates = host.every_output_derivative();
        assert!(!rates.is_empty());
        for (name, k, s, x) in rates {
            assert!(
                s == fmi2OK && x.is_finite(),
                "{what}: d^{k} {name} = {x} ({s})"
            );
        }
    };
    check("at rest");
    set_real(c, vr::AG, 2.0);
    set_real(c, vr::at(vr::FX, 1), 1e4);
    let (r, k, d) = (vr::AG, 1, 5.0);
    assert_eq!(
        unsafe { fmi2SetRealInputDerivatives(c, &r, 1, &k, &d) },
        fmi2OK
    );
    for i in 0..10 {
        assert_eq!(unsafe { fmi2DoStep(c, 0.01 * i as f64, 0.01, 1) }, fmi2OK);
    }
    check("after 10 steps");
}
