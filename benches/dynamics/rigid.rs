//! (a) Rigid free rocking against the exact solution (impact times and
//! amplitudes of the first 10 impacts).

use super::*;

pub const RIGID_IMPACTS: usize = 10;

/// Relative errors of impact times and amplitudes (amplitude from the
/// post-impact omega) against the exact ones.
pub fn rigid_error(ex: &Exact, exact: &[(f64, f64)], got: &[(f64, f64)]) -> f64 {
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

/// Impact times and post-impact `omega` of the first `RIGID_IMPACTS`
/// impacts, and the right-hand-side evaluations.
pub fn rigid_run(sim: &Simulator, theta0: f64) -> (Vec<(f64, f64)>, u32) {
    let mut st = sim.initial_state(theta0, 0.0);
    let mut out = Vec::with_capacity(RIGID_IMPACTS);
    let mut evals = 0;
    while out.len() < RIGID_IMPACTS {
        let ev = sim.advance_to_event(&mut st, 1e3, GroundInput::default());
        evals += ev.stats.evals;
        if ev.impacts > 0 {
            out.push((st.t, st.omega));
        }
        if st.at_rest || st.t >= 1e3 {
            break;
        }
    }
    (out, evals)
}

/// (a) Rigid free rocking against the exact solution.
pub fn bench(csv: &mut Csv, budget: f64) {
    let m = support::rigid_block(1.0, 4.0);
    let b = m.body;
    let ex = Exact::new(&m);
    let theta0 = 0.8 * b.alpha;
    let exact = ex.impacts(theta0, RIGID_IMPACTS);
    println!(
        "\n(a) Rigid free rocking, 1 m x 4 m block (alpha = {:.4}, eta = {:.4}), released at 0.8 alpha: \
         max relative error of the first {RIGID_IMPACTS} impact times and amplitudes against the exact solution",
        b.alpha, m.eta
    );
    println!(
        "{:<10} {:>8} {:>10} {:>12} {:>8}",
        "solver", "rtol/h", "error", "time", "evals"
    );
    let ours_rigid = pair_rows(
        csv,
        "rigid",
        budget,
        m,
        |sim| rigid_run(sim, theta0),
        |_, got| rigid_error(&ex, &exact, got),
    );
    let rigid_accel = |_t: f64, th: f64, _om: f64, s: f64| {
        let phi = s * th;
        -(s * b.weight * (b.b * phi.cos() - b.hg * phi.sin())) / b.io
    };
    for h in [1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5] {
        let t_end = exact[RIGID_IMPACTS - 1].0 + 0.05;
        let rk4 = Rk4 {
            accel: &rigid_accel,
            eta: m.eta,
            theta_ov: b.alpha,
            h,
            max_impacts: RIGID_IMPACTS,
        };
        let run = || rk4.run([theta0, 0.0], 1.0, t_end);
        let out = run();
        let err = rigid_error(&ex, &exact, &out.impacts);
        let secs = time_it(budget, || {
            std::hint::black_box(run());
        });
        rk4_row(csv, "rigid", h, err, secs, 4.0 * t_end / h);
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
}
