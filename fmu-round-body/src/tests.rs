//! In-process tests through the FMI functions: what only the C API shows
//! (status codes, logged messages, the state after a refused step, FMI 2.0
//! against 3.0, FMU states). The physics is checked against independent
//! references in `tests/spatial.rs` of the `rocking` crate; the planar
//! limit against RockingBlock in `tests/planar.rs`; the packaged archives
//! in `fmpy-tests/test_round_body.py`.

use std::ffi::{c_char, c_void, CStr, CString};
use std::ptr;

use crate::description::{enums, vr, ROUND_BODY};
use fmi2_export::test_host;
use fmi2_export::types::*;

use crate::*;

type Host = test_host::Host<crate::RoundBodySlave>;

/// `g tan(alpha)` of the default drum (Ro 0.5 m, H 3 m): the uplift threshold, m/s2.
const UPLIFT: f64 = 9.81 / 3.0;

pub(crate) const DT: f64 = 0.01;

/// Two horizontal components and a vertical one that rock the default drum
/// off any plane without overturning it, m/s2 at t s.
pub(crate) fn ground(t: f64) -> [f64; 3] {
    let w = 2.0 * std::f64::consts::PI;
    let decay = (-0.25 * t).exp();
    [
        1.5 * UPLIFT * (w * 1.3 * t).sin() * decay,
        1.1 * UPLIFT * (w * 0.9 * t + 0.4).sin() * decay,
        1.5 * (w * 3.1 * t).sin(),
    ]
}

/// The inputs over step `k`: values at its start and the chords' slopes.
pub(crate) fn step_inputs(k: usize) -> ([f64; 3], [f64; 3]) {
    let (t0, t1) = (k as f64 * DT, (k + 1) as f64 * DT);
    let (a, b) = (ground(t0), ground(t1));
    (a, [0, 1, 2].map(|i| (b[i] - a[i]) / DT))
}

pub(crate) const INPUTS: [u32; 3] = [vr::AGX, vr::AGY, vr::AV];

/// Every Real output, then impacts, regime and overturned, as f64 bits.
fn output_vrs() -> Vec<u32> {
    (vr::THETA..=vr::FRICTION_DEMAND).collect()
}

fn fmi2_outputs(h: &Host) -> Vec<u64> {
    let (s, x) = h.get_reals_vr(&output_vrs());
    assert_eq!(s, fmi2OK, "{:?}", h.messages());
    let mut bits: Vec<u64> = x.iter().map(|x| x.to_bits()).collect();
    let (s, n) = h.get_integers_vr(&[vr::REGIME, vr::IMPACTS]);
    assert_eq!(s, fmi2OK);
    bits.extend(n.iter().map(|&n| n as u64));
    bits.push(h.get_boolean_vr(vr::OVERTURNED).1 as u64);
    bits
}

/// Steps `k0..k1` of the ground motion through FMI 2.0, the outputs after each.
fn fmi2_run(h: &Host, k0: usize, k1: usize) -> Vec<Vec<u64>> {
    let mut out = vec![];
    for k in k0..k1 {
        let (a, da) = step_inputs(k);
        h.check(
            "fmi2SetReal",
            h.set_reals(&INPUTS.iter().copied().zip(a).collect::<Vec<_>>()),
        );
        for (r, d) in INPUTS.iter().zip(da) {
            h.check("derivative", h.set_input_derivative_vr(*r, 1, d));
        }
        h.check("fmi2DoStep", h.do_step(k as f64 * DT, DT));
        out.push(fmi2_outputs(h));
    }
    out
}

fn started() -> Host {
    let h = Host::named("round");
    h.init_with(None);
    h
}

#[test]
fn the_embedded_guid_is_the_xmls() {
    assert!(MODEL_DESCRIPTION_XML.contains(&format!("guid=\"{GUID}\"")));
    assert!(MODEL_DESCRIPTION_XML.contains("modelIdentifier=\"RoundBody\""));
}

/// The run rocks off any plane and has impacts: the comparisons below are
/// of a motion, not of rest.
#[test]
fn the_test_motion_rocks_in_space() {
    let h = started();
    let run = fmi2_run(&h, 0, 400);
    let psi = output_vrs().iter().position(|&r| r == vr::PSI).unwrap();
    let theta = 0;
    let peak = run
        .iter()
        .map(|o| f64::from_bits(o[theta]))
        .fold(0.0, f64::max);
    let (lo, hi) = run
        .iter()
        .filter(|o| f64::from_bits(o[theta]) > 0.01)
        .map(|o| f64::from_bits(o[psi]))
        .fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(x), b.max(x)));
    let impacts = run.last().unwrap()[output_vrs().len() + 1];
    eprintln!("peak theta {peak:.4} rad, psi in [{lo:.3}, {hi:.3}], {impacts} impacts");
    assert!(peak > 0.05 && peak < 0.3, "peak {peak}");
    assert!(hi - lo > 1.0, "the lean's azimuth must move: {lo} .. {hi}");
}

/// At rest the bed carries the body's inertia force: -m ag horizontally,
/// m (g + av) up; the friction demand is their ratio, 1e60 where Fz <= 0.
#[test]
fn at_rest_the_forces_are_the_inertia_forces() {
    let h = started();
    let m = h.real("mass");
    let rho_v = 1800.0 * std::f64::consts::PI * 0.25 * 3.0;
    assert!((m - rho_v).abs() <= 1e-12 * m, "{m} against {rho_v}");
    h.check(
        "set",
        h.set_reals(&[(vr::AGX, 1.2), (vr::AGY, -0.7), (vr::AV, 0.5)]),
    );
    let f = h.reals(&["Fx", "Fy", "Fz", "frictionDemand"]);
    assert_eq!(f[0], -m * 1.2);
    assert_eq!(f[1], m * 0.7);
    assert_eq!(f[2], m * (9.81 + 0.5));
    assert!((f[3] - 1.2f64.hypot(0.7) / 10.31).abs() < 1e-15);
    assert_eq!(h.integer("regime"), enums::REST);
    h.check("set", h.set_real_vr(vr::AV, -2.0 * 9.81));
    assert_eq!(h.real("frictionDemand"), 1e60);
}

/// The bed touches the whole base at rest (pi Ro² of the drum's solid
/// circle) and one rim point once the body rocks.
#[test]
fn the_contact_area_is_the_base_at_rest_and_nil_rocking() {
    let h = started();
    let area = std::f64::consts::PI * 0.5 * 0.5;
    assert!((h.real("contactArea") - area).abs() <= 1e-15 * area);
    h.check("set", h.set_real_vr(vr::AGX, 2.0 * UPLIFT));
    assert_eq!(h.do_step(0.0, 0.05), fmi2OK);
    assert_eq!(h.integer("regime"), enums::ROCKING);
    assert_eq!(h.real("contactArea"), 0.0);
}

/// FMI 2.0 and 3.0 of one binary on the same inputs (with their
/// derivatives): the same outputs, bit for bit, at every step.
#[test]
fn fmi2_and_fmi3_give_the_same_bits() {
    let h = started();
    let two = fmi2_run(&h, 0, 300);
    let three = Fmi3::new();
    let md = &ROUND_BODY;
    let der: Vec<u32> = (0..3).map(|k| md.fmi3_input_derivative_vr(k)).collect();
    for (k, want) in two.iter().enumerate() {
        let (a, da) = step_inputs(k);
        let mut vrs = INPUTS.to_vec();
        vrs.extend(&der);
        let mut x = a.to_vec();
        x.extend(da);
        assert_eq!(three.set(&vrs, &x), 0, "{:?}", three.log);
        let (status, t) = three.step(k as f64 * DT, DT);
        assert_eq!((status, t), (0, k as f64 * DT + DT), "{:?}", three.log);
        assert_eq!(&three.outputs(), want, "step {k}");
    }
}

/// `fmi2GetFMUstate`, serialized and back, then the same steps again: the
/// same outputs bit for bit (and through a state not serialized).
#[test]
fn fmu_state_round_trip_is_bit_for_bit() {
    let h = started();
    fmi2_run(&h, 0, 150);
    let s = h.get_state();
    let bytes = h.serialize(s);
    let first = fmi2_run(&h, 150, 300);
    let back = h.deserialize(&bytes);
    h.check("fmi2SetFMUstate", h.set_state(back));
    assert_eq!(fmi2_run(&h, 150, 300), first);
    h.check("fmi2SetFMUstate", h.set_state(s));
    assert_eq!(fmi2_run(&h, 150, 300), first);
}

/// A state read back is checked field by field: a pivot that is no unit
/// vector, a non-finite angular velocity or a tilt past upright's sine 1
/// are refused naming the field.
#[test]
fn a_bad_state_is_refused_naming_its_field() {
    use fmi2_export::bytes::{ByteReader, ByteWriter};
    use fmi2_export::Slave;
    use rocking::spatial::SpatialState;
    let good = SpatialState {
        e: [0.1, 0.05],
        omega: [0.3, -0.2, 0.1],
        ..SpatialState::at_rest()
    };
    let read = |s: SpatialState| {
        let mut w = ByteWriter::new();
        RoundBodySlave::write_state(&s, &mut w);
        RoundBodySlave::read_state(&mut ByteReader::new(&w.buf))
    };
    assert_eq!(read(good), Ok(good));
    for (bad, field) in [
        (
            SpatialState {
                pivot: [5.0, 0.0],
                ..good
            },
            "pivot",
        ),
        (
            SpatialState {
                omega: [0.0, f64::NAN, 0.0],
                ..good
            },
            "omegaY",
        ),
        (
            SpatialState {
                e: [0.9, 0.9],
                ..good
            },
            "e = ",
        ),
        (SpatialState { h: -1.0, ..good }, "step h"),
    ] {
        let e = read(bad).unwrap_err();
        assert!(e.contains(field), "{e}");
    }
}

/// A setting of the parameters and the message it must log.
type Case<'a> = (&'a dyn Fn(&Host), &'a str);

#[test]
fn every_bad_parameter_is_an_error_naming_it() {
    let cases: [Case; 9] = [
        (&|h| h.check("set", h.set_real("Ro", -0.5)), "Ro = -0.5"),
        (&|h| h.check("set", h.set_real("Ro", f64::NAN)), "Ro = NaN"),
        (
            &|h| {
                h.check("set", h.set_integer("shape", enums::HOLLOW_CIRCLE));
                h.check("set", h.set_real("Ri", 0.5));
            },
            "Ri = 0.5",
        ),
        (
            &|h| {
                h.check("set", h.set_integer("massModel", enums::LUMPED));
                h.check("set", h.set_real("IcAxial", 0.0));
            },
            "IcAxial = 0",
        ),
        (
            &|h| h.check("set", h.set_real("theta0", 0.33)),
            "theta0 = 0.33",
        ),
        (
            &|h| h.check("set", h.set_real("psi0", f64::INFINITY)),
            "psi0 = inf",
        ),
        (
            &|h| h.check("set", h.set_real("omegaZ0", f64::NAN)),
            "omegaZ0 = NaN",
        ),
        (
            &|h| h.check("set", h.set_integer("maxSteps", 0)),
            "maxSteps = 0",
        ),
        (&|h| h.check("set", h.set_real("eta", 1.5)), "eta = 1.5"),
    ];
    for (set, message) in cases {
        let h = Host::named("bad");
        set(&h);
        if message == "eta = 1.5" {
            h.check("set", h.set_integer("restitution", enums::GIVEN));
        }
        assert_eq!(h.initialize(), fmi2Error, "{message}");
        assert!(h.logged(message), "{message}: {:?}", h.errors());
    }
    // a rectangle (RockingBlock's codes 1 and 2) is refused when set, naming shape
    for code in [1, 2] {
        let h = Host::named("rectangle");
        assert_eq!(h.set_integer("shape", code), fmi2Error);
        assert!(
            h.errors()
                .iter()
                .any(|m| m.contains("shape") && m.contains(&code.to_string())),
            "{:?}",
            h.errors()
        );
    }
}

/// A NaN input is refused at the step naming it, the state kept; the
/// instance then resets and runs.
#[test]
fn a_nan_input_is_an_error_naming_it_and_the_instance_resets() {
    for (r, name) in [(vr::AGX, "agx"), (vr::AGY, "agy"), (vr::AV, "av")] {
        let h = started();
        fmi2_run(&h, 0, 50);
        let before = fmi2_outputs(&h);
        h.set_real_vr(r, f64::NAN);
        assert_eq!(h.do_step(0.5, DT), fmi2Error);
        assert!(h.logged(&format!("{name} = NaN")), "{:?}", h.errors());
        assert_eq!(h.get_reals_vr(&[vr::THETA]).1[0].to_bits(), before[0]);
        h.check("fmi2Reset", h.reset());
        h.init_with(None);
        fmi2_run(&h, 0, 10);
    }
}

/// A huge input on a rocking body (within the 1e100 m/s2 bound, past what
/// the arithmetic holds) either overturns it or is refused naming the
/// inputs; the state is kept and the instance resets (the fuzz driver's
/// finding: agx = -3.64e31 m/s2 after a first step of 1 s).
#[test]
fn a_huge_input_on_a_rocking_body_overturns_it_or_is_refused_naming_it() {
    for (r, x) in [(vr::AGX, -3.64e31), (vr::AGY, 3.64e63)] {
        let h = started();
        h.set_real_vr(vr::AGX, 2.0 * UPLIFT);
        assert_eq!(h.do_step(0.0, 0.1), fmi2OK);
        let before = fmi2_outputs(&h);
        h.set_real_vr(vr::AGX, 0.0);
        h.set_real_vr(r, x);
        match h.do_step(0.1, 1e-3) {
            s if s == fmi2Discard => assert!(h.boolean("overturned")),
            s => {
                assert_eq!(s, fmi2Error);
                assert!(h.logged(&format!("agx = {}", if r == vr::AGX { x } else { 0.0 })));
                assert!(h.logged("agy = "), "{:?}", h.errors());
                assert_eq!(h.get_reals_vr(&[vr::THETA]).1[0].to_bits(), before[0]);
            }
        }
        h.check("fmi2Reset", h.reset());
        h.init_with(None);
        fmi2_run(&h, 0, 10);
    }
}

/// Past maxSteps a step returns fmi2Discard at the time reached, the state
/// consistent there: going on with smaller steps from it works.
#[test]
fn the_work_limit_discards_at_the_time_reached() {
    let h = Host::named("limited");
    h.check("set", h.set_integer("maxSteps", 5));
    h.set_real("theta0", 0.2);
    h.init_with(None);
    assert_eq!(h.do_step(0.0, 1.0), fmi2Discard);
    let (s, t) = h.last_successful_time();
    assert_eq!(s, fmi2OK);
    assert!(t > 0.0 && t < 1.0, "{t}");
    assert_eq!(h.terminated(), (fmi2OK, false));
    assert!(h.real("theta").is_finite());
}

/// A push past the limit overturns: fmi2Discard, terminated, overturned.
#[test]
fn overturning_ends_the_run() {
    let h = Host::named("over");
    h.set_real("theta0", 0.3);
    h.set_real("omegaY0", 2.0);
    h.set_real("omegaZ0", 0.5);
    h.init_with(None);
    let mut k = 0;
    while h.do_step(k as f64 * DT, DT) == fmi2OK {
        k += 1;
        assert!(k < 500, "no overturning");
    }
    assert_eq!(h.terminated(), (fmi2OK, true));
    assert!(h.boolean("overturned"));
    assert!((h.real("thetaOverAlpha") - 1.0).abs() < 1e-9);
}

// ----- a minimal FMI 3.0 co-simulation host ------------------------------

unsafe extern "C" fn collect(env: *mut c_void, _s: i32, _c: *const c_char, m: *const c_char) {
    // SAFETY: env is the Vec this host passed; m a C string from the FMU.
    unsafe {
        let log = &mut *(env as *mut Vec<String>);
        log.push(CStr::from_ptr(m).to_string_lossy().into_owned());
    }
}

pub(crate) struct Fmi3 {
    c: *mut c_void,
    // boxed: the FMU keeps the log's address as its environment
    #[allow(clippy::box_collection)]
    pub(crate) log: Box<Vec<String>>,
}

impl Fmi3 {
    /// Instantiated (no event mode, no early return) and initialized at t = 0.
    pub(crate) fn new() -> Fmi3 {
        Fmi3::with(&[], &[])
    }

    /// As [`Fmi3::new`] with the parameters `reals` and `enums` (by value
    /// reference) set before initialization.
    pub(crate) fn with(reals: &[(u32, f64)], enums: &[(u32, i64)]) -> Fmi3 {
        let mut log = Box::new(Vec::new());
        let name = CString::new("round3").unwrap();
        let token = CString::new(GUID).unwrap();
        let c = unsafe {
            fmi3InstantiateCoSimulation(
                name.as_ptr(),
                token.as_ptr(),
                ptr::null(),
                false,
                false,
                false,
                false,
                ptr::null(),
                0,
                &mut *log as *mut Vec<String> as *mut c_void,
                Some(collect),
                ptr::null(),
            )
        };
        assert!(!c.is_null(), "{log:?}");
        unsafe {
            for (r, x) in reals {
                assert_eq!(fmi3SetFloat64(c, r, 1, x, 1), 0, "{log:?}");
            }
            for (r, x) in enums {
                assert_eq!(fmi3SetInt64(c, r, 1, x, 1), 0, "{log:?}");
            }
            assert_eq!(
                fmi3EnterInitializationMode(c, false, 0.0, 0.0, false, 0.0),
                0
            );
            assert_eq!(fmi3ExitInitializationMode(c), 0);
        }
        Fmi3 { c, log }
    }

    pub(crate) fn set(&self, vrs: &[u32], x: &[f64]) -> i32 {
        unsafe { fmi3SetFloat64(self.c, vrs.as_ptr(), vrs.len(), x.as_ptr(), x.len()) }
    }

    /// `(status, lastSuccessfulTime)`.
    pub(crate) fn step(&self, t: f64, h: f64) -> (i32, f64) {
        let (mut event, mut terminate, mut early, mut last) = (false, false, false, f64::NAN);
        let s = unsafe {
            fmi3DoStep(
                self.c,
                t,
                h,
                true,
                &mut event,
                &mut terminate,
                &mut early,
                &mut last,
            )
        };
        (s, last)
    }

    fn outputs(&self) -> Vec<u64> {
        let mut bits: Vec<u64> = self
            .reals(&output_vrs())
            .iter()
            .map(|x| x.to_bits())
            .collect();
        let mut impacts = [0i32];
        let mut over = [false];
        unsafe {
            assert_eq!(
                fmi3GetInt32(self.c, &vr::IMPACTS, 1, impacts.as_mut_ptr(), 1),
                0,
                "{:?}",
                self.log
            );
            assert_eq!(
                fmi3GetBoolean(self.c, &vr::OVERTURNED, 1, over.as_mut_ptr(), 1),
                0
            );
        }
        bits.push(self.int64(vr::REGIME) as u64);
        bits.push(impacts[0] as u64);
        bits.push(over[0] as u64);
        bits
    }

    /// The Float64 variables `vrs`.
    pub(crate) fn reals(&self, vrs: &[u32]) -> Vec<f64> {
        let mut x = vec![f64::NAN; vrs.len()];
        let s = unsafe { fmi3GetFloat64(self.c, vrs.as_ptr(), vrs.len(), x.as_mut_ptr(), x.len()) };
        assert_eq!(s, 0, "{:?}", self.log);
        x
    }

    /// The Int64 (enumeration) variable `r`.
    pub(crate) fn int64(&self, r: u32) -> i64 {
        let mut x = [0i64];
        let s = unsafe { fmi3GetInt64(self.c, &r, 1, x.as_mut_ptr(), 1) };
        assert_eq!(s, 0, "{:?}", self.log);
        x[0]
    }
}

impl Drop for Fmi3 {
    fn drop(&mut self) {
        unsafe { fmi3FreeInstance(self.c) }
    }
}

/// The apparent weight reaching zero within a step (`g + av <= 0`) ends the
/// run there: fmi2Discard, terminated, the message naming liftOff and av.
#[test]
fn lift_off_under_av_ends_the_run() {
    let h = started();
    h.check("set", h.set_real_vr(vr::AV, -5.0));
    h.check("der", h.set_input_derivative_vr(vr::AV, 1, -100.0));
    assert_eq!(h.do_step(0.0, 0.1), fmi2Discard);
    let (_, t) = h.last_successful_time();
    // g + av(t) = 9.81 - 5 - 100 t = 0
    assert!((t - 0.0481).abs() < 1e-12, "{t}");
    assert_eq!(h.terminated(), (fmi2OK, true));
    assert!(
        h.messages()
            .iter()
            .any(|m| m.text.contains("liftOff") && m.text.contains("av = ")),
        "{:?}",
        h.messages()
    );
}

/// Every Real of the table at rest and after steps under two components
/// and av with their derivatives: fmi2OK and finite.
#[test]
fn every_real_is_finite() {
    let h = started();
    let check = |what: &str| {
        for (name, s, x) in h.every_real() {
            assert!(s == fmi2OK && x.is_finite(), "{what}: {name} = {x} ({s})");
        }
    };
    check("at rest");
    fmi2_run(&h, 0, 100);
    check("after 100 steps");
}

/// Random call sequences with absurd inputs (NaN, inf, 1e120, tiny and long
/// steps, FMU states, resets): never fmi2Fatal, never a panic reaching the
/// logger (the layer reports one as "internal error in the model"), and
/// after any error the instance resets and starts again.
#[test]
fn random_calls_never_crash_or_panic() {
    // xorshift64*: a fixed sequence, no dependency
    let mut seed = 0x5eed_1234_abcd_0001u64;
    let mut next = move |n: usize| {
        seed ^= seed >> 12;
        seed ^= seed << 25;
        seed ^= seed >> 27;
        (seed.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 33) as usize % n
    };
    let values = [0.0, 3.0, -10.0, 1e3, -1e120, f64::NAN, f64::INFINITY, 4.0];
    let steps = [4.4e-16, 1e-3, 0.01, 0.1, 1.0];
    let (mut errors, mut calls) = (0, 0);
    for _ in 0..150 {
        let h = Host::named("random");
        h.check("set", h.set_integer("maxSteps", 2000));
        h.check("set", h.set_real("theta0", [0.0, 0.1, -0.2][next(3)]));
        h.init_with(None);
        let mut t = 0.0;
        for _ in 0..30 {
            calls += 1;
            let r = INPUTS[next(3)];
            let s = match next(6) {
                0 => h.set_real_vr(r, values[next(values.len())]),
                1 => h.set_input_derivative_vr(r, 1, values[next(values.len())]),
                2 | 3 => {
                    let dt = steps[next(steps.len())];
                    let s = h.do_step(t, dt);
                    t = h.last_successful_time().1;
                    s
                }
                4 => h.every_real().iter().map(|x| x.1).max().unwrap_or(fmi2OK),
                _ => {
                    let st = h.get_state();
                    let bytes = h.serialize(st);
                    let back = h.deserialize(&bytes);
                    h.set_state(back)
                }
            };
            assert_ne!(s, fmi2Fatal, "{:?}", h.messages());
            assert!(
                !h.messages()
                    .iter()
                    .any(|m| m.text.contains("internal error")),
                "{:?}",
                h.messages()
            );
            if s == fmi2Error {
                errors += 1;
                h.check("fmi2Reset", h.reset());
                h.init_with(None);
                t = 0.0;
            }
        }
    }
    eprintln!("{calls} calls, {errors} errors");
    assert!(
        errors > 10 && errors < calls / 2,
        "{errors} errors in {calls} calls"
    );
}
