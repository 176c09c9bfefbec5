//! Memory under load, through the exported C functions: resident memory
//! (`VmRSS`, its anonymous part `RssAnon`, and the peak `VmHWM`, from
//! `/proc/self/status`) along
//!
//! 1. 10 000 bare instantiate/free cycles;
//! 2. 10 000 whole instance lives (instantiate, parameters, initialise,
//!    10 steps, an FMU state taken, serialized, deserialized, set, freed,
//!    terminate, free), alternately a rigid and a crushing case;
//! 3. a 10 000 s record at 100 Hz (1e6 communication steps, the KATNP
//!    stand-in repeated) on a crushing interface, every output read after
//!    every step, an FMU state taken and serialized every 1000 steps.
//!
//! ```sh
//! cargo bench -p fmu-rocking --bench memory [-- STEPS]
//! ```

#[path = "../tests/host/mod.rs"]
mod host;

use std::time::Instant;

use host::*;

const CYCLES: usize = 10_000;
const MARKS: [usize; 5] = [1_000, 2_000, 5_000, 10_000, usize::MAX];

fn header(first: &str, extra: &str) {
    println!("| {first} | VmRSS KiB | RssAnon KiB | VmHWM KiB | {extra} |");
    println!("|{}", "---:|".repeat(5 + extra.matches('|').count()));
}

fn row(first: String, m: Mem, extra: String) {
    println!("| {first} | {} | {} | {} | {extra} |", m.rss, m.anon, m.hwm);
}

fn cycles(title: &str, mut one: impl FnMut(usize)) -> (Mem, Mem) {
    println!("\n{title}\n");
    header("cycles", "µs per cycle (since the row above)");
    row("0".into(), mem(), String::new());
    let mut at_1000 = Mem::default();
    let mut t = Instant::now();
    let mut last = 0;
    for k in 1..=CYCLES {
        one(k);
        if MARKS.contains(&k) {
            let m = mem();
            row(
                format!("{k}"),
                m,
                format!("{:.1}", t.elapsed().as_secs_f64() * 1e6 / (k - last) as f64),
            );
            if k == 1_000 {
                at_1000 = m;
            }
            t = Instant::now();
            last = k;
        }
    }
    let end = mem();
    println!(
        "\ngrowth from cycle 1 000 to 10 000: VmRSS {:+} KiB, RssAnon {:+} KiB",
        end.rss as i64 - at_1000.rss as i64,
        end.anon as i64 - at_1000.anon as i64
    );
    (at_1000, end)
}

fn main() {
    // `cargo bench` passes `--bench`; a number is the record's step count
    let steps: usize = std::env::args()
        .skip(1)
        .find_map(|a| a.parse().ok())
        .unwrap_or(1_000_000);
    let start = mem();
    println!("# Memory under load (through the C API)\n");
    println!(
        "at start: VmRSS {} KiB, RssAnon {} KiB, VmHWM {} KiB",
        start.rss, start.anon, start.hwm
    );

    cycles(
        "## 10 000 bare fmi2Instantiate / fmi2FreeInstance cycles",
        |_| drop(long_run_host("bare", false)),
    );

    let rigid = rigid_case(1.0, 2.0);
    let crushing = crushing_case(1.0, 2e5, 1.2);
    cycles(
        "## 10 000 whole instance lives (10 steps and an FMU state round trip each; rigid and crushing alternately)",
        |k| instance_cycle(if k % 2 == 0 { &rigid } else { &crushing }, 10),
    );

    let (case, what) = record_case();
    let h = case.h;
    println!(
        "\n## {steps} steps of {h} s ({} s): {what}, {}\n",
        steps as f64 * h,
        case.name
    );
    header(
        "steps",
        "simulated time s | impacts | steps ending in a crushing regime | max abs theta rad | µs per step (since the row above)",
    );
    let fmu = long_run_host("record", false);
    fmu.init_case(&case);
    row("0".into(), mem(), "0 | 0 | 0 | 0 | ".into());
    let marks: Vec<usize> = [10_000, 100_000, 200_000, 500_000, 1_000_000]
        .into_iter()
        .filter(|&m| m < steps)
        .chain([steps])
        .collect();
    let mut at_10pct = Mem::default();
    let mut max_theta = 0f64;
    let mut crushing_steps = 0usize;
    let mut t = Instant::now();
    let mut last = 0;
    let done = run(&fmu, &case, steps, |k, s| {
        max_theta = max_theta.max(s.reals[0].abs());
        crushing_steps += matches!(s.ints[0], 2 | 3) as usize;
        let n = k + 1;
        if n % 1000 == 0 {
            let mut st = fmu.get_state();
            let b = fmu.serialize(st);
            assert!(!b.is_empty());
            fmu.check("fmi2FreeFMUstate", fmu.free_state(&mut st));
        }
        if n == steps / 10 {
            at_10pct = mem();
        }
        if marks.contains(&n) {
            row(
                format!("{n}"),
                mem(),
                format!(
                    "{:.0} | {} | {crushing_steps} | {max_theta:.4} | {:.2}",
                    n as f64 * h,
                    s.ints[1],
                    t.elapsed().as_secs_f64() * 1e6 / (n - last) as f64
                ),
            );
            t = Instant::now();
            last = n;
        }
    });
    assert_eq!(done, steps, "the block overturned at step {done}");
    let end = mem();
    println!(
        "\ngrowth from step {} to {steps}: VmRSS {:+} KiB, RssAnon {:+} KiB",
        steps / 10,
        end.rss as i64 - at_10pct.rss as i64,
        end.anon as i64 - at_10pct.anon as i64
    );
    drop(fmu);
    let m = mem();
    println!(
        "\nat the end: VmRSS {} KiB, RssAnon {} KiB, peak (VmHWM) {} KiB",
        m.rss, m.anon, m.hwm
    );
}
