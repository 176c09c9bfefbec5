//! Flat memory under load, through the exported C functions (one test in its
//! own binary, so nothing else allocates in the process meanwhile):
//!
//! - 10 000 whole instance lives (instantiate, parameters, initialise,
//!   10 steps, an FMU state taken, serialized, deserialized, set and freed,
//!   terminate, free), a rigid and a crushing case alternately;
//! - a 10 000 s record at 100 Hz (1e6 steps; 1e5 in the unoptimised dev
//!   profile) on a crushing interface, every output read after every step,
//!   an FMU state taken and serialized every 1000 steps.
//!
//! The invariant: resident anonymous memory (`RssAnon`: heap and stacks)
//! does not grow by more than 256 KiB from cycle 1 000 to 10 000, nor from
//! 10 % of the record to its end. Why that bound: the smallest block glibc's
//! malloc hands out takes 32 bytes and is written to (its header) when
//! allocated, so one block leaked per cycle would add at least
//! 9 000 x 32 B = 281 KiB, and one per step at least 900 000 x 32 B = 27 MiB;
//! measured growth in steady state is 0 KiB (`cargo bench -p fmu-rocking
//! --bench memory` prints the table). `VmRSS` (which also counts pages of
//! the binary) must grow by less than 1 MiB.
//!
//! Under valgrind or AddressSanitizer resident memory says nothing (freed
//! blocks are held back in a quarantine, shadow memory grows), so the bounds
//! are not checked there and the record is 1e4 steps: their leak checks do
//! that job.

mod host;

use host::*;

const CYCLES: usize = 10_000;
const ANON_BOUND_KIB: i64 = 256;
const RSS_BOUND_KIB: i64 = 1024;

/// The memory checker this process runs under, if any: valgrind (which
/// preloads its libraries into the client through `LD_PRELOAD`) or
/// AddressSanitizer (whose shadow gap is mapped at a fixed range on x86-64).
fn memory_tool() -> Option<&'static str> {
    if std::env::var("LD_PRELOAD").is_ok_and(|p| p.contains("vgpreload")) {
        return Some("valgrind");
    }
    let maps = std::fs::read_to_string("/proc/self/maps").unwrap_or_default();
    maps.lines()
        .any(|l| l.starts_with("8fff7000-2008fff7000 "))
        .then_some("AddressSanitizer")
}

fn steps() -> usize {
    if memory_tool().is_some() {
        10_000
    } else if cfg!(debug_assertions) {
        100_000
    } else {
        1_000_000
    }
}

fn check(what: &str, from: Mem, to: Mem) {
    let anon = to.anon as i64 - from.anon as i64;
    let rss = to.rss as i64 - from.rss as i64;
    println!(
        "{what}: RssAnon {anon:+} KiB, VmRSS {rss:+} KiB (VmHWM {} KiB)",
        to.hwm
    );
    if let Some(tool) = memory_tool() {
        println!("under {tool}: resident memory not checked");
        return;
    }
    assert!(
        anon < ANON_BOUND_KIB,
        "{what}: RssAnon grew by {anon} KiB ({from:?} -> {to:?})"
    );
    assert!(
        rss < RSS_BOUND_KIB,
        "{what}: VmRSS grew by {rss} KiB ({from:?} -> {to:?})"
    );
}

#[test]
fn memory_stays_flat_over_instance_lives_and_a_long_record() {
    let rigid = rigid_case(1.0, 2.0);
    let crushing = crushing_case(1.0, 2e5, 1.2);
    let mut at_1000 = Mem::default();
    for k in 1..=CYCLES {
        instance_cycle(if k % 2 == 0 { &rigid } else { &crushing }, 10);
        if k == 1_000 {
            at_1000 = mem();
        }
    }
    check("cycles 1 000 -> 10 000", at_1000, mem());

    let steps = steps();
    let (case, _) = record_case();
    let fmu = long_run_host("record", false);
    fmu.init_case(&case);
    let mut at_10pct = Mem::default();
    let done = run(&fmu, &case, steps, |k, _| {
        let n = k + 1;
        if n % 1000 == 0 {
            let mut st = fmu.get_state();
            assert!(!fmu.serialize(st).is_empty());
            fmu.check("fmi2FreeFMUstate", fmu.free_state(&mut st));
        }
        if n == steps / 10 {
            at_10pct = mem();
        }
    });
    assert_eq!(done, steps, "the block overturned");
    check(
        &format!("record steps {} -> {steps}", steps / 10),
        at_10pct,
        mem(),
    );
}
