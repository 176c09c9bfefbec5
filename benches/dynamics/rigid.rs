//! (a) Rigid free rocking against the exact solution (impact times and
//! amplitudes of the first 10 impacts).

use super::*;

pub fn rigid_block() -> Model {
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

pub const RIGID_IMPACTS: usize = 10;

pub struct Exact {
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

pub fn rigid_run(sim: &Simulator, theta0: f64) -> Vec<(f64, f64)> {
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

/// (a) Rigid free rocking against the exact solution.
pub fn bench(csv: &mut Csv, budget: f64) {
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
}
