//! The co-simulation host's stepping loop, in native code.
//!
//! `fmu_stepper_run` steps one instance of an FMI 2.0 co-simulation FMU
//! through a whole input record and records outputs into caller-owned
//! arrays. It calls the FMU only through the function pointers it is given
//! (those of the FMU's own shared library, already loaded and instantiated
//! by the caller), so it works with any build of any FMU with at most two
//! real inputs, and knows nothing of the model.
//!
//! It makes exactly the calls of the reference loop in
//! `python/rocking/fmu.py` (`RockingFMU.simulate`), in the same order with
//! the same arguments, so the outputs are the same bit for bit; what it
//! saves is the interpreter's cost per call (docs/performance.md).
//!
//! Why a C ABI loaded with ctypes rather than a PyO3 extension: no
//! dependency and a build of about a second (PyO3 and maturin would add both
//! to the test command), and the same ctypes function pointers fmpy already
//! holds are passed straight in.

use std::ffi::c_void;

/// `fmi2Status` values (FMI 2.0 standard, 2.1.3).
const FMI2_DISCARD: i32 = 2;
/// `fmi2StatusKind` values (FMI 2.0 standard, 4.2.3).
const FMI2_TERMINATED: i32 = 3;
const FMI2_LAST_SUCCESSFUL_TIME: i32 = 2;

type Component = *mut c_void;
type SetReal = unsafe extern "C" fn(Component, *const u32, usize, *const f64) -> i32;
type SetRealInputDerivatives =
    unsafe extern "C" fn(Component, *const u32, usize, *const i32, *const f64) -> i32;
type DoStep = unsafe extern "C" fn(Component, f64, f64, i32) -> i32;
type GetReal = unsafe extern "C" fn(Component, *const u32, usize, *mut f64) -> i32;
type GetInteger = unsafe extern "C" fn(Component, *const u32, usize, *mut i32) -> i32;
type GetRealStatus = unsafe extern "C" fn(Component, i32, *mut f64) -> i32;
type GetBooleanStatus = unsafe extern "C" fn(Component, i32, *mut i32) -> i32;

/// The FMU's functions the loop calls (`fmi2GetBoolean` has the signature
/// of `fmi2GetInteger`: `fmi2Boolean` is an `int`).
#[repr(C)]
pub struct Functions {
    pub set_real: SetReal,
    pub set_real_input_derivatives: SetRealInputDerivatives,
    pub do_step: DoStep,
    pub get_real: GetReal,
    pub get_integer: GetInteger,
    pub get_boolean: GetInteger,
    pub get_real_status: GetRealStatus,
    pub get_boolean_status: GetBooleanStatus,
}

/// The layout of [`Run`] this library reads ([`fmu_stepper_abi`]): 2 added
/// the second input.
pub const ABI: u32 = 2;

/// The version of [`Run`]'s layout, for a caller to refuse a stale build
/// (one that would not read the fields it sets).
#[no_mangle]
pub extern "C" fn fmu_stepper_abi() -> u32 {
    ABI
}

/// One input line: at each communication point its value and the slope of
/// the segment that starts there (`fmi2SetRealInputDerivatives`, order 1).
#[repr(C)]
pub struct InputLine {
    /// Null: the input is not set.
    pub value: *const f64,
    pub slope: *const f64,
    pub vr: u32,
}

/// One run's inputs and output buffers, all owned by the caller.
#[repr(C)]
pub struct Run {
    /// Communication points `grid[0..=n_steps]`, s.
    pub grid: *const f64,
    pub n_steps: usize,
    /// The inputs, set in this order before every step.
    pub input: InputLine,
    pub second: InputLine,
    /// Outputs recorded at every sample, by value reference and type.
    pub vr_real: *const u32,
    pub n_real: usize,
    pub vr_integer: *const u32,
    pub n_integer: usize,
    pub vr_boolean: *const u32,
    pub n_boolean: usize,
    /// A sample after every `every` steps and after the last one.
    pub every: usize,
    /// Row-major buffers of `capacity` rows (`n_steps / every + 2` suffice):
    /// time, then `n_real`, `n_integer`, `n_boolean` columns.
    pub capacity: usize,
    pub times: *mut f64,
    pub reals: *mut f64,
    pub integers: *mut i32,
    pub booleans: *mut i32,
}

/// What the loop ended with.
#[repr(C)]
#[derive(Debug, Default, PartialEq)]
pub struct Outcome {
    /// Rows written.
    pub rows: usize,
    /// The FMU discarded a step and reported itself terminated (the last row
    /// is at `fmi2LastSuccessfulTime`).
    pub terminated: i32,
    /// 0: every call succeeded; else the status (> fmi2Warning) of the call
    /// named by `failed_call`.
    pub status: i32,
    /// 0 none, 1 fmi2Get*, 2 fmi2SetReal/fmi2SetRealInputDerivatives,
    /// 3 fmi2DoStep, 4 fmi2GetRealStatus/fmi2GetBooleanStatus,
    /// 5 the buffers are too small, 6 fmi2SetReal/fmi2SetRealInputDerivatives
    /// of the second input.
    pub failed_call: i32,
}

/// Records one row at time `t`; `Err(status)` when a get failed.
///
/// # Safety
/// As for [`fmu_stepper_run`].
unsafe fn sample(f: &Functions, c: Component, run: &Run, row: usize, t: f64) -> Result<(), i32> {
    let mut status = (f.get_real)(c, run.vr_real, run.n_real, run.reals.add(row * run.n_real));
    if run.n_integer > 0 {
        status = status.max((f.get_integer)(
            c,
            run.vr_integer,
            run.n_integer,
            run.integers.add(row * run.n_integer),
        ));
    }
    if run.n_boolean > 0 {
        status = status.max((f.get_boolean)(
            c,
            run.vr_boolean,
            run.n_boolean,
            run.booleans.add(row * run.n_boolean),
        ));
    }
    if status > 1 {
        return Err(status);
    }
    *run.times.add(row) = t;
    Ok(())
}

/// Sets `line`'s value and slope at point `k`, if it is set; the worse status.
///
/// # Safety
/// As for [`fmu_stepper_run`].
unsafe fn set_input(f: &Functions, c: Component, line: &InputLine, k: usize) -> i32 {
    if line.value.is_null() {
        return 0;
    }
    let order: i32 = 1;
    let a = *line.value.add(k);
    let status = (f.set_real)(c, &line.vr, 1, &a);
    let slope = *line.slope.add(k);
    status.max((f.set_real_input_derivatives)(
        c, &line.vr, 1, &order, &slope,
    ))
}

/// Steps `component` from `grid[0]` to `grid[n_steps]` and records the
/// outputs (a first row at `grid[0]`, as the caller has initialised it).
/// Stops at the first failed call or at a discarded step after which the
/// FMU reports itself terminated (the body overturned).
///
/// # Safety
/// `functions` points to the functions of the library `component` was
/// instantiated by; every pointer of `run` is valid for the lengths it
/// states (`grid` and each set input's `value` and `slope`: `n_steps + 1`;
/// the buffers: `capacity` rows).
#[no_mangle]
pub unsafe extern "C" fn fmu_stepper_run(
    functions: *const Functions,
    component: *mut c_void,
    run: *const Run,
) -> Outcome {
    let (f, run) = (&*functions, &*run);
    let mut out = Outcome::default();
    let every = run.every.max(1);
    if run.capacity < run.n_steps / every + 2 {
        out.failed_call = 5;
        return out;
    }
    let fail = |mut out: Outcome, status: i32, call: i32| {
        out.status = status;
        out.failed_call = call;
        out
    };
    if let Err(s) = sample(f, component, run, 0, *run.grid) {
        return fail(out, s, 1);
    }
    out.rows = 1;
    for k in 0..run.n_steps {
        let t = *run.grid.add(k);
        let status = set_input(f, component, &run.input, k);
        if status > 1 {
            return fail(out, status, 2);
        }
        let status = set_input(f, component, &run.second, k);
        if status > 1 {
            return fail(out, status, 6);
        }
        let status = (f.do_step)(component, t, *run.grid.add(k + 1) - t, 1);
        if status > 1 {
            if status == FMI2_DISCARD {
                let mut terminated = 0;
                let s = (f.get_boolean_status)(component, FMI2_TERMINATED, &mut terminated);
                if s > 1 {
                    return fail(out, s, 4);
                }
                if terminated != 0 {
                    let mut last = 0.0;
                    let s = (f.get_real_status)(component, FMI2_LAST_SUCCESSFUL_TIME, &mut last);
                    if s > 1 {
                        return fail(out, s, 4);
                    }
                    if let Err(s) = sample(f, component, run, out.rows, last) {
                        return fail(out, s, 1);
                    }
                    out.rows += 1;
                    out.terminated = 1;
                    return out;
                }
            }
            return fail(out, status, 3);
        }
        if (k + 1) % every == 0 || k + 1 == run.n_steps {
            if let Err(s) = sample(f, component, run, out.rows, *run.grid.add(k + 1)) {
                return fail(out, s, 1);
            }
            out.rows += 1;
        }
    }
    out
}
