//! A small FMI 2.0 host of the RockingBlock FMU through its exported C
//! functions (`fmi2Instantiate` ... `fmi2FreeInstance`, the very symbols the
//! cdylib exports, linked in from the rlib). Shared by the thread and memory
//! tests, the memcheck loop (`examples/c_api_loop.rs`) and the memory bench
//! (`benches/memory.rs`, which include it with `#[path]`).
//!
//! Every call's status is checked; the logger counts messages per instance
//! and keeps only the last one, so a long run does not grow the host's own
//! memory.

#![allow(dead_code)]

use std::ffi::{c_char, c_void, CStr, CString};
use std::path::{Path, PathBuf};
use std::ptr;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

use fmi2_export::types::*;
use fmu_rocking::description::{enums, vr};
use fmu_rocking::*;

/// The real outputs read after every step, in this order.
pub const REAL_OUTPUTS: [u32; 9] = [
    vr::THETA,
    vr::OMEGA,
    vr::ANGULAR_ACCELERATION,
    vr::THETA_OVER_ALPHA,
    vr::AF,
    vr::CONTACT_LENGTH,
    vr::MR,
    vr::FX,
    vr::FZ,
];
/// The integer outputs read after every step.
pub const INT_OUTPUTS: [u32; 2] = [vr::REGIME, vr::IMPACTS];

/// What the logger saw for one instance.
#[derive(Default)]
pub struct LogSink {
    pub messages: AtomicU64,
    pub errors: AtomicU64,
    pub last: Mutex<String>,
}

extern "C" fn logger(
    env: *mut c_void,
    _name: *const c_char,
    status: fmi2Status,
    _category: *const c_char,
    message: *const c_char,
) {
    // SAFETY: env is the LogSink given at instantiation (alive as long as
    // the instance); the message is a valid NUL-terminated string.
    let sink = unsafe { &*(env as *const LogSink) };
    sink.messages.fetch_add(1, Ordering::Relaxed);
    if status >= fmi2Error {
        sink.errors.fetch_add(1, Ordering::Relaxed);
    }
    let m = unsafe { CStr::from_ptr(message) }.to_string_lossy();
    let mut last = sink.last.lock().unwrap();
    last.clear();
    last.push_str(&m);
}

/// Outputs after one step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    pub reals: [f64; 9],
    pub ints: [i32; 2],
    pub overturned: bool,
}

impl Sample {
    /// Every output as bits (for bit-for-bit comparisons).
    pub fn bits(&self) -> [u64; 12] {
        let mut b = [0u64; 12];
        for (k, x) in self.reals.iter().enumerate() {
            b[k] = x.to_bits();
        }
        b[9] = self.ints[0] as u64;
        b[10] = self.ints[1] as u64;
        b[11] = self.overturned as u64;
        b
    }
}

/// One instance. Dropping it frees the instance.
pub struct Fmu {
    pub c: fmi2Component,
    pub sink: Box<LogSink>,
    _callbacks: Box<fmi2CallbackFunctions>,
}

unsafe impl Send for Fmu {}

impl Fmu {
    /// `fmi2Instantiate` with a logger (`logging_on` = debug logging).
    pub fn new(name: &str, logging_on: bool) -> Fmu {
        let sink = Box::<LogSink>::default();
        let callbacks = Box::new(fmi2CallbackFunctions {
            // SAFETY: the FMU calls the logger with no variadic arguments
            // (it formats its messages itself); on x86-64 System V a
            // non-variadic callee receives such a call unchanged.
            logger: Some(unsafe {
                std::mem::transmute::<
                    extern "C" fn(
                        *mut c_void,
                        *const c_char,
                        fmi2Status,
                        *const c_char,
                        *const c_char,
                    ),
                    fmi2CallbackLogger,
                >(logger)
            }),
            allocateMemory: None,
            freeMemory: None,
            stepFinished: None,
            componentEnvironment: &*sink as *const LogSink as *mut c_void,
        });
        let name = CString::new(name).unwrap();
        let guid = CString::new(GUID).unwrap();
        let c = unsafe {
            fmi2Instantiate(
                name.as_ptr(),
                fmi2CoSimulation,
                guid.as_ptr(),
                c"file:///tmp/rocking-resources".as_ptr(),
                &*callbacks,
                fmi2False,
                logging_on as fmi2Boolean,
            )
        };
        assert!(!c.is_null(), "fmi2Instantiate returned NULL");
        Fmu {
            c,
            sink,
            _callbacks: callbacks,
        }
    }

    fn check(&self, what: &str, s: fmi2Status, want: fmi2Status) {
        assert_eq!(
            s,
            want,
            "{what}: status {s}, last message: {}",
            self.sink.last.lock().unwrap()
        );
    }

    pub fn debug_logging(&self, on: bool, categories: &[&str]) {
        let cs: Vec<CString> = categories
            .iter()
            .map(|c| CString::new(*c).unwrap())
            .collect();
        let ps: Vec<fmi2String> = cs.iter().map(|c| c.as_ptr()).collect();
        let s = unsafe { fmi2SetDebugLogging(self.c, on as fmi2Boolean, ps.len(), ps.as_ptr()) };
        self.check("fmi2SetDebugLogging", s, fmi2OK);
    }

    pub fn setup(&self, tolerance: Option<f64>, start: f64, stop: Option<f64>) {
        let s = unsafe {
            fmi2SetupExperiment(
                self.c,
                tolerance.is_some() as fmi2Boolean,
                tolerance.unwrap_or(0.0),
                start,
                stop.is_some() as fmi2Boolean,
                stop.unwrap_or(0.0),
            )
        };
        self.check("fmi2SetupExperiment", s, fmi2OK);
    }

    pub fn set_reals(&self, pairs: &[(u32, f64)]) -> fmi2Status {
        let (vrs, xs): (Vec<u32>, Vec<f64>) = pairs.iter().copied().unzip();
        unsafe { fmi2SetReal(self.c, vrs.as_ptr(), vrs.len(), xs.as_ptr()) }
    }

    pub fn set_integers(&self, pairs: &[(u32, i32)]) -> fmi2Status {
        let (vrs, xs): (Vec<u32>, Vec<i32>) = pairs.iter().copied().unzip();
        unsafe { fmi2SetInteger(self.c, vrs.as_ptr(), vrs.len(), xs.as_ptr()) }
    }

    /// Sets the parameters of `case`, enters and leaves initialization.
    pub fn init(&self, case: &Case) {
        self.setup(case.tolerance, 0.0, None);
        self.check("fmi2SetInteger", self.set_integers(&case.ints), fmi2OK);
        self.check("fmi2SetReal", self.set_reals(&case.reals), fmi2OK);
        let s = unsafe { fmi2EnterInitializationMode(self.c) };
        self.check("fmi2EnterInitializationMode", s, fmi2OK);
        let s = unsafe { fmi2ExitInitializationMode(self.c) };
        self.check("fmi2ExitInitializationMode", s, fmi2OK);
    }

    /// Sets `ag` (and its slope, if not 0), then one `fmi2DoStep`.
    pub fn step(&self, t: f64, h: f64, ag: f64, dag: f64) -> fmi2Status {
        let s = unsafe { fmi2SetReal(self.c, &vr::AG, 1, &ag) };
        self.check("fmi2SetReal(ag)", s, fmi2OK);
        if dag != 0.0 {
            let s = unsafe { fmi2SetRealInputDerivatives(self.c, &vr::AG, 1, &1, &dag) };
            self.check("fmi2SetRealInputDerivatives", s, fmi2OK);
        }
        unsafe { fmi2DoStep(self.c, t, h, fmi2False) }
    }

    pub fn sample(&self) -> Sample {
        let mut reals = [f64::NAN; 9];
        let mut ints = [-1i32; 2];
        let mut b = -1;
        unsafe {
            let s = fmi2GetReal(
                self.c,
                REAL_OUTPUTS.as_ptr(),
                REAL_OUTPUTS.len(),
                reals.as_mut_ptr(),
            );
            self.check("fmi2GetReal", s, fmi2OK);
            let s = fmi2GetInteger(
                self.c,
                INT_OUTPUTS.as_ptr(),
                INT_OUTPUTS.len(),
                ints.as_mut_ptr(),
            );
            self.check("fmi2GetInteger", s, fmi2OK);
            let s = fmi2GetBoolean(self.c, &vr::OVERTURNED, 1, &mut b);
            self.check("fmi2GetBoolean", s, fmi2OK);
        }
        Sample {
            reals,
            ints,
            overturned: b != fmi2False,
        }
    }

    pub fn get_state(&self) -> fmi2FMUstate {
        let mut st: fmi2FMUstate = ptr::null_mut();
        let s = unsafe { fmi2GetFMUstate(self.c, &mut st) };
        self.check("fmi2GetFMUstate", s, fmi2OK);
        st
    }

    /// Overwrites an existing state (`fmi2GetFMUstate` with `*state != NULL`).
    pub fn update_state(&self, st: &mut fmi2FMUstate) {
        let s = unsafe { fmi2GetFMUstate(self.c, st) };
        self.check("fmi2GetFMUstate (overwrite)", s, fmi2OK);
    }

    pub fn set_state(&self, st: fmi2FMUstate) {
        let s = unsafe { fmi2SetFMUstate(self.c, st) };
        self.check("fmi2SetFMUstate", s, fmi2OK);
    }

    pub fn free_state(&self, st: &mut fmi2FMUstate) {
        let s = unsafe { fmi2FreeFMUstate(self.c, st) };
        self.check("fmi2FreeFMUstate", s, fmi2OK);
        assert!(st.is_null());
    }

    pub fn serialize(&self, st: fmi2FMUstate) -> Vec<u8> {
        let mut n = 0usize;
        let s = unsafe { fmi2SerializedFMUstateSize(self.c, st, &mut n) };
        self.check("fmi2SerializedFMUstateSize", s, fmi2OK);
        let mut buf = vec![0u8; n];
        let s = unsafe { fmi2SerializeFMUstate(self.c, st, buf.as_mut_ptr() as *mut fmi2Byte, n) };
        self.check("fmi2SerializeFMUstate", s, fmi2OK);
        buf
    }

    pub fn deserialize(&self, buf: &[u8]) -> fmi2FMUstate {
        let mut st: fmi2FMUstate = ptr::null_mut();
        let s = unsafe {
            fmi2DeSerializeFMUstate(self.c, buf.as_ptr() as *const fmi2Byte, buf.len(), &mut st)
        };
        self.check("fmi2DeSerializeFMUstate", s, fmi2OK);
        st
    }

    pub fn terminated(&self) -> bool {
        let mut b = -1;
        let s = unsafe { fmi2GetBooleanStatus(self.c, fmi2Terminated, &mut b) };
        self.check("fmi2GetBooleanStatus", s, fmi2OK);
        b != fmi2False
    }

    pub fn last_successful_time(&self) -> f64 {
        let mut t = f64::NAN;
        let s = unsafe { fmi2GetRealStatus(self.c, fmi2LastSuccessfulTime, &mut t) };
        self.check("fmi2GetRealStatus", s, fmi2OK);
        t
    }

    pub fn terminate(&self) {
        let s = unsafe { fmi2Terminate(self.c) };
        self.check("fmi2Terminate", s, fmi2OK);
    }

    pub fn reset(&self) {
        let s = unsafe { fmi2Reset(self.c) };
        self.check("fmi2Reset", s, fmi2OK);
    }
}

impl Drop for Fmu {
    fn drop(&mut self) {
        unsafe { fmi2FreeInstance(self.c) };
    }
}

/// The ground acceleration of a case.
#[derive(Clone, Debug)]
pub enum Ground {
    /// `a sin(2 pi f t)` for `t < t_end`, then 0.
    Sine { a: f64, f: f64, t_end: f64 },
    /// A record sampled at the communication step, repeated.
    Record(std::sync::Arc<Vec<f64>>),
}

impl Ground {
    /// The input for step `k` (time `t`).
    pub fn at(&self, k: usize, t: f64) -> f64 {
        match self {
            Ground::Sine { a, f, t_end } => {
                if t < *t_end {
                    a * (2.0 * std::f64::consts::PI * f * t).sin()
                } else {
                    0.0
                }
            }
            Ground::Record(r) => r[k % r.len()],
        }
    }
}

/// Parameters, tolerance, communication step and ground motion of one run.
#[derive(Clone, Debug)]
pub struct Case {
    pub name: String,
    pub ints: Vec<(u32, i32)>,
    pub reals: Vec<(u32, f64)>,
    pub tolerance: Option<f64>,
    pub h: f64,
    pub ground: Ground,
    /// Also pass the input's slope to the next sample (first-order hold).
    pub slopes: bool,
}

impl Case {
    /// The ground input and its slope for step `k`.
    pub fn input(&self, k: usize) -> (f64, f64) {
        let t = k as f64 * self.h;
        let a = self.ground.at(k, t);
        if self.slopes {
            let b = self.ground.at(k + 1, t + self.h);
            (a, (b - a) / self.h)
        } else {
            (a, 0.0)
        }
    }
}

/// A rigid (Housner) block rocking with impacts under a sine pulse; `scale`
/// varies the block (height) and `amp` the forcing (in units of g tan alpha).
pub fn rigid_case(scale: f64, amp: f64) -> Case {
    let (b, h) = (0.4, 2.0 * scale);
    let alpha = (b / h).atan();
    Case {
        name: format!("rigid x{scale}"),
        ints: vec![
            (vr::INTERFACE, enums::RIGID),
            (vr::RESTITUTION, enums::HOUSNER),
        ],
        reals: vec![(vr::B, b), (vr::H, h)],
        tolerance: Some(1e-8),
        h: 0.01,
        ground: Ground::Sine {
            a: amp * 9.81 * alpha.tan(),
            f: 2.5 / scale.sqrt(),
            t_end: 2.0,
        },
        slopes: false,
    }
}

/// A block on a flexible interface that crushes (kn = 1e8 Pa/m; with
/// fm = 0.2 MPa the toe crushes at theta_c = 9e-3 rad, amp = 1.2 rocks it to
/// 0.08 rad with impacts), forced by a sine pulse, with the input's slope
/// passed each step; `scale`, `fm` and `amp` (in g tan alpha) vary it.
pub fn crushing_case(scale: f64, fm: f64, amp: f64) -> Case {
    let (b, h) = (0.5, 2.5 * scale);
    let alpha = (b / h).atan();
    Case {
        name: format!("crushing x{scale} fm {fm}"),
        ints: vec![(vr::INTERFACE, enums::ELASTO_PLASTIC)],
        reals: vec![(vr::B, b), (vr::H, h), (vr::KN, 1e8), (vr::FM, fm)],
        tolerance: Some(1e-8),
        h: 0.01,
        ground: Ground::Sine {
            a: amp * 9.81 * alpha.tan(),
            f: 1.2 / scale.sqrt(),
            t_end: 1.5,
        },
        slopes: true,
    }
}

/// Blocks that rock with impacts, then overturn a little after t = 2 s: the
/// rigid case with twice the forcing (at 2 Hz, for 10 s), or the crushing
/// case with 2 g tan alpha.
pub fn overturning_case(crushing: bool) -> Case {
    let mut c = if crushing {
        crushing_case(1.0, 2e5, 2.0)
    } else {
        let mut c = rigid_case(1.0, 4.0);
        if let Ground::Sine { f, t_end, .. } = &mut c.ground {
            *f = 2.0;
            *t_end = 10.0;
        }
        c
    };
    c.name = format!(
        "overturning {}",
        if crushing { "crushing" } else { "rigid" }
    );
    c.tolerance = None;
    c
}

/// The ground-motion records shipped with the repository.
pub fn ground_motions() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/ground-motions")
}

/// The KATNP stand-in record (synthetic, 100 Hz, m/s²).
pub fn katnp_standin() -> Vec<f64> {
    let p = ground_motions().join("katnp-standin/KATNP_NS_standin.csv");
    let text =
        std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("cannot read {}: {e}", p.display()));
    text.lines()
        .filter(|l| !l.starts_with('#'))
        .skip(1)
        .map(|l| l.split(',').nth(1).unwrap().trim().parse().unwrap())
        .collect()
}

/// Runs `case` for `steps` steps on a fresh, already initialised `fmu`,
/// calling `each(k, sample)` after every step; stops at overturning.
/// Returns the number of completed steps.
pub fn run(fmu: &Fmu, case: &Case, steps: usize, mut each: impl FnMut(usize, &Sample)) -> usize {
    for k in 0..steps {
        let (a, d) = case.input(k);
        let s = fmu.step(k as f64 * case.h, case.h, a, d);
        if s == fmi2Discard {
            assert!(fmu.terminated());
            return k;
        }
        assert_eq!(s, fmi2OK, "{}: fmi2DoStep at step {k}", case.name);
        each(k, &fmu.sample());
    }
    steps
}

/// Memory of this process from `/proc/self/status`, KiB.
#[derive(Clone, Copy, Debug, Default)]
pub struct Mem {
    /// Resident set size (`VmRSS`: anonymous + file-backed + shared).
    pub rss: u64,
    /// Peak resident set size (`VmHWM`).
    pub hwm: u64,
    /// Resident anonymous memory (`RssAnon`: heap, stacks), where a leak shows.
    pub anon: u64,
}

pub fn mem() -> Mem {
    let s = std::fs::read_to_string("/proc/self/status").unwrap();
    let field = |name: &str| {
        s.lines()
            .find(|l| l.starts_with(name))
            .and_then(|l| l.split_whitespace().nth(1))
            .and_then(|x| x.parse().ok())
            .unwrap_or_else(|| panic!("{name} not in /proc/self/status"))
    };
    Mem {
        rss: field("VmRSS:"),
        hwm: field("VmHWM:"),
        anon: field("RssAnon:"),
    }
}

/// One instance's whole life: instantiate, set up, parameters, initialise,
/// `steps` steps with outputs read, an FMU state taken, serialized,
/// deserialized, set and both freed, terminate, free.
pub fn instance_cycle(case: &Case, steps: usize) {
    let f = Fmu::new(&case.name, false);
    f.init(case);
    run(&f, case, steps, |_, _| {});
    let mut st = f.get_state();
    let bytes = f.serialize(st);
    let mut back = f.deserialize(&bytes);
    f.set_state(back);
    f.free_state(&mut back);
    f.free_state(&mut st);
    f.terminate();
}

/// The long run: the KATNP stand-in (synthetic, 80 s at 100 Hz), times 1.2
/// and repeated, on a flexible interface that crushes (kn = 1e9 Pa/m,
/// fm = 0.3 MPa): the block rocks to about 0.2 alpha with about 50 impacts
/// per 1000 steps and partial crushing, and does not overturn; the input's
/// slope is passed every step.
pub fn record_case() -> (Case, &'static str) {
    let ground: Vec<f64> = katnp_standin().iter().map(|a| 1.2 * a).collect();
    let what = "KATNP stand-in x1.2, repeated";
    let mut c = crushing_case(1.0, 3e5, 0.0);
    for (r, x) in &mut c.reals {
        if *r == vr::KN {
            *x = 1e9;
        }
    }
    c.name = "record, crushing interface".into();
    c.ground = Ground::Record(std::sync::Arc::new(ground));
    (c, what)
}

/// Bursts of shaking sampled every 0.01 s (`n` samples): every 10 s, a sine
/// at `f` Hz whose amplitude rises to `a` and falls back over 4 s, then 6 s
/// of quiet.
pub fn bursts(a: f64, f: f64, n: usize) -> Vec<f64> {
    use std::f64::consts::PI;
    (0..n)
        .map(|k| {
            let t = k as f64 * 0.01;
            let s = t % 10.0;
            if s < 4.0 {
                a * (PI * s / 4.0).sin() * (2.0 * PI * f * t).sin()
            } else {
                0.0
            }
        })
        .collect()
}
