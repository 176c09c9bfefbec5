//! (b) The Dharahara tower (docs/model.md §4) on a crushing interface under a
//! one-cycle sine pulse: first impact, first peak, overturning time.

use super::*;

pub fn dharahara(fm: f64) -> Model {
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

pub const DT: f64 = 0.01;
pub const T_DHARAHARA: f64 = 10.0;

/// The pulse sampled at 100 Hz (the FMU's view of it): samples k = 0..=N.
pub fn pulse_samples(m: &Model, amp_g: f64, n: usize) -> Vec<f64> {
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

pub fn input_at(samples: &[f64], k: usize) -> GroundInput {
    let a0 = samples.get(k).copied().unwrap_or(0.0);
    let a1 = samples.get(k + 1).copied().unwrap_or(0.0);
    GroundInput {
        ag: a0,
        dag: (a1 - a0) / DT,
    }
}

/// One FMU-like run: a call per 100 Hz interval; stops at overturning.
/// Returns the states at the interval ends (and the final one), and the
/// right-hand-side evaluations.
pub fn dharahara_run(sim: &Simulator, samples: &[f64], t_end: f64) -> (Vec<State>, u32) {
    let mut st = sim.initial_state(0.0, 0.0);
    let n = (t_end / DT).round() as usize;
    let mut out = Vec::with_capacity(n + 1);
    let mut evals = 0;
    out.push(st);
    for k in 0..n {
        evals += sim
            .advance(&mut st, (k + 1) as f64 * DT, input_at(samples, k))
            .stats
            .evals;
        out.push(st);
        if st.overturned {
            break;
        }
    }
    (out, evals)
}

/// Quantities of a run: first impact time, first peak |theta|, overturning
/// time. Impacts and peaks are located by re-running intervals from the
/// saved states (State is plain data) with `advance_to_event` and by
/// bisection on `omega`.
pub fn dharahara_quantities(sim: &Simulator, samples: &[f64], states: &[State]) -> [f64; 3] {
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

pub fn quantity_error(q: &[f64; 3], r: &[f64; 3]) -> f64 {
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

pub fn ag_linear(samples: &[f64], t: f64) -> f64 {
    let k = (t / DT) as usize;
    let a0 = samples.get(k).copied().unwrap_or(0.0);
    let a1 = samples.get(k + 1).copied().unwrap_or(0.0);
    a0 + (a1 - a0) * (t / DT - k as f64)
}

/// (b) The Dharahara tower under a one-cycle sine pulse.
pub fn bench(csv: &mut Csv, budget: f64, quick: bool) {
    let md = dharahara(2e6);
    let samples = pulse_samples(&md, 0.16, (T_DHARAHARA / DT) as usize);
    let reference = {
        let sim = Simulator::new(md, 1e-13);
        let (st, _) = dharahara_run(&sim, &samples, T_DHARAHARA);
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
    let ours_dh = pair_rows(
        csv,
        "dharahara",
        budget,
        md,
        |sim| dharahara_run(sim, &samples, T_DHARAHARA),
        |sim, states| {
            let q = dharahara_quantities(sim, &samples, states);
            quantity_error(&q, &reference)
        },
    );
    let acc =
        |t: f64, th: f64, om: f64, s: f64| flexible_accel(&md, ag_linear(&samples, t), th, om, s);
    let hs: &[f64] = if quick {
        &[1e-2, 3e-3]
    } else {
        &[1e-2, 3e-3, 1e-3, 3e-4, 1e-4]
    };
    for &h in hs {
        let rk4 = Rk4 {
            accel: &acc,
            eta: md.eta,
            theta_ov: md.theta_ov,
            h,
            max_impacts: usize::MAX,
        };
        let run = || rk4.run([0.0, 0.0], -1.0, T_DHARAHARA);
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
        rk4_row(csv, "dharahara", h, err, secs, 4.0 * t_run / h);
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
}
