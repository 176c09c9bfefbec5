//! The cost of the round tower in space on its 49 beds against the planar
//! run of the same body and record (docs/performance.md, "The tower in
//! space on flexible and crushing beds"; the issue's target: at most 5x on
//! a crushing bed). For each case of docs/model.md §4
//! (`examples/support/dharahara.rs` `cases`) under one record pair: planar
//! along x with the vertical, in space under x and the vertical (the same
//! input: the same motion), and in space under both components and the
//! vertical; rtol 1e-10, 10 s past the record. Where the planar run ends
//! early (overturning, liftOff) and the run in space goes on, the run in
//! space is also timed over the planar run's span (the same samples), so
//! that a ratio compares the same body, record and interval. CPU time, the
//! best of 3 interleaved repetitions, integrator steps (accepted and
//! rejected) and rejected steps. Prints a table, then the median and the
//! worst ratio.
//!
//! ```sh
//! .venv/bin/python examples/dharahara_space.py --flexible   # writes out/dharahara_space/inputs
//! cargo run --release --example dharahara_space_cost -- 1 out/dharahara_space/inputs/Darfield_DFHS.txt
//! ```
//!
//! To iterate on a few cases, `DHARAHARA_CASES` restricts the run to the
//! case ids it lists (comma-separated), or to the crushing beds
//! (`crushing`); the issue's figures come from a run of all 49.

#[path = "support/cpu.rs"]
mod cpu;
#[path = "support/dharahara.rs"]
mod dharahara;
#[path = "support/pair_file.rs"]
mod pair_file;
#[path = "support/space_runs.rs"]
mod space_runs;

use cpu::cpu;
use space_runs::{Run, RTOL, TAIL_S};

const REPEAT: usize = 3;

fn outcome(r: &Run, alpha: f64) -> String {
    match (r.overturned, r.lift_off) {
        (Some(t), _) => format!("overturns {t:.2} s"),
        (None, Some(t)) => format!("liftOff {t:.2} s"),
        _ => format!("{:.3}", r.peak / alpha),
    }
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// The cases `filter` keeps: all without one, the crushing beds for
/// `crushing`, else those whose ids it lists (comma-separated).
fn select(
    cases: Vec<(String, rocking::Params)>,
    filter: Option<String>,
) -> Vec<(String, rocking::Params)> {
    let Some(filter) = filter else {
        return cases;
    };
    let ids: Vec<&str> = filter.split(',').map(str::trim).collect();
    let kept: Vec<_> = cases
        .into_iter()
        .filter(|(id, p)| {
            if filter == "crushing" {
                p.interface == rocking::model::LawKind::ElastoPlastic
            } else {
                ids.contains(&id.as_str())
            }
        })
        .collect();
    assert!(!kept.is_empty(), "DHARAHARA_CASES={filter}: no such case");
    kept
}

fn main() {
    let mut args = std::env::args().skip(1);
    let usage = "usage: dharahara_space_cost SCALE FILE";
    let scale: f64 = args.next().expect(usage).parse().expect("SCALE: a number");
    let pair = pair_file::read(&args.next().expect(usage));
    let cases = select(dharahara::cases(), std::env::var("DHARAHARA_CASES").ok());
    println!(
        "{} x{scale}, rtol {RTOL:e}, {TAIL_S} s past the record, CPU best of {REPEAT}",
        pair.name
    );
    println!();
    println!("| case | planar x: steps (rejected) | CPU (ms) | outcome | space x: steps (rejected) | CPU / planar | space x y v: steps (rejected) | CPU (ms) | CPU / planar | outcome | CPU / planar, planar's span |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    // ratios: all cases, crushing beds, crushing beds where both runs last the
    // whole record (neither overturns nor lifts off), CPU per step, space
    // along x alone
    let (mut all, mut crushing, mut whole, mut per_step, mut along_x) =
        (vec![], vec![], vec![], vec![], vec![]);
    // crushing beds, the run in space cut to the planar run's span
    let mut same_span = vec![];
    let mut worst = (0.0, String::new());
    for (id, params) in &cases {
        let (sim, body) = space_runs::tower(id, params);
        // the planar run's span in samples (it ends at overturning or
        // liftOff): the run in space over that span too, timed beside
        let span = space_runs::planar(&sim, &pair, scale, 0.0, TAIL_S, 0).samples;
        let runs: [&dyn Fn() -> Run; 4] = [
            &|| space_runs::planar(&sim, &pair, scale, 0.0, TAIL_S, 0),
            &|| space_runs::space(&body, &pair, scale, false, TAIL_S, 0),
            &|| space_runs::space(&body, &pair, scale, true, TAIL_S, 0),
            &|| space_runs::space_for(&body, &pair, scale, true, span, 0),
        ];
        let mut best = [f64::INFINITY; 4];
        let mut out: [Run; 4] = Default::default();
        for _ in 0..REPEAT {
            for (i, run) in runs.iter().enumerate() {
                if i == 3 && out[2].samples <= span {
                    continue; // the whole run in space is no longer
                }
                let t = cpu();
                out[i] = run();
                best[i] = best[i].min(cpu() - t);
            }
        }
        let ratio = best[2] / best[0];
        let span_ratio = if out[2].samples <= span {
            ratio
        } else {
            best[3] / best[0]
        };
        all.push(ratio);
        along_x.push(best[1] / best[0]);
        let [p, sx, s, _] = &out;
        per_step.push(ratio * p.steps as f64 / s.steps as f64);
        if params.interface == rocking::model::LawKind::ElastoPlastic {
            crushing.push(ratio);
            same_span.push(span_ratio);
            let ends = |r: &Run| r.overturned.is_none() && r.lift_off.is_none();
            if ends(p) && ends(s) {
                whole.push(ratio);
            }
        }
        if ratio > worst.0 {
            worst = (ratio, id.clone());
        }
        println!(
            "| {id} | {} ({}) | {:.1} | {} | {} ({}) | {:.2} | {} ({}) | {:.1} | {:.2} | {} | {:.2} |",
            p.steps,
            p.rejected,
            best[0] * 1e3,
            outcome(p, sim.model.body.alpha),
            sx.steps,
            sx.rejected,
            best[1] / best[0],
            s.steps,
            s.rejected,
            best[2] * 1e3,
            ratio,
            outcome(s, sim.model.body.alpha),
            span_ratio
        );
    }
    println!();
    let max = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
    println!("| CPU ratio | cases | median | worst |");
    println!("|---|---|---|---|");
    for (label, v) in [
        ("space x y v / planar x, all", &mut all),
        ("space x y v / planar x, crushing beds", &mut crushing),
        ("... crushing, both runs last the record", &mut whole),
        (
            "... crushing, space over the planar run's span",
            &mut same_span,
        ),
        ("space x y v / planar x, per step", &mut per_step),
        ("space x / planar x (the same motion)", &mut along_x),
    ] {
        println!(
            "| {label} | {} | {:.2} | {:.2} |",
            v.len(),
            median(v),
            max(v)
        );
    }
    println!("worst ratio: {} ({:.2})", worst.1, worst.0);
}
