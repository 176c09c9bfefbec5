//! The cost of the vertical input on a real record, in the Rust loop
//! (docs/performance.md): the Dharahara tower on three crushing beds under
//! DFHS 090 x3 of data/ground-motions, with and without the Darfield
//! station's vertical component (x3 too), rtol 1e-11, 5 s past the record;
//! CPU time (best of 3, interleaved) and integrator steps.
//!
//! The record comes from the Python readers, as a text file (the time step,
//! then `ag av` per sample, m/s²):
//!
//! ```sh
//! .venv/bin/python benches/vertical_record.py --dump /tmp/dfhs.txt
//! cargo run --release --example vertical_record -- /tmp/dfhs.txt
//! VERTICAL_RECORD_ONLY=F85_fm2,av cargo run --release --example vertical_record -- /tmp/dfhs.txt
//! ```
//!
//! `VERTICAL_RECORD_ONLY=CASE,av` (or `,av0`) runs that case once and prints
//! its steps, peak rotation and a checksum of the states at every sample
//! (for instruction counts with `valgrind --tool=callgrind`, less those of
//! `VERTICAL_RECORD_ONLY=none`, and to compare two builds bit for bit).

use rocking::dynamics::{GroundInput, Simulator, VerticalInput};
use rocking::model::LawKind;
use rocking::Params;

#[path = "support/cpu.rs"]
mod cpu;
#[path = "support/dharahara.rs"]
mod dharahara;

use cpu::cpu;

/// The record's scale, as in the Dharahara study (docs/dharahara.md).
const SCALE: f64 = 3.0;
/// Samples of quiet after the record.
const TAIL: usize = 1000;

/// The record file: time step (s), horizontal and vertical samples (m/s²).
fn read(path: &str) -> (f64, Vec<f64>, Vec<f64>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let mut lines = text.lines();
    let number = |s: &str| -> f64 { s.parse().unwrap_or_else(|e| panic!("{path}: {s:?}: {e}")) };
    let dt = number(
        lines
            .next()
            .unwrap_or_else(|| panic!("{path}: empty"))
            .trim(),
    );
    let (mut ag, mut av) = (Vec::new(), Vec::new());
    for line in lines {
        let mut values = line.split_whitespace().map(number);
        let (Some(h), Some(v)) = (values.next(), values.next()) else {
            panic!("{path}: {line:?}: two numbers expected");
        };
        ag.push(SCALE * h);
        av.push(SCALE * v);
    }
    (dt, ag, av)
}

/// One run, `av` or none: integrator steps, peak `|theta|` (rad) and a
/// checksum of the states at the samples (their bits).
fn run(sim: &Simulator, dt: f64, ag: &[f64], av: Option<&[f64]>) -> (u64, f64, u64) {
    let mut st = sim.initial_state(0.0, 0.0);
    let (mut steps, mut peak, mut sum) = (0, 0.0_f64, 0u64);
    let n = ag.len() - 1;
    let sample = |x: &[f64], k: usize| if k <= n { x[k] } else { 0.0 };
    for k in 0..n + TAIL {
        let (a0, a1) = (sample(ag, k), sample(ag, k + 1));
        let (v0, v1) = av.map_or((0.0, 0.0), |v| (sample(v, k), sample(v, k + 1)));
        let ev = sim.advance_vertical(
            &mut st,
            (k + 1) as f64 * dt,
            GroundInput {
                ag: a0,
                dag: (a1 - a0) / dt,
            },
            VerticalInput {
                av: v0,
                dav: (v1 - v0) / dt,
            },
        );
        steps += ev.stats.steps as u64 + ev.stats.rejected as u64;
        peak = peak.max(st.theta.abs());
        for x in [st.t, st.theta, st.omega] {
            sum = sum.rotate_left(7) ^ x.to_bits();
        }
        if st.overturned || ev.terminal.is_some() {
            break;
        }
    }
    (steps, peak, sum)
}

fn main() {
    let path = std::env::args()
        .nth(1)
        .expect("usage: vertical_record RECORD.txt (see the example's docs)");
    let (dt, ag, av) = read(&path);
    // (case, kn Pa/m, fm Pa): the crushing beds of docs/dharahara.md
    let cases = [
        ("F85_fm2", 85e6, 2e6),
        ("F170_fm5", 170e6, 5e6),
        ("I15_fm2", 15e9, 2e6),
    ];
    let only = std::env::var("VERTICAL_RECORD_ONLY").ok();
    if only.is_none() {
        println!(
            "| case | steps av = 0 | steps with av | CPU av = 0 (s) | CPU with av (s) | ratio |"
        );
        println!("|---|---|---|---|---|---|");
    }
    for (name, kn, fm) in cases {
        let params = Params {
            interface: LawKind::ElastoPlastic,
            kn,
            fm,
            ..dharahara::tower(None, None)
        };
        let sim = Simulator::new(params.build().unwrap(), 1e-11);
        if let Some(only) = &only {
            for (input, v) in [("av0", None), ("av", Some(&av[..]))] {
                if *only == format!("{name},{input}") {
                    let (steps, peak, sum) = run(&sim, dt, &ag, v);
                    println!(
                        "{name} {input}: {steps} steps, peak {peak:.6e} rad, checksum {sum:016x}"
                    );
                }
            }
            continue;
        }
        let (mut best, mut steps) = ([f64::INFINITY; 2], [0; 2]);
        for _ in 0..3 {
            for (i, v) in [None, Some(&av[..])].into_iter().enumerate() {
                let t = cpu();
                steps[i] = run(&sim, dt, &ag, v).0;
                best[i] = best[i].min(cpu() - t);
            }
        }
        println!(
            "| {name} | {} | {} | {:.3} | {:.3} | {:.2} |",
            steps[0],
            steps[1],
            best[0],
            best[1],
            best[1] / best[0]
        );
    }
}
