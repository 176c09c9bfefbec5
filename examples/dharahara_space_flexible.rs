//! The Dharahara tower's 49 cases in space against planar runs
//! (docs/dharahara.md, "The tower in space on flexible and crushing beds"):
//! the cases of docs/model.md §4 (rigid, and the 48 foundation and interface
//! beds, `examples/support/dharahara.rs` `cases`), under each record pair of
//! the file list at each scale: in space under both horizontal components
//! and the vertical, and planar (with the vertical) along every azimuth of
//! `AZIMUTHS` (0 to 165 degrees by 15, x and y among them: 12 planar runs a
//! case, where the rigid study of `dharahara_space` takes 36), all rtol
//! 1e-10, 10 s past the record. Prints one JSON document: per case, record
//! and scale, peak tilt over alpha, overturning time, crossings (returns to
//! upright that applied the restitution rule: planar `zeroCrossings`, the
//! spatial `impacts`), liftOff time and the integrator's steps, in space
//! and planar along x, y and the worst azimuth (the earliest overturning,
//! else the largest peak). `--history ID@RECORD@SCALE,...` runs only those
//! and adds the top's path every 0.05 s (in space and planar along x, y and
//! the worst azimuth). `examples/dharahara_space.py --flexible` writes the
//! inputs and draws the page's table and figures from the output.
//!
//! ```sh
//! cargo run --release --example dharahara_space_flexible -- 1,3 DIR/*.txt > out.json
//! cargo run --release --example dharahara_space_flexible -- --history F170_fm5@Coalinga@3 3 DIR/*.txt
//! ```

use serde_json::{json, Value};

#[path = "support/dharahara.rs"]
mod dharahara;
#[path = "support/pair_file.rs"]
mod pair_file;
#[path = "support/space_runs.rs"]
mod space_runs;

use space_runs::{Run, RTOL, TAIL_S};

/// History sampling, s.
const EVERY: f64 = 0.05;
/// Planar azimuths, degrees from x toward y.
const AZIMUTHS: [f64; 12] = [
    0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 90.0, 105.0, 120.0, 135.0, 150.0, 165.0,
];

fn summary(r: &Run, alpha: f64) -> Value {
    json!({"peak_over_alpha": r.peak / alpha, "overturned_at": r.overturned, "crossings": r.crossings,
           "lift_off_at": r.lift_off, "steps": r.steps, "rejected": r.rejected})
}

fn main() {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let mut wanted: Option<Vec<(String, String, f64)>> = None;
    if args.first().is_some_and(|a| a == "--history") {
        let list = args.get(1).expect("--history ID@RECORD@SCALE,...").clone();
        wanted = Some(
            list.split(',')
                .map(|w| {
                    let parts: Vec<&str> = w.split('@').collect();
                    assert_eq!(parts.len(), 3, "--history: {w:?} is not ID@RECORD@SCALE");
                    let scale = parts[2]
                        .parse()
                        .unwrap_or_else(|e| panic!("--history: scale {:?}: {e}", parts[2]));
                    (parts[0].to_string(), parts[1].replace('_', " "), scale)
                })
                .collect(),
        );
        args.drain(..2);
    }
    let mut args = args.into_iter();
    let scales: Vec<f64> = args
        .next()
        .expect("usage: dharahara_space_flexible [--history ID@RECORD@SCALE,...] SCALES FILE...")
        .split(',')
        .map(|s| s.parse().expect("scales: numbers separated by commas"))
        .collect();
    let pairs: Vec<_> = args.map(|p| pair_file::read(&p)).collect();
    let cases = dharahara::cases();
    let alpha = cases[0].1.build().unwrap().body.alpha;
    let mut out = vec![];
    for (id, params) in &cases {
        let (sim, body) = space_runs::tower(id, params);
        for p in &pairs {
            for &scale in &scales {
                let history = wanted.as_ref().map(|w| {
                    w.iter()
                        .any(|(i, r, s)| i == id && *r == p.name && *s == scale)
                });
                if history == Some(false) {
                    continue;
                }
                let every = if history == Some(true) {
                    (EVERY / p.dt).round().max(1.0) as usize
                } else {
                    0
                };
                let sweep: Vec<(f64, Run)> = AZIMUTHS
                    .iter()
                    .map(|&deg| {
                        let keep = if deg == 0.0 || deg == 90.0 { every } else { 0 };
                        (
                            deg,
                            space_runs::planar(&sim, p, scale, deg.to_radians(), TAIL_S, keep),
                        )
                    })
                    .collect();
                // the worst azimuth: the earliest overturning, else the largest peak
                let worst = sweep
                    .iter()
                    .enumerate()
                    .min_by(|(_, (_, a)), (_, (_, b))| {
                        let key = |r: &Run| (r.overturned.unwrap_or(f64::INFINITY), -r.peak);
                        key(a).partial_cmp(&key(b)).unwrap()
                    })
                    .map(|(i, _)| i)
                    .unwrap();
                let worst_deg = AZIMUTHS[worst];
                let worst_history = if every > 0 && worst_deg != 0.0 && worst_deg != 90.0 {
                    space_runs::planar(&sim, p, scale, worst_deg.to_radians(), TAIL_S, every)
                        .history
                } else {
                    sweep[worst].1.history.clone()
                };
                let sp = space_runs::space(&body, p, scale, true, TAIL_S, every);
                let (px, py) = (&sweep[0].1, &sweep[6].1);
                eprintln!(
                    "{id} {} x{scale}: space {:.3} {:?} ({} steps), x {:.3} {:?}, y {:.3} {:?}, worst {worst_deg} deg {:.3} {:?}",
                    p.name,
                    sp.peak / alpha,
                    sp.overturned,
                    sp.steps,
                    px.peak / alpha,
                    px.overturned,
                    py.peak / alpha,
                    py.overturned,
                    sweep[worst].1.peak / alpha,
                    sweep[worst].1.overturned
                );
                let mut run = json!({
                    "case": id, "record": p.name, "bearing_x": p.bearing_x.map_or(Value::Null, |b| json!(b)),
                    "scale": scale, "space": summary(&sp, alpha),
                    "planar_x": summary(px, alpha), "planar_y": summary(py, alpha),
                    "worst_azimuth_deg": worst_deg, "planar_worst": summary(&sweep[worst].1, alpha),
                    "sweep": sweep.iter().map(|(deg, r)| json!({"azimuth_deg": deg, "run": summary(r, alpha)})).collect::<Vec<_>>(),
                });
                if every > 0 {
                    run["history"] = json!({"space": sp.history, "planar_x": px.history,
                                            "planar_y": py.history, "planar_worst": worst_history});
                }
                out.push(run);
            }
        }
    }
    let doc = json!({"alpha": alpha, "rtol": RTOL, "tail_s": TAIL_S, "azimuths_deg": AZIMUTHS, "runs": out});
    println!("{}", serde_json::to_string(&doc).unwrap());
}
