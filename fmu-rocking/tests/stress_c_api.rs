//! The extreme-but-valid grid of `tests/dynamics_stress.rs`, coarser, run
//! through the FMU's C API (exported `fmi2*` functions): kn 1e6..1e15 Pa/m
//! (raised to 3x the stability limit `W hG / Is` where needed), fm from
//! 1.01 W/A to none, slenderness 0.01..0.6, heights 0.1..100 m,
//! communication steps 1e-5..1 s, every shape, law and formulation, input
//! given as values or as values with first derivatives, start times 0 and
//! 1e9 s, and a seeded random sweep.
//!
//! Every step returns `fmi2OK`, or `fmi2Discard` with `overturned` true,
//! `fmi2Terminated` true and `fmi2LastSuccessfulTime` inside the step (then
//! the run ends); never `fmi2Error` or `fmi2Warning`, no error message.
//! After every step no output is NaN, the state outputs are finite and
//! `|theta| <= thetaOv`. Each run has a watchdog (a stalled `fmi2DoStep`
//! fails the test instead of hanging it).

#![allow(non_upper_case_globals)] // the FMI constants keep their C names

mod host;
#[path = "../../tests/support/lcg.rs"]
mod lcg;

use std::f64::consts::PI;
use std::sync::mpsc;
use std::thread;
use std::time::{Duration, Instant};

use fmi2_export::model_description::Causality;
use host::*;
use lcg::Lcg;

#[derive(Clone, Copy, Debug)]
struct Case {
    shape: i32,
    /// Height of the prism, m.
    size: f64,
    alpha: f64,
    law: i32,
    kn: f64,
    /// fm as a multiple of W/A (infinite: none).
    fm_ratio: f64,
    formulation: i32,
    /// Peak ground acceleration over g tan(alpha).
    shaking: f64,
    /// The shaking lasts this long, then the record is quiet.
    shake_time: f64,
    record: f64,
    dt: f64,
    /// Give the input's slope with fmi2SetRealInputDerivatives.
    derivatives: bool,
    start: f64,
    /// kn as a multiple of the stability limit W hG / Is (0: kn, raised to
    /// 3x the limit where needed).
    kn_factor: f64,
}

const RHO: f64 = 2000.0;
const G: f64 = 9.81;

use enums::*;

/// Depth D = H tan(alpha) and the shape's sizes; area and second moment
/// (docs/model.md §1) for the stability limit.
fn geometry(c: &Case) -> (Vec<(&'static str, f64)>, f64, f64) {
    let d = c.size * c.alpha.tan();
    match c.shape {
        SOLID_RECTANGLE => (vec![("B", d), ("L", d)], d * d, d * d.powi(3) / 12.0),
        HOLLOW_RECTANGLE => {
            let t = 0.2 * d;
            let i = d - 2.0 * t;
            (
                vec![("B", d), ("L", d), ("t", t)],
                d * d - i * i,
                (d * d.powi(3) - i * i.powi(3)) / 12.0,
            )
        }
        SOLID_CIRCLE => {
            let r = d / 2.0;
            (vec![("Ro", r)], PI * r * r, PI * r.powi(4) / 4.0)
        }
        _ => {
            let (ro, ri) = (d / 2.0, 0.3 * d);
            (
                vec![("Ro", ro), ("Ri", ri)],
                PI * (ro * ro - ri * ri),
                PI * (ro.powi(4) - ri.powi(4)) / 4.0,
            )
        }
    }
}

const OUTPUTS: [&str; 10] = [
    "theta",
    "omega",
    "angularAcceleration",
    "thetaOverAlpha",
    "af",
    "contactLength",
    "MR",
    "Fx",
    "Fz",
    "ag",
];

/// The calculated parameters (all Real), as the table declares them.
fn calculated() -> impl Iterator<Item = &'static str> {
    ROCKING_BLOCK
        .variables
        .iter()
        .filter(|v| v.causality == Causality::CalculatedParameter)
        .map(|v| v.name)
}

#[derive(Debug, Default)]
struct Outcome {
    steps: usize,
    overturned: bool,
    impacts: i32,
    zero_crossings: i32,
    seconds: f64,
}

fn run(c: Case) -> Result<Outcome, String> {
    let started = Instant::now();
    let h = Host::new();
    let fail = |what: String| -> Result<Outcome, String> { Err(format!("{c:?}: {what}")) };
    let (sizes, area, is) = geometry(&c);
    for (n, x) in [
        ("shape", c.shape),
        ("massModel", PRISM),
        ("interface", c.law),
        ("formulation", c.formulation),
    ] {
        if h.set_integer(n, x) != fmi2OK {
            return fail(format!("set {n}: {:?}", h.messages()));
        }
    }
    let w = RHO * G * area * c.size;
    let kn_min = w * (c.size / 2.0) / is;
    let kn = if c.kn_factor > 0.0 {
        c.kn_factor * kn_min
    } else {
        c.kn.max(3.0 * kn_min)
    };
    let mut reals = sizes;
    reals.extend([
        ("H", c.size),
        ("rho", RHO),
        ("g", G),
        ("kn", kn),
        ("fm", c.fm_ratio * RHO * G * c.size),
    ]);
    for &(n, x) in &reals {
        if h.set_real(n, x) != fmi2OK {
            return fail(format!("set {n} = {x}: {:?}", h.messages()));
        }
    }
    if h.setup(None, c.start, None) != fmi2OK || h.enter_init() != fmi2OK {
        return fail(format!("setup: {:?}", h.messages()));
    }
    if h.exit_init() != fmi2OK {
        return fail(format!("valid parameters refused: {:?}", h.messages()));
    }
    for n in calculated() {
        let x = h.real(n);
        // finite, thetaC without crushing too (1e60: docs/model.md §5)
        if !x.is_finite() {
            return fail(format!("{n} = {x}"));
        }
    }
    let (weight, r0, io, alpha, theta_ov) = (
        h.real("weight"),
        h.real("R0"),
        h.real("IO"),
        h.real("alpha"),
        h.real("thetaOv"),
    );
    // multi-frequency shaking around the body's own frequency
    let p = (weight * r0 / io).sqrt();
    let amp = c.shaking * G * alpha.tan();
    let ag = |t: f64| -> f64 {
        if t >= c.shake_time {
            return 0.0;
        }
        let x = p * t;
        -amp * (PI * t / c.shake_time).sin()
            * (0.6 * (0.7 * x).sin() + 0.3 * (1.9 * x + 1.0).sin() + 0.2 * (4.3 * x + 2.0).sin())
    };
    let n = (c.record / c.dt).round() as usize;
    let mut out = Outcome::default();
    for k in 0..n {
        let (t0, t1) = (k as f64 * c.dt, (k + 1) as f64 * c.dt);
        let tc = c.start + t0;
        let (a0, a1) = (ag(t0), ag(t1));
        if h.set_real("ag", a0) != fmi2OK {
            return fail(format!("set ag = {a0}: {:?}", h.messages()));
        }
        if c.derivatives && h.set_input_derivative("ag", 1, (a1 - a0) / c.dt) != fmi2OK {
            return fail(format!("set dag/dt: {:?}", h.messages()));
        }
        let s = h.do_step(tc, c.dt);
        out.steps += 1;
        let ov = h.boolean("overturned");
        match s {
            fmi2OK if !ov => {}
            fmi2Discard if ov => {
                let (st, term) = h.terminated();
                let (st2, last) = h.last_successful_time();
                if st != fmi2OK || !term || st2 != fmi2OK {
                    return fail(format!("Discard without fmi2Terminated at step {k}"));
                }
                if !(last >= tc - 1e-9 * tc.abs().max(1.0) && last <= tc + c.dt) {
                    return fail(format!(
                        "overturning time {last} outside the step ({tc}, {})",
                        tc + c.dt
                    ));
                }
                out.overturned = true;
            }
            _ => {
                return fail(format!(
                    "step {k} at t = {tc}: status {s}, overturned {ov}: {:?}",
                    h.messages()
                ))
            }
        }
        for (name, x) in OUTPUTS.iter().zip(h.reals(&OUTPUTS)) {
            if !x.is_finite() {
                return fail(format!("{name} = {x} after step {k}"));
            }
        }
        let theta = h.real("theta");
        if theta.abs() > theta_ov {
            return fail(format!("|theta| = {} > thetaOv = {theta_ov}", theta.abs()));
        }
        out.impacts = h.integer("impacts");
        out.zero_crossings = h.integer("zeroCrossings");
        if !(0..=out.zero_crossings).contains(&out.impacts) {
            return fail(format!(
                "impacts = {} outside [0, zeroCrossings = {}]",
                out.impacts, out.zero_crossings
            ));
        }
        let regime = h.integer("regime");
        if !(0..=4).contains(&regime) {
            return fail(format!("regime {regime}"));
        }
        if out.overturned {
            break;
        }
    }
    if h.terminate() != fmi2OK {
        return fail(format!("fmi2Terminate: {:?}", h.messages()));
    }
    let bad: Vec<_> = h
        .messages()
        .into_iter()
        .filter(|m| {
            m.status == fmi2Error
                || m.status == fmi2Fatal
                || (m.status != fmi2OK && !m.text.contains("overturned"))
        })
        .collect();
    if !bad.is_empty() {
        return fail(format!("messages: {bad:?}"));
    }
    out.seconds = started.elapsed().as_secs_f64();
    Ok(out)
}

/// Runs a case with a watchdog.
fn run_watched(c: Case, secs: u64) -> Outcome {
    let (tx, rx) = mpsc::channel();
    thread::spawn(move || {
        let _ = tx.send(run(c));
    });
    match rx.recv_timeout(Duration::from_secs(secs)) {
        Ok(Ok(o)) => o,
        Ok(Err(e)) => panic!("{e}"),
        Err(mpsc::RecvTimeoutError::Disconnected) => panic!("{c:?}: the run panicked (above)"),
        Err(mpsc::RecvTimeoutError::Timeout) => {
            panic!("{c:?}: no answer after {secs} s (a stalled fmi2DoStep)")
        }
    }
}

const BASE: Case = Case {
    shape: SOLID_RECTANGLE,
    size: 2.5,
    alpha: 0.2,
    law: ELASTO_PLASTIC,
    kn: 5e9,
    fm_ratio: 100.0,
    formulation: SHIFTING_PIVOT,
    shaking: 1.5,
    shake_time: 5.0,
    record: 12.0,
    dt: 0.01,
    derivatives: true,
    start: 0.0,
    kn_factor: 0.0,
};

fn grid() -> Vec<(&'static str, Case)> {
    let mut v = Vec::new();
    for kn in [1e6, 1e8, 1e10, 1e12, 1e14, 1e15] {
        for (law, fm_ratio) in [(ELASTIC, f64::INFINITY), (ELASTO_PLASTIC, 20.0)] {
            for shaking in [0.5, 1.5] {
                v.push((
                    "kn",
                    Case {
                        kn,
                        law,
                        fm_ratio,
                        shaking,
                        ..BASE
                    },
                ));
            }
        }
    }
    for fm_ratio in [1.01, 1.1, 2.0, 10.0, 1e3, f64::INFINITY] {
        for shaking in [0.5, 1.5] {
            v.push((
                "fm",
                Case {
                    fm_ratio,
                    shaking,
                    ..BASE
                },
            ));
        }
    }
    for alpha in [0.01, 0.2, 0.6] {
        for size in [0.1f64, 2.5, 100.0] {
            for law in [RIGID, ELASTO_PLASTIC] {
                let slow = size.sqrt().max(1.0);
                v.push((
                    "alpha/size",
                    Case {
                        alpha,
                        size,
                        law,
                        record: 12.0 * slow,
                        shake_time: 5.0 * slow,
                        dt: 0.01 * slow,
                        ..BASE
                    },
                ));
            }
        }
    }
    for (dt, record) in [
        (1e-5, 0.3),
        (1e-4, 2.0),
        (1e-3, 8.0),
        (0.1, 20.0),
        (1.0, 30.0),
    ] {
        for law in [RIGID, ELASTO_PLASTIC] {
            for derivatives in [true, false] {
                v.push((
                    "dt",
                    Case {
                        dt,
                        record,
                        shake_time: record.min(5.0),
                        law,
                        derivatives,
                        ..BASE
                    },
                ));
            }
        }
    }
    for shape in [
        SOLID_RECTANGLE,
        HOLLOW_RECTANGLE,
        SOLID_CIRCLE,
        HOLLOW_CIRCLE,
    ] {
        for formulation in [COSTA, SHIFTING_PIVOT] {
            for law in [RIGID, ELASTIC, ELASTO_PLASTIC] {
                v.push((
                    "shape/formulation/law",
                    Case {
                        shape,
                        formulation,
                        law,
                        fm_ratio: if law == ELASTIC { f64::INFINITY } else { 5.0 },
                        ..BASE
                    },
                ));
            }
        }
    }
    // at the validity limits: kn just above W hG / Is, fm just above W/A
    for delta in [1e-2, 1e-4, 1e-6] {
        for shape in [SOLID_RECTANGLE, HOLLOW_CIRCLE] {
            for (law, fm_ratio) in [(ELASTIC, f64::INFINITY), (ELASTO_PLASTIC, 1.0 + delta)] {
                v.push((
                    "validity limits",
                    Case {
                        shape,
                        law,
                        fm_ratio,
                        kn_factor: 1.0 + delta,
                        shaking: 0.3,
                        ..BASE
                    },
                ));
            }
            v.push((
                "validity limits",
                Case {
                    shape,
                    fm_ratio: 1.0 + delta,
                    shaking: 0.3,
                    ..BASE
                },
            ));
        }
    }
    // large start times (regression: fmi2DoStep hung at startTime 1e9 s)
    for (kn, start) in [(5e9, 1e9), (1e15, 1e4), (1e15, 1e9)] {
        v.push(("start time", Case { kn, start, ..BASE }));
    }
    // STRESS_RANDOM and STRESS_SEED widen the sweep for exploration
    let env = |k: &str, d: u64| {
        std::env::var(k)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(d)
    };
    let mut r = Lcg(env("STRESS_SEED", 0x5eed_c0a1));
    for _ in 0..env("STRESS_RANDOM", 300) {
        let law = r.pick(&[RIGID, ELASTIC, ELASTO_PLASTIC]);
        let dt = r.pick(&[1e-3, 0.01, 0.05, 0.3, 1.0]);
        let size = r.log_uniform(0.1, 100.0);
        v.push((
            "random",
            Case {
                shape: r.pick(&[
                    SOLID_RECTANGLE,
                    HOLLOW_RECTANGLE,
                    SOLID_CIRCLE,
                    HOLLOW_CIRCLE,
                ]),
                size,
                alpha: r.log_uniform(0.01, 0.6),
                law,
                kn: r.log_uniform(1e6, 1e15),
                fm_ratio: if law == ELASTIC {
                    f64::INFINITY
                } else {
                    1.01 + r.log_uniform(0.01, 1e3)
                },
                formulation: r.pick(&[SHIFTING_PIVOT, COSTA]),
                shaking: 3.0 * r.next(),
                shake_time: r.log_uniform(1.0, 10.0),
                record: 15.0 * size.sqrt().max(1.0),
                dt,
                derivatives: r.next() < 0.5,
                start: r.pick(&[0.0, 0.0, 100.0, 1e6]),
                kn_factor: 0.0,
            },
        ));
    }
    v
}

#[test]
fn the_stress_grid_through_the_c_api() {
    let started = Instant::now();
    let cases = grid();
    let (mut steps, mut overturned, mut impacts, mut slowest) = (0, 0, 0i64, (0.0, String::new()));
    let mut zero_crossings = 0i64;
    let mut groups = std::collections::BTreeMap::<&str, (usize, usize, usize)>::new();
    for (group, c) in &cases {
        let o = run_watched(*c, 60);
        steps += o.steps;
        impacts += o.impacts as i64;
        zero_crossings += o.zero_crossings as i64;
        overturned += o.overturned as usize;
        let g = groups.entry(group).or_default();
        g.0 += 1;
        g.1 += o.steps;
        g.2 += o.overturned as usize;
        if o.seconds > slowest.0 {
            slowest = (o.seconds, format!("{c:?}"));
        }
    }
    eprintln!(
        "{} runs, {steps} fmi2DoStep calls, {overturned} overturned (fmi2Discard), {impacts} impacts ({zero_crossings} zero crossings), in {:.1} s; slowest run {:.2} s: {}",
        cases.len(),
        started.elapsed().as_secs_f64(),
        slowest.0,
        slowest.1
    );
    for (g, (n, s, ov)) in groups {
        eprintln!("  {g}: {n} runs, {s} steps, {ov} overturned");
    }
}
