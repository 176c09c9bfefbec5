//! The process's CPU time, for the examples that compare runs by it
//! (`#[path = "support/cpu.rs"] mod cpu;`). Linux only: the examples that
//! time runs are measurements for docs/performance.md, made here.

/// CPU time of the process so far, s.
pub fn cpu() -> f64 {
    let mut ts = Timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // CLOCK_PROCESS_CPUTIME_ID = 2 on Linux
    unsafe { clock_gettime(2, &mut ts) };
    ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9
}

#[repr(C)]
struct Timespec {
    tv_sec: i64,
    tv_nsec: i64,
}

extern "C" {
    fn clock_gettime(clk: i32, ts: *mut Timespec) -> i32;
}
