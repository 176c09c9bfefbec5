//! The RockingBlock runs the C-API tests, the memcheck loop
//! (`examples/c_api_loop.rs`) and the memory bench share: cases (parameters,
//! tolerance, step, ground motion), the outputs read after each step, the
//! run loop, and the memory of this process.

use std::path::{Path, PathBuf};

use super::*;

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

/// What a case needs of the host beyond the generic calls; every call's
/// status is checked.
pub trait CaseHost {
    /// Sets the parameters of `case`, sets up, enters and leaves initialization.
    fn init_case(&self, case: &Case);
    /// Sets `ag` (and its slope, if not 0), then one `fmi2DoStep`.
    fn step(&self, t: f64, h: f64, ag: f64, dag: f64) -> fmi2Status;
    /// The outputs now.
    fn sample(&self) -> Sample;
}

impl CaseHost for Host {
    fn init_case(&self, case: &Case) {
        self.check("fmi2SetupExperiment", self.setup(case.tolerance, 0.0, None));
        self.check("fmi2SetInteger", self.set_integers(&case.ints));
        self.check("fmi2SetReal", self.set_reals(&case.reals));
        self.check("fmi2ExitInitializationMode", self.initialize());
    }

    fn step(&self, t: f64, h: f64, ag: f64, dag: f64) -> fmi2Status {
        self.check("fmi2SetReal(ag)", self.set_real_vr(vr::AG, ag));
        if dag != 0.0 {
            let s = self.set_input_derivative_vr(vr::AG, 1, dag);
            self.check("fmi2SetRealInputDerivatives", s);
        }
        self.do_step(t, h)
    }

    fn sample(&self) -> Sample {
        let (s, reals) = self.get_reals_vr(&REAL_OUTPUTS);
        self.check("fmi2GetReal", s);
        let (s, ints) = self.get_integers_vr(&INT_OUTPUTS);
        self.check("fmi2GetInteger", s);
        let (s, overturned) = self.get_boolean_vr(vr::OVERTURNED);
        self.check("fmi2GetBoolean", s);
        Sample {
            reals: reals.try_into().unwrap(),
            ints: ints.try_into().unwrap(),
            overturned,
        }
    }
}

/// A host for a long run: named `name`, resources at a made-up location,
/// only the last message kept.
pub fn long_run_host(name: &str, logging_on: bool) -> Host {
    Host::with(Options {
        name,
        logging_on,
        resources: Some("file:///tmp/rocking-resources"),
        keep: Keep::Last,
        ..Options::default()
    })
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
pub fn run(fmu: &Host, case: &Case, steps: usize, mut each: impl FnMut(usize, &Sample)) -> usize {
    for k in 0..steps {
        let (a, d) = case.input(k);
        let s = fmu.step(k as f64 * case.h, case.h, a, d);
        if s == fmi2Discard {
            assert_eq!(fmu.terminated(), (fmi2OK, true));
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
    let f = long_run_host(&case.name, false);
    f.init_case(case);
    run(&f, case, steps, |_, _| {});
    let mut st = f.get_state();
    let bytes = f.serialize(st);
    let mut back = f.deserialize(&bytes);
    f.check("fmi2SetFMUstate", f.set_state(back));
    f.check("fmi2FreeFMUstate", f.free_state(&mut back));
    f.check("fmi2FreeFMUstate", f.free_state(&mut st));
    f.check("fmi2Terminate", f.terminate());
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
