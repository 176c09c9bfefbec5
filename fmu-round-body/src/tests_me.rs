//! Model Exchange and FMI 3.0's early return through the C API, in
//! process: a host written here (RK4 at a fixed step, a sign change of an
//! event indicator located by bisection, the event iteration of the
//! standard) drives FMI 2.0 and FMI 3.0 Model Exchange of one binary to the
//! same bits; early return stops where a co-simulation run's `impacts`
//! (or `regime`) changes; bad Model Exchange input is refused naming it;
//! on the flexible beds Model Exchange follows the FMU's own
//! co-simulation with either formulation (`shiftingPivot` through its
//! states `omegaW`). The motion itself is checked against co-simulation in
//! `tests/spatial_continuous.rs` and `tests/spatial_flexible_me.rs` of the
//! `rocking` crate and by fmpy (`fmpy-tests/test_round_body.py`).

use std::ffi::{c_char, c_void, CStr, CString};
use std::ptr;

use crate::description::{enums, vr};
use fmi2_export::test_host;
use fmi2_export::types::*;

use crate::*;

type Host = test_host::Host<crate::RoundBodySlave>;

const NX: usize = 7;
const NZ: usize = crate::description::EVENT_INDICATORS as usize;
const INPUTS: [u32; 3] = [vr::AGX, vr::AGY, vr::AV];

/// `g tan(alpha)` of the default drum (Ro 0.5 m, H 3 m), m/s2.
const UPLIFT: f64 = 9.81 / 3.0;

/// Two horizontal components and a vertical one (tests.rs's), m/s2 at t s.
fn ground(t: f64) -> [f64; 3] {
    let w = 2.0 * std::f64::consts::PI;
    let decay = (-0.25 * t).exp();
    [
        1.5 * UPLIFT * (w * 1.3 * t).sin() * decay,
        1.1 * UPLIFT * (w * 0.9 * t + 0.4).sin() * decay,
        1.5 * (w * 3.1 * t).sin(),
    ]
}

/// The Model Exchange calls a host makes, in FMI 2.0 or 3.0; each asserts
/// an OK status.
trait Me {
    fn set_inputs(&self, a: [f64; 3]);
    fn set_time(&self, t: f64);
    fn set_x(&self, x: &[f64; NX]);
    fn x(&self) -> [f64; NX];
    fn dx(&self) -> [f64; NX];
    fn z(&self) -> [f64; NZ];
    fn enter_event_mode(&self);
    /// The event iteration; returns `terminateSimulation`.
    fn event_iteration(&self) -> bool;
    fn enter_continuous(&self);
    /// `(enterEventMode, terminateSimulation)`.
    fn completed_step(&self) -> (bool, bool);
    fn impacts(&self) -> i32;
}

struct Me2(Host);

impl Me2 {
    /// Instantiated, the default parameters, not initialized.
    fn new() -> Me2 {
        Me2(Host::instantiate(fmi2ModelExchange, false))
    }
    fn error(&self) -> String {
        self.0.errors().join("; ")
    }
}

impl Me for Me2 {
    fn set_inputs(&self, a: [f64; 3]) {
        let s = self
            .0
            .set_reals(&INPUTS.iter().copied().zip(a).collect::<Vec<_>>());
        assert_eq!(s, fmi2OK, "{}", self.error());
    }
    fn set_time(&self, t: f64) {
        assert_eq!(unsafe { fmi2SetTime(self.0.c, t) }, fmi2OK);
    }
    fn set_x(&self, x: &[f64; NX]) {
        let s = unsafe { fmi2SetContinuousStates(self.0.c, x.as_ptr(), NX) };
        assert_eq!(s, fmi2OK, "{}", self.error());
    }
    fn x(&self) -> [f64; NX] {
        let mut x = [f64::NAN; NX];
        assert_eq!(
            unsafe { fmi2GetContinuousStates(self.0.c, x.as_mut_ptr(), NX) },
            fmi2OK
        );
        x
    }
    fn dx(&self) -> [f64; NX] {
        let mut d = [f64::NAN; NX];
        let s = unsafe { fmi2GetDerivatives(self.0.c, d.as_mut_ptr(), NX) };
        assert_eq!(s, fmi2OK, "{}", self.error());
        d
    }
    fn z(&self) -> [f64; NZ] {
        let mut z = [f64::NAN; NZ];
        let s = unsafe { fmi2GetEventIndicators(self.0.c, z.as_mut_ptr(), NZ) };
        assert_eq!(s, fmi2OK, "{}", self.error());
        z
    }
    fn enter_event_mode(&self) {
        assert_eq!(unsafe { fmi2EnterEventMode(self.0.c) }, fmi2OK);
    }
    fn event_iteration(&self) -> bool {
        loop {
            let mut info = fmi2EventInfo {
                newDiscreteStatesNeeded: fmi2True,
                terminateSimulation: fmi2False,
                nominalsOfContinuousStatesChanged: fmi2False,
                valuesOfContinuousStatesChanged: fmi2False,
                nextEventTimeDefined: fmi2True,
                nextEventTime: 0.0,
            };
            let s = unsafe { fmi2NewDiscreteStates(self.0.c, &mut info) };
            assert_eq!(s, fmi2OK, "{}", self.error());
            if info.terminateSimulation != fmi2False {
                return true;
            }
            if info.newDiscreteStatesNeeded == fmi2False {
                return false;
            }
        }
    }
    fn enter_continuous(&self) {
        assert_eq!(unsafe { fmi2EnterContinuousTimeMode(self.0.c) }, fmi2OK);
    }
    fn completed_step(&self) -> (bool, bool) {
        let (mut e, mut t) = (fmi2True, fmi2True);
        let s = unsafe { fmi2CompletedIntegratorStep(self.0.c, fmi2True, &mut e, &mut t) };
        assert_eq!(s, fmi2OK);
        (e != fmi2False, t != fmi2False)
    }
    fn impacts(&self) -> i32 {
        self.0.integer("impacts")
    }
}

unsafe extern "C" fn collect(env: *mut c_void, _s: i32, _c: *const c_char, m: *const c_char) {
    // SAFETY: env is the Vec this host passed; m a C string from the FMU.
    unsafe {
        let log = &mut *(env as *mut Vec<String>);
        log.push(CStr::from_ptr(m).to_string_lossy().into_owned());
    }
}

/// An FMI 3.0 instance (Model Exchange, or co-simulation with event mode
/// and early return).
struct Fmi3 {
    c: *mut c_void,
    #[allow(clippy::box_collection)]
    log: Box<Vec<String>>,
}

impl Fmi3 {
    fn new(model_exchange: bool) -> Fmi3 {
        let mut log = Box::new(Vec::new());
        let env = &mut *log as *mut Vec<String> as *mut c_void;
        let name = CString::new("round3").unwrap();
        let token = CString::new(GUID).unwrap();
        let c = unsafe {
            if model_exchange {
                fmi3InstantiateModelExchange(
                    name.as_ptr(),
                    token.as_ptr(),
                    ptr::null(),
                    false,
                    false,
                    env,
                    Some(collect),
                )
            } else {
                fmi3InstantiateCoSimulation(
                    name.as_ptr(),
                    token.as_ptr(),
                    ptr::null(),
                    false,
                    false,
                    true,
                    true,
                    ptr::null(),
                    0,
                    env,
                    Some(collect),
                    ptr::null(),
                )
            }
        };
        assert!(!c.is_null(), "{log:?}");
        Fmi3 { c, log }
    }

    fn set(&self, vrs: &[u32], x: &[f64]) {
        let s = unsafe { fmi3SetFloat64(self.c, vrs.as_ptr(), vrs.len(), x.as_ptr(), x.len()) };
        assert_eq!(s, 0, "{:?}", self.log);
    }

    fn init(&self) {
        unsafe {
            assert_eq!(
                fmi3EnterInitializationMode(self.c, false, 0.0, 0.0, false, 0.0),
                0
            );
            assert_eq!(fmi3ExitInitializationMode(self.c), 0, "{:?}", self.log);
        }
    }

    /// Initialized, then (co-simulation with event mode) in step mode.
    fn init_step(&self) {
        self.init();
        assert!(!self.update());
        assert_eq!(unsafe { fmi3EnterStepMode(self.c) }, 0);
    }

    fn update(&self) -> bool {
        let (mut need, mut term, mut nom, mut val, mut def, mut next) =
            (true, false, false, false, false, 0.0);
        let s = unsafe {
            fmi3UpdateDiscreteStates(
                self.c, &mut need, &mut term, &mut nom, &mut val, &mut def, &mut next,
            )
        };
        assert_eq!(s, 0, "{:?}", self.log);
        assert!(!need && !def);
        term
    }

    fn get(&self, r: u32) -> f64 {
        let mut x = [f64::NAN];
        let s = unsafe { fmi3GetFloat64(self.c, &r, 1, x.as_mut_ptr(), 1) };
        assert_eq!(s, 0, "{:?}", self.log);
        x[0]
    }

    fn int32(&self, r: u32) -> i32 {
        let mut n = [0i32];
        assert_eq!(unsafe { fmi3GetInt32(self.c, &r, 1, n.as_mut_ptr(), 1) }, 0);
        n[0]
    }

    /// `fmi3DoStep`: `(status, eventHandlingNeeded, terminate, earlyReturn,
    /// lastSuccessfulTime)`.
    fn step(&self, t: f64, h: f64) -> (i32, bool, bool, bool, f64) {
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
        (s, event, terminate, early, last)
    }
}

impl Drop for Fmi3 {
    fn drop(&mut self) {
        unsafe { fmi3FreeInstance(self.c) }
    }
}

impl Me for Fmi3 {
    fn set_inputs(&self, a: [f64; 3]) {
        self.set(&INPUTS, &a);
    }
    fn set_time(&self, t: f64) {
        assert_eq!(unsafe { fmi3SetTime(self.c, t) }, 0);
    }
    fn set_x(&self, x: &[f64; NX]) {
        let s = unsafe { fmi3SetContinuousStates(self.c, x.as_ptr(), NX) };
        assert_eq!(s, 0, "{:?}", self.log);
    }
    fn x(&self) -> [f64; NX] {
        let mut x = [f64::NAN; NX];
        assert_eq!(
            unsafe { fmi3GetContinuousStates(self.c, x.as_mut_ptr(), NX) },
            0
        );
        x
    }
    fn dx(&self) -> [f64; NX] {
        let mut d = [f64::NAN; NX];
        let s = unsafe { fmi3GetContinuousStateDerivatives(self.c, d.as_mut_ptr(), NX) };
        assert_eq!(s, 0, "{:?}", self.log);
        d
    }
    fn z(&self) -> [f64; NZ] {
        let mut z = [f64::NAN; NZ];
        let s = unsafe { fmi3GetEventIndicators(self.c, z.as_mut_ptr(), NZ) };
        assert_eq!(s, 0, "{:?}", self.log);
        z
    }
    fn enter_event_mode(&self) {
        assert_eq!(unsafe { fmi3EnterEventMode(self.c) }, 0);
    }
    fn event_iteration(&self) -> bool {
        self.update()
    }
    fn enter_continuous(&self) {
        assert_eq!(unsafe { fmi3EnterContinuousTimeMode(self.c) }, 0);
    }
    fn completed_step(&self) -> (bool, bool) {
        let (mut e, mut t) = (true, true);
        let s = unsafe { fmi3CompletedIntegratorStep(self.c, true, &mut e, &mut t) };
        assert_eq!(s, 0);
        (e, t)
    }
    fn impacts(&self) -> i32 {
        self.int32(vr::IMPACTS)
    }
}

fn fired(a: &[f64; NZ], b: &[f64; NZ]) -> bool {
    a.iter().zip(b).any(|(x, y)| *x > 0.0 && *y <= 0.0)
}

thread_local! {
    /// The host's input is `ground` sampled every 0.01 s and linear in
    /// between (co-simulation's input with its slopes) instead of `ground`
    /// itself. One test thread each.
    static LINEAR: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// The input the host sets at `t`: `ground(t)`, or its samples every
/// `tests::DT` joined linearly if `LINEAR`.
fn input(t: f64) -> [f64; 3] {
    if !LINEAR.get() {
        return ground(t);
    }
    let dt = crate::tests::DT;
    let k = (t / dt).floor();
    let (a, b) = (ground(k * dt), ground((k + 1.0) * dt));
    let s = t / dt - k;
    std::array::from_fn(|i| a[i] + s * (b[i] - a[i]))
}

/// The derivatives at `(t, x)` with the inputs there.
fn rates(me: &dyn Me, t: f64, x: &[f64; NX]) -> [f64; NX] {
    me.set_time(t);
    me.set_inputs(input(t));
    me.set_x(x);
    me.dx()
}

fn rk4(me: &dyn Me, t: f64, x: [f64; NX], h: f64) -> [f64; NX] {
    let add = |k: &[f64; NX], a: f64| std::array::from_fn(|i| x[i] + a * k[i]);
    let k1 = rates(me, t, &x);
    let k2 = rates(me, t + 0.5 * h, &add(&k1, 0.5 * h));
    let k3 = rates(me, t + 0.5 * h, &add(&k2, 0.5 * h));
    let k4 = rates(me, t + h, &add(&k3, h));
    std::array::from_fn(|i| x[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
}

/// The indicators at `(t, x)`.
fn at(me: &dyn Me, t: f64, x: &[f64; NX]) -> [f64; NZ] {
    me.set_time(t);
    me.set_inputs(input(t));
    me.set_x(x);
    me.z()
}

/// The host: from the instance initialized under `ground(0)`, RK4 steps of
/// `h` to `t_end`, each event located by bisection to 1e-13 s and handled
/// on its far side. Returns the states' bits and `impacts` every 0.01 s,
/// and the number of events.
fn run(me: &dyn Me, t_end: f64, h: f64) -> (Vec<[u64; NX + 1]>, u32) {
    me.set_inputs(input(0.0));
    assert!(!me.event_iteration());
    me.enter_continuous();
    run_on(me, 0, t_end, h)
}

/// The host from step `k0` (time `k0 h`) in continuous-time mode, as [`run`].
fn run_on(me: &dyn Me, k0: usize, t_end: f64, h: f64) -> (Vec<[u64; NX + 1]>, u32) {
    let record = |x: &[f64; NX]| -> [u64; NX + 1] {
        std::array::from_fn(|i| {
            if i < NX {
                x[i].to_bits()
            } else {
                me.impacts() as u64
            }
        })
    };
    let (mut t, mut x) = (k0 as f64 * h, me.x());
    let mut z0 = at(me, t, &x);
    let per = (0.01 / h).round() as usize;
    let (mut k, mut events) = (k0, 0);
    let mut out = vec![];
    while t < t_end - 1e-12 {
        let t1 = (k + 1) as f64 * h;
        let y = rk4(me, t, x, t1 - t);
        let z = at(me, t1, &y);
        if fired(&z0, &z) {
            let (mut lo, mut hi) = (0.0, t1 - t);
            while hi - lo > 1e-13 {
                let mid = 0.5 * (lo + hi);
                if fired(&z0, &at(me, t + mid, &rk4(me, t, x, mid))) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            let ye = rk4(me, t, x, hi);
            at(me, t + hi, &ye);
            me.completed_step();
            me.enter_event_mode();
            events += 1;
            assert!(!me.event_iteration(), "the test motion does not end");
            me.enter_continuous();
            t += hi;
            x = me.x();
            z0 = me.z();
            continue;
        }
        at(me, t1, &y);
        if me.completed_step().0 {
            me.enter_event_mode();
            events += 1;
            assert!(!me.event_iteration());
            me.enter_continuous();
        }
        (t, x) = (t1, me.x());
        z0 = me.z();
        k += 1;
        if k % per == 0 {
            out.push(record(&x));
        }
    }
    (out, events)
}

/// A bed of `kn = 1e8 Pa/m` under the default drum, crushing at `fm = 0.3
/// MPa` (tests_flexible.rs's).
const KN: f64 = 1e8;
const FM: f64 = 3e5;

/// An FMI 2.0 instance of `kind` on the bed `interface` with `formulation`,
/// not initialized.
fn on_bed(kind: fmi2Type, interface: i32, formulation: i32) -> Host {
    let h = Host::instantiate(kind, false);
    h.check("interface", h.set_integer("interface", interface));
    h.check("formulation", h.set_integer("formulation", formulation));
    h.check("kn", h.set_real("kn", KN));
    h.check("fm", h.set_real("fm", FM));
    h
}

/// Model Exchange on the elastic and the crushing bed, `costa` and
/// `shiftingPivot` (whose states are `omegaW`, its rate needing no rate of
/// `av`), against the FMU's own co-simulation (tolerance 1e-10, the
/// inputs' slopes set) under two components and `av`, both seeing `ground`
/// sampled every 0.01 s and linear in between: the same impacts at every
/// 0.01 s and `sin(theta)` within 1e-7 over 2 s (the host's RK4 at 1e-3 s,
/// within that of its run at 5e-4 s, asserted).
#[test]
fn model_exchange_on_a_flexible_bed_follows_co_simulation() {
    LINEAR.set(true);
    for (interface, formulation) in [
        (enums::ELASTIC, enums::COSTA),
        (enums::ELASTO_PLASTIC, enums::COSTA),
        (enums::ELASTIC, enums::SHIFTING_PIVOT),
        (enums::ELASTO_PLASTIC, enums::SHIFTING_PIVOT),
    ] {
        let me = |h: f64| {
            let m = Me2(on_bed(fmi2ModelExchange, interface, formulation));
            m.0.init();
            run(&m, 2.0, h)
        };
        let (a, events) = me(1e-3);
        let (fine, _) = me(5e-4);
        let cs = on_bed(fmi2CoSimulation, interface, formulation);
        cs.init_with(Some(1e-10));
        let tilt = |x: &[u64; NX + 1]| f64::from_bits(x[0]).hypot(f64::from_bits(x[1]));
        let (mut worst, mut host, mut peak, mut crushed) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for k in 0..200 {
            let (t0, t1) = (
                k as f64 * crate::tests::DT,
                (k + 1) as f64 * crate::tests::DT,
            );
            let (x0, x1) = (ground(t0), ground(t1));
            let pairs: Vec<_> = INPUTS.iter().copied().zip(x0).collect();
            cs.check("fmi2SetReal", cs.set_reals(&pairs));
            for i in 0..3 {
                let slope = (x1[i] - x0[i]) / crate::tests::DT;
                cs.check(
                    "derivative",
                    cs.set_input_derivative_vr(INPUTS[i], 1, slope),
                );
            }
            cs.check("fmi2DoStep", cs.do_step(t0, crate::tests::DT));
            let (s, x) = cs.get_reals_vr(&[vr::EX, vr::EY, vr::CRUSHED_AREA]);
            assert_eq!(s, fmi2OK);
            let e = x[0].hypot(x[1]);
            worst = worst.max((e - tilt(&a[k])).abs());
            host = host.max((tilt(&fine[k]) - tilt(&a[k])).abs());
            peak = peak.max(e);
            crushed = crushed.max(x[2]);
            assert_eq!(
                cs.integer("impacts") as u64,
                a[k][NX],
                "interface {interface}: impacts at t = {t1}"
            );
        }
        eprintln!(
            "interface {interface} formulation {formulation}: {events} events, impacts {}, peak sin(theta) {peak:.4}, crushed area {crushed:.3} m2; \
             |d sin(theta)| {worst:.2e}, host 1e-3 s vs 5e-4 s {host:.2e}",
            a[199][NX]
        );
        // off a plane the contact runs round the rim (the heel open): the
        // restitution rule may not apply at all
        assert!(peak > 0.05 && events >= 2, "the run must rock");
        assert_eq!(crushed > 0.0, interface == enums::ELASTO_PLASTIC);
        assert!(worst <= 1e-7, "{worst:e}");
        assert!(host <= 1e-7, "host {host:e}");
    }
    LINEAR.set(false);
}

/// Model Exchange's velocity states are `omegaWX`, `omegaWY`, `omegaWZ`:
/// the outputs of those names, bit for bit, during a run under two
/// components and `av`; with `shiftingPivot` on a flexible bed they differ
/// from `omegaX`, `omegaY`, `omegaZ` there (the angular velocity, from them
/// under the present `av`), with `costa` they are the same bits.
#[test]
fn model_exchange_states_are_omega_w() {
    for interface in [enums::ELASTIC, enums::ELASTO_PLASTIC] {
        for formulation in [enums::COSTA, enums::SHIFTING_PIVOT] {
            let m = Me2(on_bed(fmi2ModelExchange, interface, formulation));
            m.0.init();
            run(&m, 1.0, 1e-3);
            let x = m.x();
            let (s, w) = m.0.get_reals_vr(&[
                vr::OMEGA_WX,
                vr::OMEGA_WY,
                vr::OMEGA_WZ,
                vr::OMEGA_X,
                vr::OMEGA_Y,
                vr::OMEGA_Z,
            ]);
            assert_eq!(s, fmi2OK);
            assert_eq!(&w[..3], &x[2..5]);
            let gap = (0..3).map(|i| (w[i] - w[3 + i]).abs()).fold(0.0, f64::max);
            eprintln!("interface {interface} formulation {formulation}: |omegaW - omega| {gap:.2e} rad/s at t = 1 s");
            if formulation == enums::COSTA {
                assert_eq!(&w[..3], &w[3..]);
            } else {
                assert!(gap > 1e-6, "{gap:e}");
            }
        }
    }
}

/// FMI 2.0 and 3.0 Model Exchange of one binary, driven by the same host
/// under two components and `av`: the same states and impacts, bit for
/// bit, at every 0.01 s; the run rocks (uplift, the contact running round
/// the rim).
#[test]
fn model_exchange_in_fmi2_and_fmi3_gives_the_same_bits() {
    let two = Me2::new();
    two.0.init();
    let (a, events) = run(&two, 2.0, 1e-3);
    let three = Fmi3::new(true);
    three.init();
    let (b, _) = run(&three, 2.0, 1e-3);
    let peak = a
        .iter()
        .map(|r| f64::from_bits(r[0]).hypot(f64::from_bits(r[1])).asin())
        .fold(0.0, f64::max);
    eprintln!("{events} events, peak theta {peak:.4} rad");
    assert!(events >= 3 && peak > 0.05, "{events} events, peak {peak}");
    assert_eq!(a.len(), 200);
    assert_eq!(a, b);
}

/// An FMU state of a Model Exchange instance in continuous-time mode,
/// serialized and set again, repeats the run bit for bit: the discrete
/// state (the contact side, rest) is in it.
#[test]
fn model_exchange_fmu_state_repeats_the_run_bit_for_bit() {
    let me = Me2::new();
    me.0.init();
    let h = 1e-3;
    let (first, _) = run(&me, 1.0, h);
    let s = me.0.get_state();
    let bytes = me.0.serialize(s);
    let (a, events) = run_on(&me, 1000, 2.0, h);
    assert!(events >= 1 && first.len() == 100);
    let back = me.0.deserialize(&bytes);
    me.0.check("fmi2SetFMUstate", me.0.set_state(back));
    assert_eq!(run_on(&me, 1000, 2.0, h).0, a);
    me.0.check("fmi2SetFMUstate", me.0.set_state(s));
    assert_eq!(run_on(&me, 1000, 2.0, h).0, a);
}

/// Bad Model Exchange input is an error naming it (the number of states,
/// a NaN state, a tilt past upright's sine 1); the instance, reset, runs
/// again as a new one.
#[test]
fn bad_model_exchange_input_is_an_error_naming_it() {
    let me = Me2::new();
    // reset and initialized again, in continuous-time mode
    let again = || {
        assert_eq!(me.0.reset(), fmi2OK);
        me.0.clear_log();
        me.0.init();
        assert!(!me.event_iteration());
        me.enter_continuous();
    };
    me.0.init();
    assert!(!me.event_iteration());
    me.enter_continuous();
    let x = me.x();
    let s = unsafe { fmi2SetContinuousStates(me.0.c, x.as_ptr(), 6) };
    assert_eq!(s, fmi2Error);
    assert!(me.0.logged("nx = 6: this model has 7"), "{}", me.error());
    again();
    let mut bad = x;
    bad[2] = f64::NAN;
    let s = unsafe { fmi2SetContinuousStates(me.0.c, bad.as_ptr(), NX) };
    assert_eq!(s, fmi2Error);
    assert!(me.0.logged("x[2] = NaN"), "{}", me.error());
    again();
    let mut past = x;
    (past[0], past[1]) = (0.8, 0.7);
    let s = unsafe { fmi2SetContinuousStates(me.0.c, past.as_ptr(), NX) };
    assert_eq!(s, fmi2Error);
    assert!(me.0.logged("ex = 0.8, ey = 0.7"), "{}", me.error());
    again();
    let mut d = [0.0; NX];
    assert_eq!(
        unsafe { fmi2GetDerivatives(me.0.c, d.as_mut_ptr(), 3) },
        fmi2Error
    );
    assert!(me.0.logged("nx = 3: this model has 7"), "{}", me.error());
    again();
    // a NaN input is refused where it is set
    assert_eq!(me.0.set_real_vr(vr::AGY, f64::NAN), fmi2Error);
    assert!(me.0.logged("agy"), "{}", me.error());
    eprintln!("{}", me.error());
    // reset, the instance runs as a new one
    assert_eq!(me.0.reset(), fmi2OK);
    me.0.init();
    let (after, _) = run(&me, 0.5, 1e-3);
    let fresh = Me2::new();
    fresh.0.init();
    assert_eq!(after, run(&fresh, 0.5, 1e-3).0);
}

/// The times at which an FMI 2.0 co-simulation run in steps of `small`
/// (s) sees `regime`, `impacts` or `overturned` change (the ends of those
/// steps), up to `n` of them, under `agx = k t`, from the parameters set.
fn changes(set: &dyn Fn(&Host), k: f64, small: f64, n: usize) -> Vec<f64> {
    let cs = Host::named("reference");
    set(&cs);
    cs.init();
    let mut out = vec![];
    let mut was = (enums::REST, 0, false);
    let was_rest = cs.integer("regime");
    was.0 = was_rest;
    for j in 0..100_000 {
        let t = j as f64 * small;
        cs.check("set", cs.set_real_vr(vr::AGX, k * t));
        cs.check("der", cs.set_input_derivative_vr(vr::AGX, 1, k));
        let s = cs.do_step(t, small);
        let now = (
            cs.integer("regime"),
            cs.integer("impacts"),
            cs.boolean("overturned"),
        );
        if now != was {
            out.push(t + small);
            was = now;
        }
        if out.len() == n || s != fmi2OK {
            break;
        }
    }
    out
}

/// FMI 3.0's early return: each `fmi3DoStep` of 10 s stops at the next
/// event, within the step of 1e-4 s in which an FMI 2.0 co-simulation run
/// sees it: free rocking from a tilt (impacts), and under `agx = k t`
/// uplift (at `g tan(alpha)/k`, closed form) then overturning.
#[test]
fn early_return_stops_at_uplift_impacts_and_overturning() {
    let small = 1e-4;
    let tilted = |h: &Host| {
        h.check("theta0", h.set_real("theta0", 0.1));
        h.check("psi0", h.set_real("psi0", 0.7));
    };
    let ramp = UPLIFT / 0.25;
    for (name, set, k, n) in [
        ("free rocking", &tilted as &dyn Fn(&Host), 0.0, 5),
        ("ramp", &|_: &Host| {}, ramp, 2),
    ] {
        let want = changes(set, k, small, n);
        assert_eq!(want.len(), n, "{name}: {want:?}");
        let three = Fmi3::new(false);
        if k == 0.0 {
            let vrs = [1u32, 2].map(|i| vr::THETA0 + i - 1);
            three.set(&vrs, &[0.1, 0.7]);
        }
        three.init_step();
        let der = crate::description::ROUND_BODY.fmi3_input_derivative_vr(0);
        let mut t = 0.0;
        for (i, &w) in want.iter().enumerate() {
            three.set(&[vr::AGX, der], &[k * t, k]);
            let (s, event, terminate, early, last) = three.step(t, 10.0);
            assert_eq!(s, 0, "{:?}", three.log);
            eprintln!(
                "{name}, event {i}: early return at {last:.9} s, co-simulation's change in ({:.4}, {w:.4}] s",
                w - small
            );
            assert!(
                early && last > w - small && last <= w,
                "{name}, event {i} at {last}"
            );
            if terminate {
                assert_eq!(i, n - 1);
                assert!((three.get(vr::THETA_OVER_ALPHA) - 1.0).abs() < 1e-9);
                break;
            }
            assert!(event);
            unsafe {
                assert_eq!(fmi3EnterEventMode(three.c), 0);
                assert!(!three.update());
                assert_eq!(fmi3EnterStepMode(three.c), 0);
            }
            t = last;
        }
        if k > 0.0 {
            // the uplift's closed form
            assert!((want[0] - 0.25).abs() <= small);
        } else {
            assert_eq!(three.int32(vr::IMPACTS), n as i32);
        }
    }
}
