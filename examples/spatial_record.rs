//! The cost of the round body in space against the planar run of the same
//! body and record (docs/performance.md, "A round body in space"): the
//! rigid Dharahara tower under each shipped record with two horizontal
//! components, scaled to rock it, planar along x, in space along x alone
//! (the same input), and in space under both components and the vertical;
//! CPU time (best of 3, interleaved), integrator steps, peak tilt, impacts.
//!
//! ```sh
//! .venv/bin/python benches/spatial_record.py --dump /tmp/spatial-records
//! cargo run --release --example spatial_record -- /tmp/spatial-records/*.txt
//! ```

use rocking::dynamics::{GroundInput, Simulator, VerticalInput};
use rocking::model::LawKind;
use rocking::spatial::{PlanInput, Spatial, SpatialState};

#[path = "support/cpu.rs"]
mod cpu;
#[path = "support/dharahara.rs"]
mod dharahara;
#[path = "support/pair_file.rs"]
mod pair_file;

use cpu::cpu;

const RTOL: f64 = 1e-9;
/// Samples of quiet after the record.
const TAIL: usize = 1000;

/// What one run did: steps (accepted and rejected), peak tilt (rad), impacts, overturned.
type Outcome = (u64, f64, u64, bool);

fn sample(rec: &[[f64; 3]], k: usize, scale: f64, c: usize) -> f64 {
    rec.get(k).map_or(0.0, |s| scale * s[c])
}

fn planar(sim: &Simulator, dt: f64, rec: &[[f64; 3]], scale: f64) -> Outcome {
    let mut st = sim.initial_state(0.0, 0.0);
    let (mut steps, mut peak) = (0u64, 0.0f64);
    for k in 0..rec.len() + TAIL {
        let (a0, a1) = (sample(rec, k, scale, 0), sample(rec, k + 1, scale, 0));
        let ev = sim.advance(
            &mut st,
            (k + 1) as f64 * dt,
            GroundInput {
                ag: a0,
                dag: (a1 - a0) / dt,
            },
        );
        steps += (ev.stats.steps + ev.stats.rejected) as u64;
        peak = peak.max(st.theta.abs());
        if st.overturned {
            break;
        }
    }
    (steps, peak, st.impacts, st.overturned)
}

fn spatial(body: &Spatial, dt: f64, rec: &[[f64; 3]], scale: f64, both: bool) -> Outcome {
    let mut st = SpatialState::at_rest();
    let (mut steps, mut peak) = (0u64, 0.0f64);
    let on = if both { 1.0 } else { 0.0 };
    for k in 0..rec.len() + TAIL {
        let s0 = [0, 1, 2].map(|c| sample(rec, k, scale, c));
        let s1 = [0, 1, 2].map(|c| sample(rec, k + 1, scale, c));
        let h = PlanInput {
            a: [s0[0], on * s0[1]],
            da: [(s1[0] - s0[0]) / dt, on * (s1[1] - s0[1]) / dt],
        };
        let v = VerticalInput {
            av: on * s0[2],
            dav: on * (s1[2] - s0[2]) / dt,
        };
        let ev = body.advance(&mut st, (k + 1) as f64 * dt, h, v);
        steps += (ev.steps + ev.rejected) as u64;
        peak = peak.max(st.theta());
        if st.overturned {
            break;
        }
    }
    (steps, peak, st.impacts, st.overturned)
}

fn main() {
    let params = rocking::Params {
        interface: LawKind::Rigid,
        ..dharahara::tower(None, None)
    };
    let model = params.build().unwrap();
    let b = model.body;
    // a hollow cylinder about its axis
    let c_axial = b.mass * (dharahara::RO.powi(2) + dharahara::RI.powi(2)) / 2.0;
    let sim = Simulator::new(model, RTOL);
    let body = Spatial::new(&params, Some(c_axial), RTOL).unwrap();
    println!("| record | scale | run | steps | CPU (ms) | CPU / planar | peak tilt / alpha | impacts | overturned |");
    println!("|---|---|---|---|---|---|---|---|---|");
    for path in std::env::args().skip(1) {
        let file = pair_file::read(&path);
        let (dt, rec) = (file.dt, file.samples);
        let pga = rec.iter().map(|s| s[0].abs()).fold(0.0, f64::max);
        // to three times the tower's uplift acceleration along x
        let scale = 3.0 * b.g * b.b / b.hg / pga;
        let runs: [(&str, &dyn Fn() -> Outcome); 3] = [
            ("planar along x", &|| planar(&sim, dt, &rec, scale)),
            ("space, x only", &|| spatial(&body, dt, &rec, scale, false)),
            ("space, x y v", &|| spatial(&body, dt, &rec, scale, true)),
        ];
        let mut best = [f64::INFINITY; 3];
        let mut out = [(0, 0.0, 0, false); 3];
        for _ in 0..3 {
            for (i, (_, run)) in runs.iter().enumerate() {
                let t = cpu();
                out[i] = run();
                best[i] = best[i].min(cpu() - t);
            }
        }
        let name = std::path::Path::new(&path)
            .file_stem()
            .unwrap()
            .to_string_lossy()
            .to_string();
        for (i, (label, _)) in runs.iter().enumerate() {
            let (steps, peak, impacts, over) = out[i];
            println!(
                "| {name} | {scale:.2} | {label} | {steps} | {:.1} | {:.2} | {:.3} | {impacts} | {over} |",
                best[i] * 1e3,
                best[i] / best[0],
                peak / b.alpha
            );
        }
    }
}
