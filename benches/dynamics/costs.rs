//! (2) The cost of a record at 100 Hz, per record and per call, its growth
//! with the record length, and the rest path.

use super::*;

/// A stationary synthetic ground motion: three sines around the body's
/// frequency, ramped in over 0.5 s and out over the last 0.5 s of `[0, len]`.
pub fn synthetic(m: &Model, amp: f64, len: f64) -> impl Fn(f64) -> f64 {
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
pub fn record_run(sim: &Simulator, ag: &dyn Fn(f64) -> f64, record: f64) -> (State, u64) {
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
pub const RIGID_AMP: f64 = 1.05;

pub fn per_call_costs(budget: f64) {
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
