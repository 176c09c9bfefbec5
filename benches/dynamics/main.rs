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

mod costs;
mod dharahara;
mod rigid;
mod scipy;
// the physics tests' references: exact rigid rocking, a plain RK4
#[path = "../../tests/support/mod.rs"]
mod support;

use rocking::dynamics::{GroundInput, Method, Simulator, State};
use rocking::model::{LawKind, MassKind, ShapeKind};
use rocking::{Model, Params};
use std::fmt::Write as _;
use std::time::Instant;

use costs::*;
use dharahara::*;
use scipy::*;
use support::exact::Exact;
use support::rk4::{flexible_accel, Rk4};

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

struct Csv(String);

impl Csv {
    fn row(&mut self, case: &str, solver: &str, param: f64, error: f64, seconds: f64, evals: f64) {
        let _ = writeln!(
            self.0,
            "{case},{solver},{param:e},{error:e},{seconds:e},{evals}"
        );
    }
}

/// DOP853 and DP5 on one case at each of `RTOLS`: `run` (timed) gives a
/// simulator's result and its right-hand-side evaluations, `error` scores
/// the result. Prints and writes a row per run; returns DOP853's `(rtol,
/// error, seconds)` for the comparison with SciPy.
fn pair_rows<T>(
    csv: &mut Csv,
    case: &str,
    budget: f64,
    model: Model,
    run: impl Fn(&Simulator) -> (T, u32),
    error: impl Fn(&Simulator, &T) -> f64,
) -> Vec<(f64, f64, f64)> {
    let mut dop853 = Vec::new();
    for method in [Method::Dop853, Method::Dp5] {
        for rtol in RTOLS {
            let sim = Simulator::with_method(model, rtol, method);
            let (got, evals) = run(&sim);
            let err = error(&sim, &got);
            let secs = time_it(budget, || {
                std::hint::black_box(run(&sim));
            });
            let name = format!("{method:?}");
            println!(
                "{name:<10} {rtol:>8.0e} {err:>10.2e} {:>9.1} µs {evals:>8}",
                secs * 1e6
            );
            csv.row(case, &name, rtol, err, secs, evals as f64);
            if method == Method::Dop853 {
                dop853.push((rtol, err, secs));
            }
        }
    }
    dop853
}

/// One row of the RK4 reference: step `h` (s), error, time (s), evaluations.
fn rk4_row(csv: &mut Csv, case: &str, h: f64, err: f64, secs: f64, evals: f64) {
    println!(
        "{:<10} {h:>8.0e} {err:>10.2e} {:>9.1} µs {evals:>8.0}",
        "RK4",
        secs * 1e6
    );
    csv.row(case, "RK4", h, err, secs, evals);
}

const RTOLS: [f64; 9] = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12];

fn main() {
    let mut csv = Csv(String::from("case,solver,param,error,seconds,evals\n"));
    let quick = std::env::var("BENCH_QUICK").is_ok();
    let budget = if quick { 0.05 } else { 0.3 };

    rigid::bench(&mut csv, budget);
    dharahara::bench(&mut csv, budget, quick);
    // (2)
    per_call_costs(budget);

    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/target/bench-dynamics");
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(format!("{dir}/work_precision.csv"), &csv.0).unwrap();
    println!("\nwrote {dir}/work_precision.csv (plot: .venv/bin/python benches/plot_dynamics.py)");
}
