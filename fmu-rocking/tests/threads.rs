//! Instances share nothing: 8 threads, each with its own two instances (a
//! block on a flexible interface that crushes, and a rigid block, with
//! parameters and forcing that differ from thread to thread), run 10 000
//! communication steps through the exported C functions at the same time,
//! and every output after every step, and the serialized FMU states taken
//! along the way, equal bit for bit those of the same runs done one after
//! the other on one thread.

mod host;

use std::sync::{Arc, Barrier};
use std::thread;

use fmu_rocking::description::vr;
use host::*;

const THREADS: usize = 8;
const STEPS: usize = 10_000;
/// Steps at which each instance's FMU state is taken and serialized.
const SNAPSHOT_EVERY: usize = 2_500;

/// The two runs of thread `i`: parameters and forcing differ per thread.
fn jobs(i: usize) -> [Case; 2] {
    let x = i as f64;
    let mut crushing = crushing_case(1.0 + 0.05 * x, 2e5 * (1.0 + 0.05 * x), 0.0);
    let alpha = (0.5f64 / (2.5 * (1.0 + 0.05 * x))).atan();
    crushing.ground = Ground::Record(Arc::new(bursts(
        1.2 * 9.81 * alpha.tan(),
        1.2 + 0.05 * x,
        STEPS + 1,
    )));
    crushing.name = format!("crushing #{i}");
    let mut rigid = rigid_case(1.0 + 0.1 * x, 0.0);
    let alpha = (0.4f64 / (2.0 * (1.0 + 0.1 * x))).atan();
    rigid.ground = Ground::Record(Arc::new(bursts(
        2.0 * 9.81 * alpha.tan(),
        2.5 + 0.1 * x,
        STEPS + 1,
    )));
    rigid.reals.push((vr::ETA, 0.85 + 0.01 * x));
    rigid
        .ints
        .push((vr::RESTITUTION, fmu_rocking::description::enums::GIVEN));
    rigid.name = format!("rigid #{i}");
    [crushing, rigid]
}

/// What one run produced: the outputs after every step, the serialized
/// FMU states, and whether it overturned (and when).
#[derive(PartialEq, Debug)]
struct Trace {
    outputs: Vec<[u64; 12]>,
    states: Vec<Vec<u8>>,
    overturned_at: Option<u64>,
}

/// Runs both cases of a thread, stepping the two instances alternately.
fn run_pair(cases: &[Case; 2]) -> [Trace; 2] {
    let fmus = [
        long_run_host(&cases[0].name, false),
        long_run_host(&cases[1].name, false),
    ];
    let mut traces: [Trace; 2] = std::array::from_fn(|_| Trace {
        outputs: Vec::with_capacity(STEPS),
        states: Vec::new(),
        overturned_at: None,
    });
    for (f, c) in fmus.iter().zip(cases) {
        f.init_case(c);
    }
    for k in 0..STEPS {
        for j in 0..2 {
            let (f, c, tr) = (&fmus[j], &cases[j], &mut traces[j]);
            if tr.overturned_at.is_some() {
                continue;
            }
            let (a, d) = c.input(k);
            let s = f.step(k as f64 * c.h, c.h, a, d);
            if s == fmi2_export::types::fmi2Discard {
                assert_eq!(f.terminated(), (fmi2OK, true));
                tr.overturned_at = Some(f.last_successful_time().1.to_bits());
                continue;
            }
            assert_eq!(s, fmi2_export::types::fmi2OK, "{} step {k}", c.name);
            tr.outputs.push(f.sample().bits());
            if (k + 1) % SNAPSHOT_EVERY == 0 {
                let mut st = f.get_state();
                tr.states.push(f.serialize(st));
                f.check("fmi2FreeFMUstate", f.free_state(&mut st));
            }
        }
    }
    traces
}

#[test]
fn eight_threads_equal_one_thread_bit_for_bit() {
    let all: Vec<[Case; 2]> = (0..THREADS).map(jobs).collect();

    // all at once, one thread per pair, started together
    let barrier = Arc::new(Barrier::new(THREADS));
    let handles: Vec<_> = all
        .iter()
        .cloned()
        .map(|cases| {
            let barrier = barrier.clone();
            thread::spawn(move || {
                barrier.wait();
                run_pair(&cases)
            })
        })
        .collect();
    let parallel: Vec<[Trace; 2]> = handles.into_iter().map(|h| h.join().unwrap()).collect();

    // the same runs, one after the other, on this thread
    let serial: Vec<[Trace; 2]> = all.iter().map(run_pair).collect();

    for (i, (p, s)) in parallel.iter().zip(&serial).enumerate() {
        for j in 0..2 {
            let name = &all[i][j].name;
            let (p, s) = (&p[j], &s[j]);
            assert_eq!(p.outputs.len(), s.outputs.len(), "{name}: steps");
            if let Some(k) = (0..p.outputs.len()).find(|&k| p.outputs[k] != s.outputs[k]) {
                panic!(
                    "{name}: outputs differ after step {k}: {:?} vs {:?}",
                    p.outputs[k], s.outputs[k]
                );
            }
            assert_eq!(p.states, s.states, "{name}: serialized FMU states");
            assert_eq!(p.overturned_at, s.overturned_at, "{name}: overturning");
        }
    }

    // the runs differ from thread to thread (an instance that computed with
    // another's parameters or state could not go unnoticed)
    for (a, ta) in serial.iter().enumerate() {
        for tb in &serial[a + 1..] {
            for (x, y) in ta.iter().zip(tb) {
                assert_ne!(x.outputs[100], y.outputs[100]);
            }
        }
    }

    // the runs do what they are meant to: rock with impacts, and crush
    for (i, t) in serial.iter().enumerate() {
        for (j, tr) in t.iter().enumerate() {
            let last = tr.outputs.last().unwrap();
            let impacts = last[10];
            let crushed = tr.outputs.iter().any(|o| o[9] == 2 || o[9] == 3);
            println!(
                "{:<12} {:>6} steps, {:>4} impacts, crushed {crushed}, overturned {:?}, {} states",
                all[i][j].name,
                tr.outputs.len(),
                impacts,
                tr.overturned_at.map(f64::from_bits),
                tr.states.len()
            );
            assert!(impacts >= 10, "{}: {impacts} impacts", all[i][j].name);
            assert_eq!(crushed, j == 0, "{}: crushing", all[i][j].name);
        }
    }
}
