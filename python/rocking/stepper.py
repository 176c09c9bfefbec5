"""The stepping loop in native code: `fmu-stepper` (the workspace crate), through ctypes.

`step(functions, component, ...)` steps an instantiated, initialised FMU
through a whole record and returns numpy arrays. It makes the very FMI calls
of the Python loop in `fmu.RockingFMU.simulate` (the reference, kept), in the
same order with the same arguments, so the results are the same bit for bit
(fmpy-tests/test_stepper.py checks it); it saves the interpreter's cost per
step (docs/performance.md).

The library is `libfmu_stepper.so` (`fmu_stepper.dll` on Windows) that
`cargo xtask fmu` (or `cargo build --release -p fmu-stepper`) writes to
target/release, or the file named by $ROCKING_STEPPER. `library()` is None
when there is none: callers then use the Python loop.
"""

import ctypes
import os
import sys
from ctypes import POINTER, Structure, c_double, c_int, c_size_t, c_uint32, c_void_p

import numpy as np

from . import paths

_NAME = {"win32": "fmu_stepper.dll", "darwin": "libfmu_stepper.dylib"}.get(sys.platform, "libfmu_stepper.so")

#: Outcome.failed_call: which call failed.
CALLS = {1: "fmi2Get*", 2: "fmi2SetReal/fmi2SetRealInputDerivatives", 3: "fmi2DoStep",
         4: "fmi2GetRealStatus/fmi2GetBooleanStatus", 5: "fmu_stepper_run (buffers too small)",
         6: "fmi2SetReal/fmi2SetRealInputDerivatives (av)"}

#: The layout of `Run` this module writes (the library's `fmu_stepper_abi()`).
ABI = 2

# The FMU's functions the loop calls, in the order of the Rust struct `Functions`.
FUNCTIONS = ("fmi2SetReal", "fmi2SetRealInputDerivatives", "fmi2DoStep", "fmi2GetReal",
             "fmi2GetInteger", "fmi2GetBoolean", "fmi2GetRealStatus", "fmi2GetBooleanStatus")


class _Functions(Structure):
    _fields_ = [(name, c_void_p) for name in FUNCTIONS]


class _InputLine(Structure):
    _fields_ = [("value", POINTER(c_double)), ("slope", POINTER(c_double)), ("vr", c_uint32)]


class _Run(Structure):
    _fields_ = [("grid", POINTER(c_double)), ("n_steps", c_size_t),
                ("input", _InputLine), ("second", _InputLine),
                ("vr_real", POINTER(c_uint32)), ("n_real", c_size_t),
                ("vr_integer", POINTER(c_uint32)), ("n_integer", c_size_t),
                ("vr_boolean", POINTER(c_uint32)), ("n_boolean", c_size_t),
                ("every", c_size_t), ("capacity", c_size_t),
                ("times", POINTER(c_double)), ("reals", POINTER(c_double)),
                ("integers", POINTER(c_int)), ("booleans", POINTER(c_int))]


class Outcome(Structure):
    _fields_ = [("rows", c_size_t), ("terminated", c_int), ("status", c_int), ("failed_call", c_int)]


_LIB = False  # not looked for yet


def library_path():
    """Where the library is looked for ($ROCKING_STEPPER, else target/release)."""
    env = os.environ.get("ROCKING_STEPPER")
    if env:
        return env
    if paths.REPO is None:
        return None
    return str(paths.target_dir() / "release" / _NAME)


def library():
    """The loaded library's `fmu_stepper_run`, or None when it is not built."""
    global _LIB
    if _LIB is False:
        path = library_path()
        _LIB = None
        if path and os.path.isfile(path):
            lib = ctypes.CDLL(path)
            abi = getattr(lib, "fmu_stepper_abi", None)
            if abi is None or abi() != ABI:  # a stale build: it would not read every field
                raise RuntimeError(f"{path}: built for another layout of its runs (ABI "
                                   f"{abi() if abi else 1}, this module writes {ABI}): rebuild it "
                                   "(cargo xtask fmu)")
            run = lib.fmu_stepper_run
            run.argtypes = [POINTER(_Functions), c_void_p, POINTER(_Run)]
            run.restype = Outcome
            _LIB = run
        elif os.environ.get("ROCKING_STEPPER"):
            raise FileNotFoundError(f"ROCKING_STEPPER={path}: no such file")
    return _LIB


def functions(raw):
    """The struct of function pointers from fmpy's ctypes functions (`FMU2Slave._functions`)."""
    return _Functions(*[ctypes.cast(raw[name], c_void_p).value for name in FUNCTIONS])


def _ptr(array, ctype):
    return array.ctypes.data_as(POINTER(ctype))


def _vrs(values):
    return np.ascontiguousarray(values, dtype=np.uint32)


def step(fns, component, grid, acc, slope, vr_input, vr_real, vr_integer, vr_boolean, every, second=None):
    """Step from grid[0] to grid[-1]; `acc`, `slope` None: no input; `second`: None, or a
    second input (value reference, values, slopes on the grid), set after the first.

    Returns (outcome, times, reals, integers, booleans), the arrays cut to the rows written.
    """
    run_fn = library()
    grid = np.ascontiguousarray(grid, dtype=float)
    n_steps = len(grid) - 1
    cap = n_steps // every + 2
    vr_r, vr_i, vr_b = _vrs(vr_real), _vrs(vr_integer), _vrs(vr_boolean)
    times = np.empty(cap)
    reals = np.empty((cap, len(vr_r)))
    ints = np.empty((cap, len(vr_i)), dtype=np.intc)
    bools = np.empty((cap, len(vr_b)), dtype=np.intc)
    keep = [grid]
    run = _Run(grid=_ptr(grid, c_double), n_steps=n_steps,
               vr_real=_ptr(vr_r, c_uint32), n_real=len(vr_r),
               vr_integer=_ptr(vr_i, c_uint32), n_integer=len(vr_i),
               vr_boolean=_ptr(vr_b, c_uint32), n_boolean=len(vr_b),
               every=every, capacity=cap, times=_ptr(times, c_double), reals=_ptr(reals, c_double),
               integers=_ptr(ints, c_int), booleans=_ptr(bools, c_int))
    for field, line in (("input", None if acc is None else (vr_input, acc, slope)), ("second", second)):
        if line is not None:
            value, slope_ = (np.ascontiguousarray(x, dtype=float) for x in line[1:])
            keep += [value, slope_]
            setattr(run, field, _InputLine(_ptr(value, c_double), _ptr(slope_, c_double), line[0]))
    out = run_fn(ctypes.byref(fns), component, ctypes.byref(run))
    del keep
    n = out.rows
    return out, times[:n], reals[:n], ints[:n], bools[:n]
