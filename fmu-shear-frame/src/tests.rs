//! In-process tests through the exported C functions: what only the C API
//! shows (status codes, logged messages, the state after a refused step).
//! The physics is checked in `shear-frame/tests` and, through the packaged
//! FMU, in `fmpy-tests/test_shear_frame.py`.

use std::ffi::{c_char, c_void, CStr, CString};
use std::ptr;
use std::sync::Mutex;

use crate::description::vr;
use fmi2_export::types::*;

use crate::*;

static LOG: Mutex<Vec<(i32, String)>> = Mutex::new(Vec::new());

extern "C" fn logger(
    _env: *mut c_void,
    _name: *const c_char,
    status: fmi2Status,
    _category: *const c_char,
    message: *const c_char,
) {
    let m = unsafe { CStr::from_ptr(message) }
        .to_string_lossy()
        .into_owned();
    LOG.lock().unwrap().push((status, m));
}

fn instantiate() -> fmi2Component {
    let name = CString::new("frame").unwrap();
    let guid = CString::new(GUID).unwrap();
    let callbacks = Box::leak(Box::new(fmi2CallbackFunctions {
        // SAFETY: same ABI for calls without variadic arguments (x86-64 SysV).
        logger: Some(unsafe {
            std::mem::transmute::<
                extern "C" fn(*mut c_void, *const c_char, fmi2Status, *const c_char, *const c_char),
                fmi2CallbackLogger,
            >(logger)
        }),
        allocateMemory: None,
        freeMemory: None,
        stepFinished: None,
        componentEnvironment: ptr::null_mut(),
    }));
    let c = unsafe {
        fmi2Instantiate(
            name.as_ptr(),
            fmi2CoSimulation,
            guid.as_ptr(),
            ptr::null(),
            callbacks,
            0,
            0,
        )
    };
    assert!(!c.is_null());
    c
}

/// Whether an error message containing `s` was logged (tests run in
/// parallel and share the log).
fn logged(s: &str) -> bool {
    LOG.lock()
        .unwrap()
        .iter()
        .any(|(st, m)| *st == fmi2Error && m.contains(s))
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

fn initialize(c: fmi2Component) -> fmi2Status {
    unsafe {
        assert_eq!(fmi2EnterInitializationMode(c), fmi2OK);
        fmi2ExitInitializationMode(c)
    }
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
        let c = instantiate();
        set(c);
        assert_eq!(initialize(c), fmi2Error, "{message}");
        assert!(logged(message), "{message}");
        unsafe { fmi2FreeInstance(c) };
    }
    // an enumeration value outside DampingKind is refused when set
    let c = instantiate();
    let (r, x) = (vr::DAMPING, 9);
    assert_eq!(unsafe { fmi2SetInteger(c, &r, 1, &x) }, fmi2Error);
    assert!(LOG
        .lock()
        .unwrap()
        .iter()
        .any(|(st, m)| *st == fmi2Error && m.contains("damping") && m.contains('9')));
    unsafe { fmi2FreeInstance(c) };
}

#[test]
fn a_step_that_overflows_is_refused_and_the_state_kept() {
    let c = instantiate();
    set_integer(c, vr::N, 1);
    set_real(c, vr::at(vr::M, 1), 1e-3);
    set_real(c, vr::at(vr::K, 1), 1e-3);
    set_real(c, vr::at(vr::U, 1), 0.25);
    assert_eq!(initialize(c), fmi2OK);
    set_real(c, vr::at(vr::FX, 1), 1e308);
    assert_eq!(unsafe { fmi2DoStep(c, 0.0, 1.0, 1) }, fmi2Error);
    assert!(logged("the step produced a non-finite state"));
    assert_eq!(real(c, vr::at(vr::U, 1)), 0.25);
    unsafe { fmi2FreeInstance(c) };
}

#[test]
fn output_derivatives_only_of_outputs_and_orders_1_and_2() {
    let c = instantiate();
    assert_eq!(initialize(c), fmi2OK);
    let mut x = 0.0;
    unsafe {
        let r = vr::at(vr::U, 1);
        assert_eq!(fmi2GetRealOutputDerivatives(c, &r, 1, &1, &mut x), fmi2OK);
        assert_eq!(
            fmi2GetRealOutputDerivatives(c, &r, 1, &3, &mut x),
            fmi2Error
        );
        assert!(logged("derivative order 3"));
        assert_eq!(fmi2Reset(c), fmi2OK);
        assert_eq!(initialize(c), fmi2OK);
        let r = vr::at(vr::PERIOD, 1);
        assert_eq!(
            fmi2GetRealOutputDerivatives(c, &r, 1, &1, &mut x),
            fmi2Error
        );
        fmi2FreeInstance(c);
    }
}

#[test]
fn the_embedded_guid_is_the_xmls() {
    assert!(MODEL_DESCRIPTION_XML.contains(&format!("guid=\"{GUID}\"")));
    assert!(MODEL_DESCRIPTION_XML.contains("modelIdentifier=\"ShearFrame\""));
}
