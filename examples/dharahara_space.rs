//! The rigid Dharahara tower in space against planar runs (docs/dharahara.md,
//! "The rigid tower in space"): under each record pair of the file list, at
//! each scale, the tower in space under both horizontal components and the
//! vertical, and planar along x, along y and along every azimuth from 0 to
//! 175 degrees by 5 (each with the vertical), all rtol 1e-10, 10 s past the
//! record. Prints one JSON document: per record and scale, every run's peak
//! tilt over alpha, overturning time, impacts, liftOff time, and the
//! histories (every 0.05 s) of the run in space and of the planar runs along
//! x, y and the worst azimuth. `examples/dharahara_space.py` writes the
//! inputs and draws the page's figures and table from the output.
//!
//! ```sh
//! cargo run --release --example dharahara_space -- 1,3 DIR/*.txt > out.json
//! ```
//! Each input file: a first line `# name bearing_x`, the time step (s), then
//! `agx agy av` per sample (m/s²).

use rocking::dynamics::{Simulator, VerticalInput};
use rocking::model::LawKind;
use rocking::spatial::{PlanInput, Spatial, SpatialState};
use serde_json::{json, Value};

#[path = "support/dharahara.rs"]
mod dharahara;
#[path = "support/pair_file.rs"]
mod pair_file;
#[path = "support/space_runs.rs"]
mod space_runs;

/// History sampling, s.
const EVERY: f64 = 0.05;

use pair_file::PairFile as Pair;
use space_runs::{at, planar_input, samples, Run, RTOL, TAIL_S};

/// Planar along the azimuth `az` (rad from x toward y), with the vertical.
fn planar(sim: &Simulator, p: &Pair, scale: f64, az: f64, keep: bool) -> Run {
    let (s, c) = az.sin_cos();
    let (hg, radius) = (sim.model.body.hg, sim.model.body.b);
    let mut st = sim.initial_state(0.0, 0.0);
    let mut run = Run::default();
    let every = (EVERY / p.dt).round().max(1.0) as usize;
    for k in 0..samples(p, TAIL_S) {
        let (ga, v) = planar_input(p, k, scale, az);
        let ev = sim.advance_vertical(&mut st, (k + 1) as f64 * p.dt, ga, v);
        if keep && (k + 1) % every == 0 {
            // the top, at 2 hG, from the base's centre at rest: about the
            // toe at R sgn(theta), R sgn(theta) (1 - cos) + 2 hG sin
            let (sn, cs) = st.theta.sin_cos();
            let lean = radius * st.theta.signum() * (1.0 - cs) + 2.0 * hg * sn;
            run.history.push([st.t, st.theta, lean * c, lean * s]);
        }
        if run.after_planar(&st, &ev) {
            break;
        }
    }
    run.crossings = st.impacts;
    run
}

/// In space under both components, with or without the vertical.
fn space(body: &Spatial, p: &Pair, scale: f64, vertical: bool) -> Run {
    let hg = body.model.body.hg;
    let mut st = SpatialState::at_rest();
    let mut run = Run::default();
    let every = (EVERY / p.dt).round().max(1.0) as usize;
    let v_on = if vertical { 1.0 } else { 0.0 };
    for k in 0..samples(p, TAIL_S) {
        let (a0, a1) = (at(p, k, scale), at(p, k + 1, scale));
        let h = PlanInput {
            a: [a0[0], a0[1]],
            da: [(a1[0] - a0[0]) / p.dt, (a1[1] - a0[1]) / p.dt],
        };
        let v = VerticalInput {
            av: v_on * a0[2],
            dav: v_on * (a1[2] - a0[2]) / p.dt,
        };
        let ev = body.advance(&mut st, (k + 1) as f64 * p.dt, h, v);
        if (k + 1) % every == 0 {
            // the top, 2 hG up the axis from the base: G plus hG e
            run.history.push([
                st.t,
                st.theta(),
                st.xg[0] + hg * st.e[0],
                st.xg[1] + hg * st.e[1],
            ]);
        }
        if run.after_space(&st, &ev) {
            break;
        }
    }
    run.crossings = st.impacts;
    run
}

fn summary(r: &Run, alpha: f64) -> Value {
    json!({"peak_over_alpha": r.peak / alpha, "overturned_at": r.overturned, "impacts": r.crossings, "lift_off_at": r.lift_off})
}

fn main() {
    let mut args = std::env::args().skip(1);
    let scales: Vec<f64> = args
        .next()
        .expect("usage: dharahara_space SCALES FILE...")
        .split(',')
        .map(|s| s.parse().expect("scales: numbers separated by commas"))
        .collect();
    let params = rocking::Params {
        interface: LawKind::Rigid,
        ..dharahara::tower(None, None)
    };
    let (sim, body) = space_runs::tower("rigid", &params);
    let b = sim.model.body;
    let mut out = vec![];
    for path in args {
        let p = pair_file::read(&path);
        for &scale in &scales {
            let sweep: Vec<(f64, Run)> = (0..36)
                .map(|i| {
                    let deg = 5.0 * i as f64;
                    (deg, planar(&sim, &p, scale, deg.to_radians(), false))
                })
                .collect();
            // the worst azimuth: the earliest overturning, else the largest peak
            let worst = sweep
                .iter()
                .min_by(|(_, a), (_, b)| {
                    let key = |r: &Run| (r.overturned.unwrap_or(f64::INFINITY), -r.peak);
                    key(a).partial_cmp(&key(b)).unwrap()
                })
                .map(|(deg, _)| *deg)
                .unwrap();
            let sp = space(&body, &p, scale, true);
            let sp_h = space(&body, &p, scale, false);
            let px = planar(&sim, &p, scale, 0.0, true);
            let py = planar(&sim, &p, scale, 90f64.to_radians(), true);
            let pw = planar(&sim, &p, scale, worst.to_radians(), true);
            eprintln!(
                "{} x{scale}: space {:.3} ({:?}), x {:.3}, y {:.3}, worst {worst} deg {:.3}",
                p.name,
                sp.peak / b.alpha,
                sp.overturned,
                px.peak / b.alpha,
                py.peak / b.alpha,
                pw.peak / b.alpha
            );
            out.push(json!({
                "record": p.name, "bearing_x": p.bearing_x.map_or(Value::Null, |b| json!(b)), "scale": scale,
                "space": summary(&sp, b.alpha), "space_without_av": summary(&sp_h, b.alpha),
                "planar_x": summary(&px, b.alpha), "planar_y": summary(&py, b.alpha),
                "worst_azimuth_deg": worst, "planar_worst": summary(&pw, b.alpha),
                "sweep": sweep.iter().map(|(deg, r)| json!({"azimuth_deg": deg, "run": summary(r, b.alpha)})).collect::<Vec<_>>(),
                "history": {"space": sp.history, "planar_x": px.history, "planar_y": py.history, "planar_worst": pw.history},
            }));
        }
    }
    let doc = json!({"alpha": b.alpha, "hG": b.hg, "rtol": RTOL, "tail_s": TAIL_S, "runs": out});
    println!("{}", serde_json::to_string(&doc).unwrap());
}
