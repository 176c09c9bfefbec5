//! The cost of the vertical input (docs/performance.md): the same runs with
//! `av = 0` and with a vertical component, CPU time (the best of several
//! repetitions, interleaved) and integrator steps.
//!
//! ```sh
//! cargo run --release --example vertical_cost
//! VERTICAL_COST_ONLY=tower,av cargo run --release --example vertical_cost
//! ```
//!
//! Cases: the default 0.5 m x 1 m x 2.5 m block on each interface law
//! under 20 s of a synthetic record at 100 Hz (0.5 g at most horizontally,
//! a decaying sum of sines), and under the same with a vertical component
//! of 0.6 times its amplitude at other frequencies; and the Dharahara tower
//! on its F170_fm5 foundation under the same at 0.3 g and 0.3 times the
//! frequencies, whose bed crushes (to 1.45 thetaC).
//!
//! `VERTICAL_COST_ONLY=CASE,av` (or `,av0`; CASE a prefix of a case's
//! name) runs that case once and prints its steps and a checksum of the
//! states at every communication point: for instruction counts
//! (`valgrind --tool=callgrind`, the run's own share is the count less the
//! one of `VERTICAL_COST_ONLY=none`) and to compare two builds bit for bit.

use rocking::dynamics::{GroundInput, Simulator, VerticalInput};
use rocking::model::LawKind;
use rocking::Params;

#[path = "support/cpu.rs"]
mod cpu;
#[path = "support/dharahara.rs"]
mod dharahara;

use cpu::cpu;

const DT: f64 = 0.01;
const N: usize = 2000;
const G: f64 = 9.81;

fn record(amp: f64, freqs: [f64; 3]) -> Vec<f64> {
    (0..=N)
        .map(|k| {
            let t = k as f64 * DT;
            let env = (t / 2.0).min(1.0) * (-(t - 2.0).max(0.0) / 8.0).exp();
            amp * env
                * freqs
                    .iter()
                    .map(|f| (std::f64::consts::TAU * f * t).sin())
                    .sum::<f64>()
                / 3.0
        })
        .collect()
}

/// One run: integrator steps and a checksum of the states at the
/// communication points (their bits).
fn run(sim: &Simulator, ag: &[f64], av: &[f64]) -> (u64, u64) {
    let mut st = sim.initial_state(0.0, 0.0);
    let mut steps = 0;
    let mut sum = 0u64;
    for k in 0..N {
        let input = GroundInput {
            ag: ag[k],
            dag: (ag[k + 1] - ag[k]) / DT,
        };
        let v = VerticalInput {
            av: av[k],
            dav: (av[k + 1] - av[k]) / DT,
        };
        let ev = sim.advance_vertical(&mut st, (k + 1) as f64 * DT, input, v);
        steps += ev.stats.steps as u64 + ev.stats.rejected as u64;
        for x in [st.t, st.theta, st.omega] {
            sum = sum.rotate_left(7) ^ x.to_bits();
        }
        if st.overturned || ev.terminal.is_some() {
            break;
        }
    }
    (steps, sum)
}

/// The Dharahara tower of docs/dharahara.md on its F170_fm5 foundation
/// (kn = 170 MPa/m, fm = 5 MPa).
fn tower() -> Params {
    Params {
        interface: LawKind::ElastoPlastic,
        kn: 170e6,
        fm: 5e6,
        ..dharahara::tower(None, None)
    }
}

fn main() {
    let block = |law| Params {
        interface: law,
        kn: 1e9,
        ..Params::default()
    };
    // (name, body, amplitude in g, frequency factor)
    let cases = [
        ("rigid", block(LawKind::Rigid), 0.5, 1.0),
        ("elastic", block(LawKind::Elastic), 0.5, 1.0),
        ("elastoPlastic", block(LawKind::ElastoPlastic), 0.5, 1.0),
        ("tower F170_fm5 (crushes)", tower(), 0.3, 0.3),
    ];
    let only = std::env::var("VERTICAL_COST_ONLY").ok();
    if only.is_none() {
        println!(
            "| case | steps av = 0 | steps with av | CPU av = 0 (ms) | CPU with av (ms) | ratio |"
        );
        println!("|---|---|---|---|---|---|");
    }
    for (name, params, amp, fr) in cases {
        let ag = record(amp * G, [1.1 * fr, 2.3 * fr, 3.7 * fr]);
        let av0 = vec![0.0; N + 1];
        let av = record(0.6 * amp * G, [1.7 * fr, 4.1 * fr, 6.3 * fr]);
        let sim = Simulator::new(params.build().unwrap(), 1e-9);
        if let Some(only) = &only {
            let (case, input) = only.split_once(',').unwrap_or((only, "av"));
            if name.starts_with(case) {
                let (steps, sum) = run(&sim, &ag, if input == "av0" { &av0 } else { &av });
                println!("{name} {input}: {steps} steps, checksum {sum:016x}");
            }
            continue;
        }
        let (mut best0, mut best1) = (f64::INFINITY, f64::INFINITY);
        let (mut s0, mut s1) = (0, 0);
        for _ in 0..7 {
            let t = cpu();
            s0 = run(&sim, &ag, &av0).0;
            best0 = best0.min(cpu() - t);
            let t = cpu();
            s1 = run(&sim, &ag, &av).0;
            best1 = best1.min(cpu() - t);
        }
        println!(
            "| {name} | {s0} | {s1} | {:.2} | {:.2} | {:.2} |",
            best0 * 1e3,
            best1 * 1e3,
            best1 / best0
        );
    }
}
