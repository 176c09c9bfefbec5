//! Model Exchange through the C API: the state machine of FMI 2.0 §3.2.3,
//! argument checks, and a host written here (RK4 at a fixed step, every
//! sign change of an event indicator located by bisection, the event
//! iteration of the standard) reproducing co-simulation of the same FMU.

mod host;
#[path = "../../tests/support/pulse.rs"]
mod pulse;

use fmu_rocking::*;
use host::*;
use pulse::pulse;

const NX: usize = 2;
const NZ: usize = fmu_rocking::description::EVENT_INDICATORS as usize;

/// A vertical input `av(t)` for the host loops below (none: `av` is left as
/// set).
type Av = Option<fn(f64) -> f64>;

/// The ground inputs of a run: `ag(t)` and the vertical.
type Ground<'a> = (&'a dyn Fn(f64) -> f64, Av);

/// The Model Exchange calls of one instance, and the vertical input the
/// host loops below set with `ag`.
struct Me(Host, std::cell::Cell<Av>);

impl Me {
    fn new(logging: bool) -> Me {
        Me(
            Host::instantiate(fmi2ModelExchange, logging),
            Default::default(),
        )
    }
    /// An instance with the default parameters, initialized: event mode.
    fn initialized() -> Me {
        let me = Me::new(false);
        me.0.init();
        me
    }
    /// An initialized instance in continuous-time mode, after the first
    /// event iteration.
    fn continuous() -> Me {
        let me = Me::initialized();
        me.event_iteration();
        assert_eq!(me.enter_continuous(), fmi2OK);
        me
    }
    /// The ground inputs at `t`: `ag(t)`, and `av(t)` if the host has one.
    fn set_ground(&self, ag: &dyn Fn(f64) -> f64, t: f64) {
        assert_eq!(self.0.set_real("ag", ag(t)), fmi2OK);
        if let Some(av) = self.1.get() {
            assert_eq!(self.0.set_real("av", av(t)), fmi2OK);
        }
    }
    fn set_time(&self, t: f64) -> fmi2Status {
        unsafe { fmi2SetTime(self.0.c, t) }
    }
    fn set_x(&self, x: &[f64; NX]) -> fmi2Status {
        unsafe { fmi2SetContinuousStates(self.0.c, x.as_ptr(), NX) }
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
        assert_eq!(s, fmi2OK, "{:?}", self.0.messages());
        d
    }
    fn z(&self) -> [f64; NZ] {
        let mut z = [f64::NAN; NZ];
        assert_eq!(
            unsafe { fmi2GetEventIndicators(self.0.c, z.as_mut_ptr(), NZ) },
            fmi2OK
        );
        z
    }
    fn enter_event_mode(&self) -> fmi2Status {
        unsafe { fmi2EnterEventMode(self.0.c) }
    }
    fn enter_continuous(&self) -> fmi2Status {
        unsafe { fmi2EnterContinuousTimeMode(self.0.c) }
    }
    /// The event iteration; returns `terminateSimulation`.
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
            assert_eq!(s, fmi2OK, "{:?}", self.0.messages());
            assert_eq!(info.nextEventTimeDefined, fmi2False);
            if info.terminateSimulation != fmi2False {
                return true;
            }
            if info.newDiscreteStatesNeeded == fmi2False {
                return false;
            }
        }
    }
    fn completed_step(&self) -> (bool, bool) {
        let (mut e, mut t) = (fmi2True, fmi2True);
        let s = unsafe { fmi2CompletedIntegratorStep(self.0.c, fmi2True, &mut e, &mut t) };
        assert_eq!(s, fmi2OK);
        (e != fmi2False, t != fmi2False)
    }
}

fn crossed(a: &[f64; NZ], b: &[f64; NZ]) -> bool {
    a.iter()
        .zip(b)
        .any(|(&x, &y)| (x > 0.0 && y <= 0.0) || (x < 0.0 && y >= 0.0))
}

/// RK4 from the FMU's state `(t, x)` over `dt`, `ag(t)` set at each stage.
fn rk4(me: &Me, ag: &dyn Fn(f64) -> f64, t: f64, x: [f64; NX], dt: f64) -> [f64; NX] {
    let f = |s: f64, y: [f64; NX]| {
        assert_eq!(me.set_time(s), fmi2OK);
        me.set_ground(ag, s);
        assert_eq!(me.set_x(&y), fmi2OK);
        me.dx()
    };
    let add = |k: [f64; NX], a: f64| [x[0] + a * k[0], x[1] + a * k[1]];
    let k1 = f(t, x);
    let k2 = f(t + dt / 2.0, add(k1, dt / 2.0));
    let k3 = f(t + dt / 2.0, add(k2, dt / 2.0));
    let k4 = f(t + dt, add(k3, dt));
    let mut y = x;
    for i in 0..NX {
        y[i] += dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
    y
}

/// Sets the state at `t` and returns the indicators there.
fn at(me: &Me, ag: &dyn Fn(f64) -> f64, t: f64, x: [f64; NX]) -> [f64; NZ] {
    assert_eq!(me.set_time(t), fmi2OK);
    me.set_ground(ag, t);
    assert_eq!(me.set_x(&x), fmi2OK);
    me.z()
}

/// Explicit Euler steps of 1 ms from `(t, x)` (event indicators `z0`) to
/// t = 1.5 s, each crossing of an indicator handled as an event; after each
/// step `each(t, x, event)`, where `x` is the state after any event.
fn euler(
    me: &Me,
    ag: &dyn Fn(f64) -> f64,
    (mut t, mut x): (f64, [f64; NX]),
    mut z0: [f64; NZ],
    mut each: impl FnMut(f64, [f64; NX], bool),
) {
    let h = 1e-3;
    while t < 1.5 {
        let d = me.dx();
        x = [x[0] + h * d[0], x[1] + h * d[1]];
        t += h;
        let z = at(me, ag, t, x);
        me.completed_step();
        let event = crossed(&z0, &z);
        if event {
            me.enter_event_mode();
            me.event_iteration();
            me.enter_continuous();
            x = me.x();
        }
        z0 = me.z();
        each(t, x, event);
    }
}

/// Runs an ME instance from `t = 0` to `t_end` with step `h`; returns
/// `theta` at every multiple of `sample`, and the time of termination.
fn run_me(
    params: &[(&str, f64)],
    ints: &[(&str, i32)],
    (ag, av): Ground<'_>,
    t_end: f64,
    h: f64,
    sample: f64,
) -> (Vec<f64>, Option<f64>, u32) {
    let me = Me::new(false);
    me.1.set(av);
    for &(n, x) in params {
        assert_eq!(me.0.set_real(n, x), fmi2OK);
    }
    for &(n, x) in ints {
        assert_eq!(me.0.set_integer(n, x), fmi2OK);
    }
    me.set_ground(ag, 0.0);
    me.0.init();
    if me.event_iteration() {
        return (vec![], Some(0.0), 0);
    }
    assert_eq!(me.enter_continuous(), fmi2OK);
    let (mut t, mut x) = (0.0, me.x());
    let mut z0 = at(&me, ag, t, x);
    let mut out = vec![x[0]];
    let mut events = 0;
    let per = (sample / h).round() as usize;
    let mut k = 0;
    while t < t_end - 1e-12 {
        let t_next = ((k + 1) as f64 * h).min(t_end);
        let dt = t_next - t;
        let y = rk4(&me, ag, t, x, dt);
        let z = at(&me, ag, t + dt, y);
        if crossed(&z0, &z) {
            let (mut lo, mut hi) = (0.0, dt);
            while hi - lo > 1e-15 * (1.0 + t) {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                let ym = rk4(&me, ag, t, x, mid);
                if crossed(&z0, &at(&me, ag, t + mid, ym)) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            let ye = rk4(&me, ag, t, x, hi);
            at(&me, ag, t + hi, ye);
            let (_, term) = me.completed_step();
            assert!(!term);
            events += 1;
            assert_eq!(me.enter_event_mode(), fmi2OK);
            if me.event_iteration() {
                return (out, Some(t + hi), events);
            }
            assert_eq!(me.enter_continuous(), fmi2OK);
            t += hi;
            x = me.x();
            z0 = me.z();
            continue;
        }
        me.completed_step();
        t = t_next;
        x = y;
        z0 = z;
        k += 1;
        if k % per == 0 {
            out.push(x[0]);
        }
    }
    (out, None, events)
}

/// The same in co-simulation, one step per sample, `ag` linear inside.
fn run_cs(
    params: &[(&str, f64)],
    ints: &[(&str, i32)],
    (ag, av): Ground<'_>,
    t_end: f64,
    sample: f64,
) -> (Vec<f64>, Option<f64>) {
    let cs = Host::new();
    for &(n, x) in params {
        assert_eq!(cs.set_real(n, x), fmi2OK);
    }
    for &(n, x) in ints {
        assert_eq!(cs.set_integer(n, x), fmi2OK);
    }
    cs.init();
    let mut out = vec![cs.real("theta")];
    let n = (t_end / sample).round() as usize;
    for k in 0..n {
        let t = k as f64 * sample;
        assert_eq!(cs.set_real("ag", ag(t)), fmi2OK);
        let slope = (ag(t + sample) - ag(t)) / sample;
        assert_eq!(cs.set_input_derivative("ag", 1, slope), fmi2OK);
        if let Some(av) = av {
            // exact at the step ends, linear inside (as ag)
            assert_eq!(cs.set_real("av", av(t)), fmi2OK);
            let slope = (av(t + sample) - av(t)) / sample;
            assert_eq!(cs.set_input_derivative("av", 1, slope), fmi2OK);
        }
        match cs.do_step(t, sample) {
            s if s == fmi2OK => out.push(cs.real("theta")),
            s if s == fmi2Discard => return (out, Some(cs.last_successful_time().1)),
            s => panic!("fmi2DoStep: {s}"),
        }
    }
    (out, None)
}

fn compare(params: &[(&str, f64)], ints: &[(&str, i32)], a: f64, tol: f64) {
    compare_av(params, ints, (a, None), tol)
}

/// [`compare`] with a vertical input `av(t)` too (none: as set).
fn compare_av(params: &[(&str, f64)], ints: &[(&str, i32)], (a, av): (f64, Av), tol: f64) {
    let dt = 0.01;
    let ag = pulse(a, 0.5, dt);
    let (cs, cs_ov) = run_cs(params, ints, (&ag, av), 2.0, dt);
    let (me, me_ov, events) = run_me(params, ints, (&ag, av), 2.0, dt / 10.0, dt);
    let worst = cs
        .iter()
        .zip(&me)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    eprintln!("{ints:?}: {} samples, {events} events, max |theta_ME - theta_CS| = {worst:.1e} rad, overturned CS {cs_ov:?} ME {me_ov:?}", cs.len().min(me.len()));
    assert!(worst < tol, "{worst:e}");
    match (cs_ov, me_ov) {
        (Some(a), Some(b)) => assert!((a - b).abs() < 1e-6, "{a} vs {b}"),
        (None, None) => assert_eq!(cs.len(), me.len()),
        other => panic!("overturning differs: {other:?}"),
    }
}

#[test]
fn me_host_reproduces_co_simulation_rigid_crushing_and_overturning() {
    let block = [("B", 0.5), ("H", 2.5), ("kn", 1e8), ("fm", 2e6)];
    let g_tan = 9.81 * 0.2;
    // rigid: rocks, then overturns under a stronger pulse
    compare(&block, &[("interface", enums::RIGID)], -1.3 * g_tan, 1e-8);
    compare(&block, &[("interface", enums::RIGID)], -3.0 * g_tan, 1e-8);
    compare(
        &block,
        &[("interface", enums::ELASTO_PLASTIC)],
        -1.3 * g_tan,
        1e-7,
    );
}

/// A constant vertical input (set once before initialization, so that both
/// hosts apply it: an input-free case for the vertical) and one-sided
/// bodies: the Model Exchange run reproduces co-simulation.
#[test]
fn me_host_reproduces_co_simulation_under_constant_av_and_one_sided() {
    let g_tan = 9.81 * 0.2;
    let with = |extra: &[(&'static str, f64)]| {
        let mut p = vec![("B", 0.5), ("H", 2.5), ("kn", 1e8), ("fm", 2e6)];
        p.extend_from_slice(extra);
        p
    };
    compare(
        &with(&[("av", -0.3 * 9.81)]),
        &[("interface", enums::RIGID)],
        -g_tan,
        1e-8,
    );
    compare(
        &with(&[("av", 0.25 * 9.81)]),
        &[("interface", enums::ELASTO_PLASTIC)],
        -1.5 * g_tan,
        1e-7,
    );
    let one_sided = [
        ("interface", enums::RIGID),
        ("restraint", enums::ONE_SIDED),
        ("side", 1),
    ];
    compare(
        &with(&[("eRestraint", 0.8)]),
        &one_sided,
        -1.3 * g_tan,
        1e-8,
    );
}

/// A slowly varying vertical input: a 0.5 Hz sine of 0.3 g sampled every
/// 10 ms and linear between the samples (a record's line), fed to the Model
/// Exchange host at every RK4 stage and to co-simulation as the line of each
/// step (value and input derivative). Model Exchange's states `(theta,
/// omegaW)` carry the power form for any `av` with no derivative of it
/// (docs/model-exchange.md, "The state omegaW"; for the rigid law `IO` does
/// not depend on N and `omegaW` is `omega`): the two agree as under a
/// constant `av`, on every law.
#[test]
fn me_host_reproduces_co_simulation_under_a_varying_av() {
    let g_tan = 9.81 * 0.2;
    let block = [("B", 0.5), ("H", 2.5), ("kn", 1e8), ("fm", 2e6)];
    let av: fn(f64) -> f64 = |t| {
        let sine = |t: f64| 0.3 * 9.81 * (std::f64::consts::TAU * 0.5 * t).sin();
        let dt = 0.01;
        let k = (t / dt).floor();
        let f = t / dt - k;
        (1.0 - f) * sine(k * dt) + f * sine((k + 1.0) * dt)
    };
    compare_av(
        &block,
        &[("interface", enums::RIGID)],
        (-1.3 * g_tan, Some(av)),
        1e-8,
    );
    for law in [enums::ELASTIC, enums::ELASTO_PLASTIC] {
        compare_av(
            &block,
            &[("interface", law)],
            (-1.5 * g_tan, Some(av)),
            1e-7,
        );
    }
    // a box section whose contact and plastic edges pass its flange edges:
    // the indicators of docs/model.md §6.4 at N, and the kinks of omegaW's
    // inertia at the weight (measured 6.0e-9 rad; 4.8e-6 with only joint
    // opening and crushing onset of the latter located; 4.2e-9 without av)
    let hollow = [("B", 0.5), ("H", 2.5), ("t", 0.1), ("kn", 1e8), ("fm", 1e6)];
    compare_av(
        &hollow,
        &[
            ("interface", enums::ELASTO_PLASTIC),
            ("shape", enums::HOLLOW_RECTANGLE),
        ],
        (-1.5 * g_tan, Some(av)),
        1e-7,
    );
    compare_av(
        &hollow,
        &[
            ("interface", enums::ELASTO_PLASTIC),
            ("shape", enums::HOLLOW_RECTANGLE),
        ],
        (-1.5 * g_tan, None),
        1e-7,
    );
}

#[test]
fn overturning_sets_terminate_simulation_with_a_message() {
    let me = Me::new(true);
    let cats = [c"logEvents".as_ptr()];
    assert_eq!(
        unsafe { fmi2SetDebugLogging(me.0.c, fmi2True, 1, cats.as_ptr()) },
        fmi2OK
    );
    assert_eq!(me.0.set_integer("interface", enums::RIGID), fmi2OK);
    // thrown toward the toe fast enough to go over (alpha = 0.197 rad)
    assert_eq!(me.0.set_real("omega", 3.0), fmi2OK);
    me.0.init();
    assert!(!me.event_iteration());
    assert_eq!(me.enter_continuous(), fmi2OK);
    let ag = |_t: f64| 0.0;
    let (mut t, mut x) = (0.0, me.x());
    let mut z0 = me.z();
    let terminated = loop {
        assert!(t < 5.0, "no overturning");
        x = rk4(&me, &ag, t, x, 1e-3);
        t += 1e-3;
        let z = at(&me, &ag, t, x);
        me.completed_step();
        if crossed(&z0, &z) {
            assert_eq!(me.enter_event_mode(), fmi2OK);
            if me.event_iteration() {
                break t;
            }
            assert_eq!(me.enter_continuous(), fmi2OK);
            x = me.x();
        }
        z0 = me.z();
    };
    assert!(me.0.boolean("overturned"));
    assert_eq!(me.0.integer("regime"), 4);
    assert!(x[0].abs() >= me.0.real("thetaOv"));
    assert!(
        me.0.messages()
            .iter()
            .any(|m| m.text.contains("overturned") && m.text.contains("terminateSimulation")),
        "{:?}",
        me.0.messages()
    );
    assert_eq!(me.dx(), [0.0, 0.0]);
    assert_eq!(me.0.terminate(), fmi2OK);
    eprintln!("overturned at t = {terminated}");
}

#[test]
fn state_machine_and_argument_checks() {
    let me = Me::new(false);
    let mut x = [0.0; NX];
    // before initialization: no states, no derivatives
    assert_eq!(
        unsafe { fmi2GetDerivatives(me.0.c, x.as_mut_ptr(), NX) },
        fmi2Error
    );
    let me = Me::new(false);
    assert_eq!(me.set_time(0.0), fmi2Error);
    let me = Me::new(false);
    assert_eq!(
        unsafe { fmi2GetNominalsOfContinuousStates(me.0.c, x.as_mut_ptr(), NX) },
        fmi2OK
    );
    assert_eq!(x, [1.0, 1.0]);
    me.0.init();
    // event mode after initialization
    assert_eq!(me.0.do_step(0.0, 0.1), fmi2Error);
    let me = Me::initialized();
    assert_eq!(
        me.set_x(&[0.1, 0.0]),
        fmi2Error,
        "states are set in continuous-time mode only"
    );
    let me = Me::initialized();
    assert!(!me.event_iteration());
    assert_eq!(me.enter_continuous(), fmi2OK);
    assert_eq!(me.set_x(&[0.01, 0.0]), fmi2OK);
    assert_eq!(me.x(), [0.01, 0.0]);
    assert_eq!(me.dx()[0], 0.0);
    assert!(me.dx()[1] < 0.0, "falls back toward theta = 0");
    let theta_ov = me.0.real("thetaOv");
    let mut nom = [0.0; NX];
    assert_eq!(
        unsafe { fmi2GetNominalsOfContinuousStates(me.0.c, nom.as_mut_ptr(), NX) },
        fmi2OK
    );
    assert_eq!(nom[0], theta_ov);
    assert!(nom[1] > 0.0);
    // wrong sizes and values
    assert_eq!(
        unsafe { fmi2SetContinuousStates(me.0.c, x.as_ptr(), 1) },
        fmi2Error
    );
    let me = Me::continuous();
    assert_eq!(me.set_x(&[f64::NAN, 0.0]), fmi2Error);
    let me = Me::initialized();
    let mut z = [0.0; 3];
    assert_eq!(
        unsafe { fmi2GetEventIndicators(me.0.c, z.as_mut_ptr(), 3) },
        fmi2Error
    );
    // continuous-time mode refuses the event-mode calls, and vice versa
    let me = Me::continuous();
    assert_eq!(me.enter_continuous(), fmi2Error);
    let me = Me::initialized();
    let (mut e, mut t) = (0, 0);
    assert_eq!(
        unsafe { fmi2CompletedIntegratorStep(me.0.c, fmi2True, &mut e, &mut t) },
        fmi2Error
    );
    // a co-simulation instance has no Model Exchange functions
    let cs = Host::new();
    cs.init();
    assert_eq!(
        unsafe { fmi2GetDerivatives(cs.c, x.as_mut_ptr(), NX) },
        fmi2Error
    );
}

#[test]
fn fmu_state_restores_the_toe_and_the_run_repeats_bit_for_bit() {
    let ag = |_t: f64| 0.0;
    let me = Me::new(false);
    assert_eq!(me.0.set_integer("interface", enums::RIGID), fmi2OK);
    assert_eq!(me.0.set_real("theta", 0.1), fmi2OK);
    me.0.init();
    me.event_iteration();
    me.enter_continuous();
    // integrate to just past the first impact (about 0.65 s) with Euler
    let x0 = me.x();
    let z0 = at(&me, &ag, 0.0, x0);
    let mut impacts = 0;
    let mut saved = None;
    let mut trace = Vec::new();
    euler(&me, &ag, (0.0, x0), z0, |t, x, event| {
        if event {
            impacts += 1;
            if impacts == 1 {
                saved = Some((me.0.get_state(), t, x));
            }
        }
        if impacts >= 1 {
            trace.push(x[0]);
        }
    });
    let (mut s, t_s, x_s) = saved.unwrap();
    assert_eq!(me.0.set_state(s), fmi2OK);
    assert_eq!(me.x(), x_s);
    let mut again = vec![x_s[0]];
    euler(&me, &ag, (t_s, x_s), me.z(), |_, x, _| again.push(x[0]));
    assert_eq!(trace.len(), again.len());
    assert!(trace
        .iter()
        .zip(&again)
        .all(|(a, b)| a.to_bits() == b.to_bits()));
    me.0.free_state(&mut s);
}

#[test]
fn a_serialized_state_restores_only_into_its_own_fmu_type() {
    let deserialize = |h: &Host, buf: &[u8]| {
        let mut s: fmi2FMUstate = std::ptr::null_mut();
        // SAFETY: a live instance and a buffer of the length passed.
        let st = unsafe {
            fmi2DeSerializeFMUstate(h.c, buf.as_ptr() as *const fmi2Byte, buf.len(), &mut s)
        };
        if !s.is_null() {
            assert_eq!(h.free_state(&mut s), fmi2OK);
        }
        st
    };
    let me = Me::initialized();
    let mut s = me.0.get_state();
    let me_buf = me.0.serialize(s);
    me.0.free_state(&mut s);
    let cs = Host::new();
    cs.init();
    let mut s = cs.get_state();
    let cs_buf = cs.serialize(s);
    cs.free_state(&mut s);
    // eventMode into a co-simulation instance, stepComplete into an ME one
    assert_eq!(deserialize(&cs, &me_buf), fmi2Error);
    let me2 = Me::new(false);
    assert_eq!(deserialize(&me2.0, &cs_buf), fmi2Error);
    let me3 = Me::new(false);
    assert_eq!(deserialize(&me3.0, &me_buf), fmi2OK);
}
