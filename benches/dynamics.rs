//! Benchmark of the rocking dynamics (`cargo bench -p rocking --bench dynamics`).
//!
//! Prints tables, and writes `target/bench-dynamics/work_precision.csv` for
//! `benches/plot_dynamics.py` (the figure in docs/dynamics.md):
//!
//! 1. work-precision (wall time against error, rtol 1e-4..1e-12) of DOP853
//!    and DP5 (this crate), a plain fixed-step RK4 written here, and SciPy's
//!    `solve_ivp` DOP853 (`benches/scipy_reference.py`, an independent
//!    implementation, spawned through `.venv/bin/python`; skipped if absent
//!    or with `BENCH_NO_SCIPY=1`) on
//!    (a) rigid free rocking against the exact solution (impact times and
//!    amplitudes of the first 10 impacts);
//!    (b) the Dharahara tower (docs/model.md §4) on a crushing interface under a
//!    one-cycle sine pulse (0.16 g, 4.5 s, sampled at 100 Hz): time of the
//!    first impact, first peak, overturning time;
//! 2. the cost of a 60 s record at 100 Hz (per record and per call), its
//!    growth with the record length, and the rest path.

use rocking::dynamics::{GroundInput, Method, Simulator, State};
use rocking::model::{LawKind, MassKind, ShapeKind};
use rocking::{Model, Params};
use std::fmt::Write as _;
use std::time::Instant;

// ---------------------------------------------------------------- helpers

/// Minimum wall time of `f` over repetitions filling about `budget` s.
fn time_it(budget: f64, mut f: impl FnMut()) -> f64 {
    let mut best = f64::INFINITY;
    let start = Instant::now();
    let mut n = 0;
    while n < 3 || (start.elapsed().as_secs_f64() < budget && n < 10_000) {
        let t0 = Instant::now();
        f();
        best = best.min(t0.elapsed().as_secs_f64());
        n += 1;
    }
    best
}

fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 0.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let dx = p1 / dp;
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            (x, 2.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}

fn quad(f: &dyn Fn(f64) -> f64, p: f64, q: f64) -> f64 {
    let rule = gauss_legendre(30);
    let mut prev = f64::NAN;
    let mut panels = 1;
    loop {
        let h = (q - p) / panels as f64;
        let mut sum = 0.0;
        for k in 0..panels {
            let a = p + k as f64 * h;
            for &(x, w) in &rule {
                sum += 0.5 * h * w * f(a + 0.5 * h * (1.0 + x));
            }
        }
        if (sum - prev).abs() <= 1e-15 * sum.abs() || panels > 1 << 12 {
            return sum;
        }
        prev = sum;
        panels *= 2;
    }
}

/// A fixed-step classical RK4 on `(theta, omega)` with `accel(t, theta,
/// omega, side)`, impacts at `theta = 0` (`omega <- eta omega`), peaks and
/// overturning located by bisection on the step length. Stops at `t_end`
/// or overturning. The input is supplied as `accel`'s `t`.
struct Rk4Out {
    impacts: Vec<(f64, f64)>,
    peaks: Vec<f64>,
    overturn: Option<f64>,
}

#[allow(clippy::too_many_arguments)]
fn rk4(
    accel: &dyn Fn(f64, f64, f64, f64) -> f64,
    y0: [f64; 2],
    side0: f64,
    eta: f64,
    theta_ov: f64,
    h: f64,
    t_end: f64,
    max_impacts: usize,
) -> Rk4Out {
    let step = |t: f64, y: [f64; 2], dt: f64, s: f64| {
        let f = |t: f64, y: [f64; 2]| [y[1], accel(t, y[0], y[1], s)];
        let k1 = f(t, y);
        let k2 = f(
            t + dt / 2.0,
            [y[0] + dt / 2.0 * k1[0], y[1] + dt / 2.0 * k1[1]],
        );
        let k3 = f(
            t + dt / 2.0,
            [y[0] + dt / 2.0 * k2[0], y[1] + dt / 2.0 * k2[1]],
        );
        let k4 = f(t + dt, [y[0] + dt * k3[0], y[1] + dt * k3[1]]);
        [
            y[0] + dt / 6.0 * (k1[0] + 2.0 * k2[0] + 2.0 * k3[0] + k4[0]),
            y[1] + dt / 6.0 * (k1[1] + 2.0 * k2[1] + 2.0 * k3[1] + k4[1]),
        ]
    };
    // bisection on the step length for a sign change of g(y(dt))
    let bisect = |t: f64, y: [f64; 2], dt: f64, s: f64, g: &dyn Fn([f64; 2]) -> f64| {
        let g0 = g(y);
        let (mut lo, mut hi) = (0.0, dt);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if g(step(t, y, mid, s)) * g0 > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        hi
    };
    let mut out = Rk4Out {
        impacts: Vec::new(),
        peaks: Vec::new(),
        overturn: None,
    };
    let (mut t, mut y, mut side) = (0.0, y0, side0);
    let n = (t_end / h).round() as usize;
    for k in 0..n {
        let t_next = (k + 1) as f64 * h;
        while t < t_next {
            let dt = t_next - t;
            let y1 = step(t, y, dt, side);
            // the first of: overturning, impact, peak
            if side * y1[0] >= theta_ov {
                let d = bisect(t, y, dt, side, &|z| side * z[0] - theta_ov);
                out.overturn = Some(t + d);
                return out;
            }
            if y[0] != 0.0 && side * y1[0] < 0.0 {
                let d = bisect(t, y, dt, side, &|z| z[0]);
                let yc = step(t, y, d, side);
                if y[1] * yc[1] < 0.0 || (side * y[1] > 0.0) {
                    // a peak before the impact
                    let dp = bisect(t, y, d, side, &|z| z[1]);
                    out.peaks.push(step(t, y, dp, side)[0].abs());
                }
                t += d;
                y = [0.0, eta * yc[1]];
                side = -side;
                out.impacts.push((t, y[1]));
                if out.impacts.len() >= max_impacts {
                    return out;
                }
                continue;
            }
            if y[1] * y1[1] < 0.0 {
                let dp = bisect(t, y, dt, side, &|z| z[1]);
                out.peaks.push(step(t, y, dp, side)[0].abs());
            }
            y = y1;
            t = t_next;
        }
    }
    out
}

// ------------------------------------------------------- (a) rigid block

fn rigid_block() -> Model {
    Params {
        shape: ShapeKind::SolidRectangle,
        b: 1.0,
        l: 1.0,
        mass_model: MassKind::Prism,
        h: 4.0,
        rho: 2000.0,
        interface: LawKind::Rigid,
        ..Params::default()
    }
    .build()
    .unwrap()
}

const RIGID_IMPACTS: usize = 10;

struct Exact {
    w_r0: f64,
    io: f64,
    alpha: f64,
}

impl Exact {
    fn v(&self, phi: f64) -> f64 {
        2.0 * self.w_r0 * (0.5 * phi).sin() * (self.alpha - 0.5 * phi).sin()
    }
    fn amplitude(&self, e: f64) -> f64 {
        let mut phi = e / (self.w_r0 * self.alpha.sin());
        for _ in 0..100 {
            let d = (self.v(phi) - e) / (self.w_r0 * (self.alpha - phi).sin());
            phi -= d;
            if d.abs() <= 1e-17 * phi {
                break;
            }
        }
        phi
    }
    fn fall_time(&self, phi: f64) -> f64 {
        let f = |u: f64| {
            let v = std::f64::consts::FRAC_PI_4 - 0.5 * u;
            let psi = phi * u.sin();
            let x = phi * v.sin().powi(2);
            let sinc = if x.abs() < 1e-4 {
                1.0 - x * x / 6.0
            } else {
                x.sin() / x
            };
            let dv = 2.0 * self.w_r0 * (self.alpha - 0.5 * (phi + psi)).sin() * phi * sinc;
            phi * 2.0 * v.cos() / (2.0 * dv / self.io).sqrt()
        };
        quad(&f, 0.0, std::f64::consts::FRAC_PI_2)
    }
}

/// Relative errors of impact times and amplitudes (amplitude from the
/// post-impact omega) against the exact ones.
fn rigid_error(ex: &Exact, exact: &[(f64, f64)], got: &[(f64, f64)]) -> f64 {
    if got.len() < exact.len() {
        return f64::INFINITY;
    }
    exact
        .iter()
        .zip(got)
        .map(|(&(te, pe), &(tg, wg))| {
            let pg = ex.amplitude(0.5 * ex.io * wg * wg);
            ((tg - te).abs() / te).max((pg - pe).abs() / pe)
        })
        .fold(0.0, f64::max)
}

fn rigid_run(sim: &Simulator, theta0: f64) -> Vec<(f64, f64)> {
    let mut st = sim.initial_state(theta0, 0.0);
    let mut out = Vec::with_capacity(RIGID_IMPACTS);
    while out.len() < RIGID_IMPACTS {
        let ev = sim.advance_to_event(&mut st, 1e3, GroundInput::default());
        if ev.impacts > 0 {
            out.push((st.t, st.omega));
        }
        if st.at_rest || st.t >= 1e3 {
            break;
        }
    }
    out
}

// ---------------------------------------------------- (b) the Dharahara

fn dharahara(fm: f64) -> Model {
    let (ro, ri, w, hg, g) = (3.99, 2.12, 24003.94e3, 30.20, 9.81);
    let m = w / g;
    let h = 2.0 * hg;
    Params {
        shape: ShapeKind::HollowCircle,
        ro,
        ri,
        mass_model: MassKind::Lumped,
        w,
        hg,
        ic: m * (h * h / 12.0 + (ro * ro + ri * ri) / 4.0),
        interface: if fm.is_finite() {
            LawKind::ElastoPlastic
        } else {
            LawKind::Elastic
        },
        kn: 2e9,
        fm,
        g,
        ..Params::default()
    }
    .build()
    .unwrap()
}

const DT: f64 = 0.01;
const T_DHARAHARA: f64 = 10.0;

/// The pulse sampled at 100 Hz (the FMU's view of it): samples k = 0..=N.
fn pulse_samples(m: &Model, amp_g: f64, n: usize) -> Vec<f64> {
    (0..=n)
        .map(|k| {
            let t = k as f64 * DT;
            if t < 4.5 {
                amp_g * m.body.g * (2.0 * std::f64::consts::PI * t / 4.5).sin()
            } else {
                0.0
            }
        })
        .collect()
}

fn input_at(samples: &[f64], k: usize) -> GroundInput {
    let a0 = samples.get(k).copied().unwrap_or(0.0);
    let a1 = samples.get(k + 1).copied().unwrap_or(0.0);
    GroundInput {
        ag: a0,
        dag: (a1 - a0) / DT,
    }
}

/// One FMU-like run: a call per 100 Hz interval; stops at overturning.
/// Returns the states at the interval ends (and the final one).
fn dharahara_run(sim: &Simulator, samples: &[f64], t_end: f64) -> Vec<State> {
    let mut st = sim.initial_state(0.0, 0.0);
    let n = (t_end / DT).round() as usize;
    let mut out = Vec::with_capacity(n + 1);
    out.push(st);
    for k in 0..n {
        sim.advance(&mut st, (k + 1) as f64 * DT, input_at(samples, k));
        out.push(st);
        if st.overturned {
            break;
        }
    }
    out
}

/// Quantities of a run: first impact time, first peak |theta|, overturning
/// time. Impacts and peaks are located by re-running intervals from the
/// saved states (State is plain data) with `advance_to_event` and by
/// bisection on `omega`.
fn dharahara_quantities(sim: &Simulator, samples: &[f64], states: &[State]) -> [f64; 3] {
    let mut first_impact = f64::NAN;
    let mut first_peak = f64::NAN;
    for (k, w) in states.windows(2).enumerate() {
        let (a, b) = (w[0], w[1]);
        let t1 = (k + 1) as f64 * DT;
        // the first zero crossing (advance_to_event stops at every one)
        if first_impact.is_nan() && b.zero_crossings > a.zero_crossings {
            let mut s = a;
            sim.advance_to_event(&mut s, t1, input_at(samples, k));
            first_impact = s.t;
        }
        if first_peak.is_nan()
            && a.omega != 0.0
            && a.omega * b.omega < 0.0
            && b.zero_crossings == a.zero_crossings
        {
            // bisection on the time where omega changes sign
            let (mut lo, mut hi) = (a.t, t1);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                let mut s = a;
                sim.advance(&mut s, mid, input_at(samples, k));
                if s.omega * a.omega > 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let mut s = a;
            sim.advance(&mut s, 0.5 * (lo + hi), input_at(samples, k));
            first_peak = s.theta.abs();
        }
    }
    let last = states.last().unwrap();
    let overturn = if last.overturned { last.t } else { f64::NAN };
    [first_impact, first_peak, overturn]
}

fn quantity_error(q: &[f64; 3], r: &[f64; 3]) -> f64 {
    q.iter()
        .zip(r)
        .map(|(a, b)| {
            if a.is_nan() && b.is_nan() {
                0.0
            } else {
                ((a - b) / b).abs()
            }
        })
        .fold(
            0.0,
            |m: f64, e| if e.is_nan() { f64::INFINITY } else { m.max(e) },
        )
}

/// `theta''` of docs/model.md §3 for the RK4 reference (contact and levers from
/// the model).
fn flexible_accel(m: &Model, ag: f64, theta: f64, omega: f64, side: f64) -> f64 {
    let s = if theta != 0.0 { theta.signum() } else { side };
    let phi = theta.abs();
    let c = m.interface.contact(phi);
    let l = m.levers(phi, &c);
    let b = &m.body;
    (-s * b.weight * l.hw - b.mass * ag * l.hg - 0.5 * s * l.dinertia * omega * omega) / l.inertia
}

fn ag_linear(samples: &[f64], t: f64) -> f64 {
    let k = (t / DT) as usize;
    let a0 = samples.get(k).copied().unwrap_or(0.0);
    let a1 = samples.get(k + 1).copied().unwrap_or(0.0);
    a0 + (a1 - a0) * (t / DT - k as f64)
}

// ------------------------------------------------------------- SciPy

fn scipy(request: &str) -> Option<serde_json::Value> {
    if std::env::var("BENCH_NO_SCIPY").is_ok() {
        return None;
    }
    let py = concat!(env!("CARGO_MANIFEST_DIR"), "/.venv/bin/python");
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/benches/scipy_reference.py");
    if !std::path::Path::new(py).exists() {
        eprintln!("(no {py}: run tools/venv.sh for the SciPy comparison)");
        return None;
    }
    let out = std::process::Command::new(py)
        .arg(script)
        .arg(request)
        .output()
        .ok()?;
    if !out.status.success() {
        eprintln!(
            "scipy_reference.py failed: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        return None;
    }
    match serde_json::from_slice(&out.stdout) {
        Ok(v) => Some(v),
        Err(e) => {
            eprintln!("scipy_reference.py printed no valid JSON: {e}");
            None
        }
    }
}

/// Reading SciPy's answer: a number (`null`, for a quantity SciPy did not
/// reach, reads as NaN) and an array (empty if absent).
trait Json {
    fn num(&self) -> f64;
    fn arr(&self) -> &[serde_json::Value];
}

impl Json for serde_json::Value {
    fn num(&self) -> f64 {
        self.as_f64().unwrap_or(f64::NAN)
    }
    fn arr(&self) -> &[serde_json::Value] {
        self.as_array().map_or(&[], |v| v.as_slice())
    }
}

fn json_list(xs: &[f64]) -> String {
    let v: Vec<String> = xs.iter().map(|x| format!("{x:e}")).collect();
    format!("[{}]", v.join(","))
}

// --------------------------------------------------------------- main

struct Csv(String);

impl Csv {
    fn row(&mut self, case: &str, solver: &str, param: f64, error: f64, seconds: f64, evals: f64) {
        let _ = writeln!(
            self.0,
            "{case},{solver},{param:e},{error:e},{seconds:e},{evals}"
        );
    }
}

const RTOLS: [f64; 9] = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12];

fn main() {
    let mut csv = Csv(String::from("case,solver,param,error,seconds,evals\n"));
    let quick = std::env::var("BENCH_QUICK").is_ok();
    let budget = if quick { 0.05 } else { 0.3 };

    // ---------------------------------------------------------- (a)
    let m = rigid_block();
    let b = m.body;
    let ex = Exact {
        w_r0: b.weight * b.r0,
        io: b.io,
        alpha: b.alpha,
    };
    let theta0 = 0.8 * b.alpha;
    let exact: Vec<(f64, f64)> = {
        let mut e = ex.v(theta0);
        let mut t = ex.fall_time(theta0);
        (0..RIGID_IMPACTS)
            .map(|_| {
                e *= m.eta * m.eta;
                let phi = ex.amplitude(e);
                let r = (t, phi);
                t += 2.0 * ex.fall_time(phi);
                r
            })
            .collect()
    };
    println!(
        "\n(a) Rigid free rocking, 1 m x 4 m block (alpha = {:.4}, eta = {:.4}), released at 0.8 alpha: \
         max relative error of the first {RIGID_IMPACTS} impact times and amplitudes against the exact solution",
        b.alpha, m.eta
    );
    println!(
        "{:<10} {:>8} {:>10} {:>12} {:>8}",
        "solver", "rtol/h", "error", "time", "evals"
    );
    let mut ours_rigid = Vec::new();
    for method in [Method::Dop853, Method::Dp5] {
        for rtol in RTOLS {
            let sim = Simulator::with_method(m, rtol, method);
            let got = rigid_run(&sim, theta0);
            let err = rigid_error(&ex, &exact, &got);
            let secs = time_it(budget, || {
                std::hint::black_box(rigid_run(&sim, theta0));
            });
            let evals = {
                let mut st = sim.initial_state(theta0, 0.0);
                let mut n = 0;
                let mut k = 0;
                while k < RIGID_IMPACTS {
                    let ev = sim.advance_to_event(&mut st, 1e3, GroundInput::default());
                    n += ev.stats.evals;
                    k += ev.impacts as usize;
                }
                n
            };
            let name = format!("{method:?}");
            println!(
                "{name:<10} {rtol:>8.0e} {err:>10.2e} {:>9.1} µs {evals:>8}",
                secs * 1e6
            );
            csv.row("rigid", &name, rtol, err, secs, evals as f64);
            if method == Method::Dop853 {
                ours_rigid.push((rtol, err, secs));
            }
        }
    }
    let rigid_accel = |_t: f64, th: f64, _om: f64, s: f64| {
        let phi = s * th;
        -(s * b.weight * (b.b * phi.cos() - b.hg * phi.sin())) / b.io
    };
    for h in [1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5] {
        let t_end = exact[RIGID_IMPACTS - 1].0 + 0.05;
        let run = || {
            rk4(
                &rigid_accel,
                [theta0, 0.0],
                1.0,
                m.eta,
                b.alpha,
                h,
                t_end,
                RIGID_IMPACTS,
            )
        };
        let out = run();
        let err = rigid_error(&ex, &exact, &out.impacts);
        let secs = time_it(budget, || {
            std::hint::black_box(run());
        });
        let evals = 4.0 * t_end / h;
        println!(
            "{:<10} {h:>8.0e} {err:>10.2e} {:>9.1} µs {evals:>8.0}",
            "RK4",
            secs * 1e6
        );
        csv.row("rigid", "RK4", h, err, secs, evals);
    }
    let req = format!(
        r#"{{"case":"rigid","repeat":3,"rtols":{},"params":{{"W":{:e},"R0":{:e},"alpha":{:e},"IO":{:e},"eta":{:e},"theta0":{:e},"impacts":{RIGID_IMPACTS}}}}}"#,
        json_list(&RTOLS),
        b.weight,
        b.r0,
        b.alpha,
        b.io,
        m.eta,
        theta0
    );
    let mut scipy_rigid = Vec::new();
    if let Some(v) = scipy(&req) {
        for r in v.arr() {
            let rtol = r.get("rtol").unwrap().num();
            let times = r.get("impact_times").unwrap().arr();
            let omegas = r.get("impact_omegas").unwrap().arr();
            let got: Vec<(f64, f64)> = times
                .iter()
                .zip(omegas)
                .map(|(t, w)| (t.num(), w.num()))
                .collect();
            let err = rigid_error(&ex, &exact, &got);
            let secs = r.get("seconds").unwrap().num();
            println!(
                "{:<10} {rtol:>8.0e} {err:>10.2e} {:>9.1} µs",
                "SciPy",
                secs * 1e6
            );
            csv.row("rigid", "SciPy", rtol, err, secs, f64::NAN);
            scipy_rigid.push((rtol, err, secs));
        }
        speedups("rigid", &ours_rigid, &scipy_rigid);
    }

    // ---------------------------------------------------------- (b)
    let md = dharahara(2e6);
    let samples = pulse_samples(&md, 0.16, (T_DHARAHARA / DT) as usize);
    let reference = {
        let sim = Simulator::new(md, 1e-13);
        let st = dharahara_run(&sim, &samples, T_DHARAHARA);
        dharahara_quantities(&sim, &samples, &st)
    };
    println!(
        "\n(b) Dharahara (hollow circle Ro 3.99 m, Ri 2.12 m, W 24003.94 kN, hG 30.20 m, kn 2 GPa/m, fm 2 MPa; \
         alpha = {:.4}, thetaOv = {:.5}) under a one-cycle sine pulse, 0.16 g, 4.5 s, 100 Hz samples:\n\
         reference (DOP853, rtol 1e-13): first impact at {:.9} s, first peak {:.9e} rad, overturning at {:.9} s.\n\
         Error: max relative error of these three.",
        md.body.alpha, md.theta_ov, reference[0], reference[1], reference[2]
    );
    println!(
        "{:<10} {:>8} {:>10} {:>12} {:>8}",
        "solver", "rtol/h", "error", "time", "evals"
    );
    let mut ours_dh = Vec::new();
    for method in [Method::Dop853, Method::Dp5] {
        for rtol in RTOLS {
            let sim = Simulator::with_method(md, rtol, method);
            let st = dharahara_run(&sim, &samples, T_DHARAHARA);
            let q = dharahara_quantities(&sim, &samples, &st);
            let err = quantity_error(&q, &reference);
            let secs = time_it(budget, || {
                std::hint::black_box(dharahara_run(&sim, &samples, T_DHARAHARA));
            });
            let evals: u32 = {
                let mut s = sim.initial_state(0.0, 0.0);
                let mut n = 0;
                for k in 0..(T_DHARAHARA / DT) as usize {
                    n += sim
                        .advance(&mut s, (k + 1) as f64 * DT, input_at(&samples, k))
                        .stats
                        .evals;
                    if s.overturned {
                        break;
                    }
                }
                n
            };
            let name = format!("{method:?}");
            println!(
                "{name:<10} {rtol:>8.0e} {err:>10.2e} {:>9.1} µs {evals:>8}",
                secs * 1e6
            );
            csv.row("dharahara", &name, rtol, err, secs, evals as f64);
            if method == Method::Dop853 {
                ours_dh.push((rtol, err, secs));
            }
        }
    }
    let acc =
        |t: f64, th: f64, om: f64, s: f64| flexible_accel(&md, ag_linear(&samples, t), th, om, s);
    let hs: &[f64] = if quick {
        &[1e-2, 3e-3]
    } else {
        &[1e-2, 3e-3, 1e-3, 3e-4, 1e-4]
    };
    for &h in hs {
        let run = || {
            rk4(
                &acc,
                [0.0, 0.0],
                -1.0,
                md.eta,
                md.theta_ov,
                h,
                T_DHARAHARA,
                usize::MAX,
            )
        };
        let out = run();
        let q = [
            out.impacts.first().map_or(f64::NAN, |x| x.0),
            out.peaks.first().copied().unwrap_or(f64::NAN),
            out.overturn.unwrap_or(f64::NAN),
        ];
        let err = quantity_error(&q, &reference);
        let secs = time_it(budget.min(0.1), || {
            std::hint::black_box(run());
        });
        let t_run = out.overturn.unwrap_or(T_DHARAHARA);
        let evals = 4.0 * t_run / h;
        println!(
            "{:<10} {h:>8.0e} {err:>10.2e} {:>9.1} µs {evals:>8.0}",
            "RK4",
            secs * 1e6
        );
        csv.row("dharahara", "RK4", h, err, secs, evals);
    }
    let b = md.body;
    let scipy_rtols: &[f64] = if quick { &[1e-6] } else { &[1e-4, 1e-6, 1e-8] };
    let req = format!(
        r#"{{"case":"flexible","rtols":{},"params":{{"ro":3.99,"ri":2.12,"W":{:e},"hG":{:e},"Ic":{:e},"g":{:e},"eta":{:e},"kn":2e9,"fm":2e6,"dt":{DT:e},"ag":{},"t_end":{T_DHARAHARA:e}}}}}"#,
        json_list(scipy_rtols),
        b.weight,
        b.hg,
        b.ic,
        b.g,
        md.eta,
        json_list(&samples)
    );
    let mut scipy_dh = Vec::new();
    if let Some(v) = scipy(&req) {
        for r in v.arr() {
            let rtol = r.get("rtol").unwrap().num();
            let q = [
                r.get("impact_times")
                    .unwrap()
                    .arr()
                    .first()
                    .map_or(f64::NAN, |x| x.num()),
                r.get("peaks")
                    .unwrap()
                    .arr()
                    .first()
                    .map_or(f64::NAN, |x| x.num()),
                r.get("overturn").map_or(f64::NAN, |x| x.num()),
            ];
            let err = quantity_error(&q, &reference);
            let secs = r.get("seconds").unwrap().num();
            println!(
                "{:<10} {rtol:>8.0e} {err:>10.2e} {:>9.1} ms   (thetaOv here {:.16e})",
                "SciPy",
                secs * 1e3,
                r.get("theta_ov").unwrap().num()
            );
            csv.row("dharahara", "SciPy", rtol, err, secs, f64::NAN);
            scipy_dh.push((rtol, err, secs));
        }
        speedups("dharahara", &ours_dh, &scipy_dh);
    }

    // ---------------------------------------------------------- (2)
    per_call_costs(budget);

    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/target/bench-dynamics");
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(format!("{dir}/work_precision.csv"), &csv.0).unwrap();
    println!("\nwrote {dir}/work_precision.csv (plot: .venv/bin/python benches/plot_dynamics.py)");
}

/// Time of ours against SciPy: at the same rtol, and at equal error
/// (ours interpolated in log-log at SciPy's error).
fn speedups(case: &str, ours: &[(f64, f64, f64)], theirs: &[(f64, f64, f64)]) {
    println!("{case}: speed-up over SciPy DOP853");
    for &(rtol, err, secs) in theirs {
        let same = ours.iter().find(|o| o.0 == rtol).map(|o| secs / o.2);
        // ours at equal error: log-linear interpolation of time vs error
        let mut at_err = None;
        for w in ours.windows(2) {
            let (e0, e1) = (w[0].1, w[1].1);
            if (e0 - err) * (e1 - err) <= 0.0 && e0 > 0.0 && e1 > 0.0 && e0 != e1 {
                let f = (err.ln() - e0.ln()) / (e1.ln() - e0.ln());
                let t = (w[0].2.ln() + f * (w[1].2.ln() - w[0].2.ln())).exp();
                at_err = Some(secs / t);
            }
        }
        println!(
            "  rtol {rtol:.0e}: SciPy error {err:.2e} in {:.3} ms; same rtol: {}; equal error: {}",
            secs * 1e3,
            same.map_or("-".into(), |x| format!("{x:.0}x")),
            at_err.map_or("(outside our range)".into(), |x| format!("{x:.0}x"))
        );
    }
}

/// A stationary synthetic ground motion: three sines around the body's
/// frequency, ramped in over 0.5 s and out over the last 0.5 s of `[0, len]`.
fn synthetic(m: &Model, amp: f64, len: f64) -> impl Fn(f64) -> f64 {
    let p = (m.body.weight * m.body.r0 / m.body.io).sqrt();
    let a = -amp * m.body.g * m.body.alpha.tan();
    move |t: f64| {
        if t >= len || t <= 0.0 {
            return 0.0;
        }
        let ramp = (t / 0.5).min(1.0).min((len - t) / 0.5).max(0.0);
        let x = p * t;
        a * ramp
            * (0.6 * (0.7 * x).sin() + 0.3 * (1.9 * x + 1.0).sin() + 0.2 * (4.3 * x + 2.0).sin())
    }
}

/// `record` s at 100 Hz with ground motion `ag`; returns (state, evals).
fn record_run(sim: &Simulator, ag: &dyn Fn(f64) -> f64, record: f64) -> (State, u64) {
    let mut st = sim.initial_state(0.0, 0.0);
    let n = (record / DT).round() as usize;
    let mut evals = 0u64;
    let mut a0 = ag(0.0);
    for k in 0..n {
        let t1 = (k + 1) as f64 * DT;
        let a1 = ag(t1);
        let ev = sim.advance(
            &mut st,
            t1,
            GroundInput {
                ag: a0,
                dag: (a1 - a0) / DT,
            },
        );
        evals += ev.stats.evals as u64;
        a0 = a1;
        if st.overturned {
            break;
        }
    }
    (st, evals)
}

/// Peak of the synthetic record for the rigid block, over g tan(alpha):
/// it rocks for the whole record without overturning.
const RIGID_AMP: f64 = 1.05;

fn per_call_costs(budget: f64) {
    println!("\n(2) Cost of a record at 100 Hz, one advance per sample (default rtol 1e-9)");
    println!(
        "{:<46} {:<7} {:>10} {:>10} {:>9} {:>9} {:>8}",
        "case", "method", "record", "per call", "evals", "impacts", "end"
    );
    let rigid = Params {
        interface: LawKind::Rigid,
        ..Params::default()
    }
    .build()
    .unwrap();
    let dh = dharahara(2e6);
    let dh_pulse = pulse_samples(&dh, 0.16, 6000);
    let dh_ag = move |t: f64| ag_linear(&dh_pulse, t);
    let dh_elastic = dharahara(f64::INFINITY);
    type Record = Box<dyn Fn(f64) -> f64>;
    let cases: Vec<(&str, Model, Record)> = vec![
        (
            "rigid block, synthetic 0.8 g tan(alpha)",
            rigid,
            Box::new(synthetic(&rigid, 0.8, 60.0)),
        ),
        (
            "rigid block, synthetic 1.05 g tan(alpha)",
            rigid,
            Box::new(synthetic(&rigid, RIGID_AMP, 60.0)),
        ),
        (
            "rigid block, synthetic 1.2 g tan(alpha)",
            rigid,
            Box::new(synthetic(&rigid, 1.2, 60.0)),
        ),
        (
            "Dharahara fm 2 MPa, 0.16 g pulse (60 s)",
            dh,
            Box::new(dh_ag),
        ),
        (
            "Dharahara no crushing, 60 s synthetic record",
            dh_elastic,
            Box::new(synthetic(&dh_elastic, 0.9, 60.0)),
        ),
    ];
    for (name, m, ag) in &cases {
        for method in [Method::Dop853, Method::Dp5] {
            let sim = Simulator::with_method(*m, 1e-9, method);
            let (st, evals) = record_run(&sim, ag.as_ref(), 60.0);
            let secs = time_it(budget, || {
                std::hint::black_box(record_run(&sim, ag.as_ref(), 60.0));
            });
            let calls = (st.t / DT).round().max(1.0);
            println!(
                "{name:<46} {:<7} {:>7.3} ms {:>7.0} ns {evals:>9} {:>9} {:>8}",
                format!("{method:?}"),
                secs * 1e3,
                secs / calls * 1e9,
                st.impacts,
                if st.overturned {
                    format!("ov {:.2}", st.t)
                } else if st.at_rest {
                    "rest".into()
                } else {
                    "moving".into()
                }
            );
        }
    }

    println!("\nGrowth with the record length (rigid block, stationary synthetic motion, DOP853)");
    println!(
        "{:>8} {:>10} {:>14} {:>9}",
        "record", "time", "per second", "impacts"
    );
    for len in [60.0, 120.0, 240.0, 480.0, 960.0] {
        let sim = Simulator::new(rigid, 1e-9);
        let ag = synthetic(&rigid, RIGID_AMP, len);
        let (st, _) = record_run(&sim, &ag, len);
        let secs = time_it(budget, || {
            std::hint::black_box(record_run(&sim, &ag, len));
        });
        println!(
            "{len:>6} s {:>7.2} ms {:>9.1} µs/s {:>9}{}",
            secs * 1e3,
            secs / len * 1e6,
            st.impacts,
            if st.overturned { " (overturned)" } else { "" }
        );
    }

    println!("\nRest path (rigid block, 60 s at 100 Hz, DOP853)");
    let sim = Simulator::new(rigid, 1e-9);
    let active = synthetic(&rigid, RIGID_AMP, 60.0);
    // 6 s of the same motion, taken where it rocks the block, then quiet
    let window = |shift: f64| {
        let a = synthetic(&rigid, RIGID_AMP, 120.0);
        move |t: f64| if t < 6.0 { a(t + shift) } else { 0.0 }
    };
    let shift = (0..60)
        .map(|k| k as f64)
        .find(|&s| {
            let (st, _) = record_run(&sim, &window(s), 60.0);
            st.impacts > 10 && !st.overturned
        })
        .unwrap_or(0.0);
    let quiet = window(shift);
    let (sa, ea) = record_run(&sim, &active, 60.0);
    let (sq, eq) = record_run(&sim, &quiet, 60.0);
    let ta = time_it(budget, || {
        std::hint::black_box(record_run(&sim, &active, 60.0));
    });
    let tq = time_it(budget, || {
        std::hint::black_box(record_run(&sim, &quiet, 60.0));
    });
    // the quiet part alone: a body at rest, 5400 calls
    let rest = sim.initial_state(0.0, 0.0);
    let calls = 5400;
    let t_rest = time_it(budget, || {
        let mut s = rest;
        for k in 0..calls {
            sim.advance(&mut s, (k + 1) as f64 * DT, GroundInput::default());
        }
        std::hint::black_box(s);
    });
    println!(
        "  moving for 60 s: {:.3} ms ({} evals, {} impacts, {})",
        ta * 1e3,
        ea,
        sa.impacts,
        if sa.overturned {
            "overturned"
        } else {
            "no overturning"
        }
    );
    println!(
        "  moving for 6 s (the same motion from {shift} s), quiet for 54 s: {:.3} ms ({} evals, {} impacts, at rest at the end: {})",
        tq * 1e3,
        eq,
        sq.impacts,
        sq.at_rest
    );
    println!(
        "  ratio {:.1}x; a call at rest costs {:.1} ns",
        ta / tq,
        t_rest / calls as f64 * 1e9
    );
}
