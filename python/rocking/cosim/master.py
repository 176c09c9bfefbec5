"""The co-simulation master: RockingBlock.fmu standing on floor j of ShearFrame.fmu.

    from rocking.cosim import CoupledFMUs, frame_params, sine_ground
    with CoupledFMUs() as fmus:                    # target/fmu/{ShearFrame,RockingBlock}.fmu
        res = fmus.run(frame=frame_params([1e4] * 3, [4e6] * 3, zeta=0.02),
                       block={"interface": "elastic", "kn": 1e8},
                       floor=3, ground=sine_ground(3.0, 2.0), stop_time=4.0, step=1e-3,
                       scheme="jacobi", inputs="extrapolate", reject=True)   # the defaults
        res.time, res.theta, res.a_floor, res.overturned, res.t_overturn

The coupling (docs/cosimulation.md §1): the frame's absolute acceleration of
floor j, `a[j]`, is the block's `ag`; the opposite of the block's support
forces `Fx`, `Fz` is applied to the frame's `Fx[j]`, `Fz[j]`. Both outputs
feed through their inputs (`a[j]` through `Fx[j]`, `Fx` through `ag`): the
algebraic loop is broken by the master's scheme.

Schemes (`scheme`):
- "jacobi": read both FMUs' outputs at t, set both inputs, step both;
- "gauss-seidel": step the frame first with the block's force predicted
  from t, then the block with the frame's `a[j]`, known over the whole step
  (interpolated between t and t + h with inputs="extrapolate", its end value
  held with inputs="constant").

Inputs (`inputs`): "constant" holds each input over the step (order 1);
"extrapolate" passes it with its first derivative (fmi2SetRealInputDerivatives;
FMI 3.0: the input der(x) of each input x), taken from the other FMU's output
derivatives (order 2); "midpoint" holds it at its extrapolation's value at the
step's midpoint, with the rates the FMUs' output derivatives then lack added
(`_Loop._with_input_rates`; the scheme for FMUs with no input derivatives). The
ground acceleration is an external input known in advance: passed as the chord
between communication points unless `ground_input` says otherwise.

`coupling="one-way"`: the block's forces are not applied to the frame (the
frame alone drives the block; what a record-driven study assumes).

`reject=True`: a step during which the block crosses theta = 0 (an impact,
its angular velocity jumps) or changes contact regime is rejected: both FMUs
go back to the step's start (fmi2SetFMUstate) and the step is bisected until
the part holding the event is no longer than h² / 0.1 s (or, with
`substeps=N`, redone in N equal parts). docs/cosimulation.md §4 measures what
it buys.

FMI 3.0 (`CoupledFMUs(fmi=3)`: target/fmu/fmi3/) has no fmi2SetRealInputDerivatives:
the 3.0 FMUs declare each continuous input's first derivative as an input der(x)
(`derivative` attribute), set with fmi3SetFloat64 into the store 2.0's call fills,
so every scheme above runs on them, bit for bit the 2.0 master's. With
`early_return=True` the block's fmi3DoStep stops at an impact, uplift or rest and
the master ends the communication step there for both FMUs (docs/cosimulation.md
§4b measures what it buys).

Overturning: the block's fmi2DoStep returns fmi2Discard with fmi2Terminated
true (3.0: terminateSimulation); the frame is brought to the same time (back to the step's start and
stepped to the overturning time), the run ends there, and the frame's FMU
state is returned serialized (`frame_state`) so the structure can go on alone.
"""

import math
import time as _time
from dataclasses import dataclass, field

import numpy as np

from .. import fmu as _fmu
from .. import paths
from .slave import Slave
from .slave3 import Slave3

SCHEMES = ("jacobi", "gauss-seidel")
INPUTS = ("constant", "extrapolate", "midpoint")
COUPLINGS = ("two-way", "one-way")
FMI_VERSIONS = (2, 3)
#: How the ground acceleration reaches the frame over a step: its chord (value and slope),
#: its value at the step's midpoint (the chord's mean) or at its start, held.
GROUND_INPUTS = ("chord", "midpoint", "held")
#: A rejected step is bisected until the part holding the event is h² / REJECT_TIME_SCALE.
REJECT_TIME_SCALE = 0.1  # s


def frame_params(masses, stiffnesses, zeta=0.05):
    """ShearFrame parameters for storey masses (kg) and stiffnesses (N/m), floor 1 first,
    modal damping ratio `zeta`."""
    if len(masses) != len(stiffnesses):
        raise ValueError("masses and stiffnesses must have one value per storey")
    p = {"n": len(masses), "damping": "modal", "zeta": float(zeta)}
    for i, (m, k) in enumerate(zip(masses, stiffnesses), start=1):
        p[f"m[{i}]"], p[f"k[{i}]"] = float(m), float(k)
    return p


def sine_ground(amplitude, frequency, cycles=None, t0=0.0):
    """ag(t) = amplitude sin(2 pi f (t - t0)) for `cycles` cycles (all time if None), m/s2.
    Vectorized; the master and the reference both take such a callable."""
    def ag(t):
        t = np.asarray(t, dtype=float)
        s = t - t0
        out = amplitude * np.sin(2 * np.pi * frequency * s)
        mask = s >= 0 if cycles is None else (s >= 0) & (s <= cycles / frequency)
        return np.where(mask, out, 0.0)
    return ag


def record_ground(time, acc):
    """ag(t) from samples (s, m/s2), linear between them, 0 after the last."""
    time, acc = np.asarray(time, float), np.asarray(acc, float)
    return lambda t: np.interp(t, time, acc, right=0.0)


@dataclass
class CosimResult:
    """One coupled run, sampled at the communication points.

    time          s
    theta, omega  the block's rotation (rad) and angular velocity (rad/s)
    a_floor       absolute acceleration of the block's floor, a[j] (m/s2)
    Fx, Fz        the block's support forces (N; the floor receives their opposite)
    u             floor displacements relative to the ground, shape (len(time), n) (m)
    ag            the ground acceleration (m/s2)
    overturned    the block overturned; the run ends at t_overturn
    t_overturn    nan unless overturned
    frame_state   the frame's serialized FMU state at the end (fmi2DeSerializeFMUstate
                  it to continue the structure alone)
    steps, rejected  communication steps taken, and rejected (reject=True)
    early_returns the times at which the block's fmi3DoStep returned early (early_return=True);
                  each is a communication point of the run
    wall          s
    """

    time: np.ndarray
    theta: np.ndarray
    omega: np.ndarray
    a_floor: np.ndarray
    Fx: np.ndarray
    Fz: np.ndarray
    u: np.ndarray
    ag: np.ndarray
    overturned: bool
    t_overturn: float
    frame_state: bytes
    steps: int
    rejected: int
    wall: float
    options: dict = field(default_factory=dict)
    messages: list = field(default_factory=list)
    early_returns: list = field(default_factory=list)


class CoupledFMUs:
    """ShearFrame.fmu and RockingBlock.fmu extracted and loaded once; `run` couples them.

    frame_fmu, block_fmu  default: target/fmu/ShearFrame.fmu and RockingBlock.fmu, or with
                          fmi=3 the FMI 3.0 archives target/fmu/fmi3/ShearFrame.fmu and
                          RockingBlock.fmu
    fmi                   2 or 3: the standard of both FMUs
    """

    def __init__(self, frame_fmu=None, block_fmu=None, fmi=2):
        if fmi not in FMI_VERSIONS:
            raise ValueError(f"fmi = {fmi!r}: not one of {FMI_VERSIONS}")
        self.fmi = fmi
        fmu_dir = paths.target_dir() / "fmu" if (frame_fmu is None or block_fmu is None) else None
        if fmu_dir is not None and fmi == 3:
            fmu_dir = fmu_dir / "fmi3"
        cls = Slave if fmi == 2 else Slave3
        self.frame = cls(frame_fmu or fmu_dir / "ShearFrame.fmu")
        self.block = cls(block_fmu or fmu_dir / "RockingBlock.fmu")
        for s in (self.frame, self.block):
            if getattr(s, "fmi_version", None) != fmi:
                raise _fmu.FMUError(f"{s.path}: not an FMI {fmi}.0 FMU")
            cs = s.capabilities
            if not ((cs.canInterpolateInputs or fmi == 3) and (cs.maxOutputDerivativeOrder or 0) >= 1
                    and cs.canGetAndSetFMUstate and cs.canHandleVariableCommunicationStepSize):
                raise _fmu.FMUError(f"{s.path}: needs canInterpolateInputs (FMI 2.0), output derivatives, "
                                    "get/set FMU state and variable steps")

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        self.frame.close()
        self.block.close()

    def run(self, frame, block, floor, ground, stop_time, step, scheme="jacobi",
            inputs="extrapolate", coupling="two-way", reject=True, substeps=None, rtol=1e-10, vertical=None,
            early_return=False, ground_input=None):
        """Couple the block on floor `floor` (1-based) of the frame from t = 0 to
        `stop_time` with communication step `step`; returns a `CosimResult`.

        frame, block  parameter (and start) values by name of each FMU
        ground        ag(t), a vectorized callable (m/s2): sine_ground, record_ground
        rtol          the block's integrator tolerance (the frame's step is exact)
        vertical      av(t), a vectorized callable (m/s2, up) or None: the ground's vertical
                      acceleration, given to the block as its input av as it is (the shear
                      frame has no vertical degree of freedom: its floors move with the ground)
        early_return  FMI 3.0 only: the block's fmi3DoStep may stop at an impact, uplift or
                      rest inside the step; the master then ends the communication step there
                      for both FMUs, runs the block's event mode and goes on from that time
        ground_input  how the frame gets the ground over a step, one of GROUND_INPUTS
                      (default "chord")
        With FMI 3.0 an input's rate (inputs="extrapolate", ground_input="chord", and av)
        goes to its der(x) input: the run is the FMI 2.0 master's bit for bit. 3.0 FMUs
        that declare no der(x) inputs take inputs="constant" or "midpoint" and
        ground_input="midpoint" or "held", without av.
        The defaults (Jacobi, extrapolated inputs, step rejection) are the most accurate
        combination measured in docs/cosimulation.md §4.
        """
        if scheme not in SCHEMES:
            raise ValueError(f"scheme = {scheme!r}: not one of {SCHEMES}")
        if inputs not in INPUTS:
            raise ValueError(f"inputs = {inputs!r}: not one of {INPUTS}")
        if coupling not in COUPLINGS:
            raise ValueError(f"coupling = {coupling!r}: not one of {COUPLINGS}")
        ground_input = ground_input or "chord"
        if ground_input not in GROUND_INPUTS:
            raise ValueError(f"ground_input = {ground_input!r}: not one of {GROUND_INPUTS}")
        if early_return and self.fmi != 3:
            raise ValueError("early_return = True needs the FMI 3.0 FMUs (fmi=3)")
        n = int(frame.get("n", 3))
        if not 1 <= int(floor) <= n:
            raise ValueError(f"floor = {floor}: must be a floor of the frame, 1..{n}")
        if not (step > 0 and stop_time > 0):
            raise ValueError("step and stop_time must be positive")
        self._check_rates(int(floor), inputs, ground_input, coupling == "two-way", vertical is not None)
        wall = _time.perf_counter()
        loop = _Loop(self.frame, self.block, int(floor), n, ground, scheme, inputs,
                     coupling == "two-way", reject, None if substeps is None else int(substeps), vertical,
                     ground_input)
        try:
            self.frame.instantiate(frame, 0.0, stop_time)
            if self.fmi == 3:
                self.block.instantiate(block, 0.0, stop_time, rtol=rtol, early_return=early_return)
            else:
                self.block.instantiate(block, 0.0, stop_time, rtol=rtol)
            self.frame.exit_init()
            self.block.exit_init()
            loop.start()
            n_steps = int(math.ceil(stop_time / step - 1e-9))
            grid = np.minimum(np.arange(n_steps + 1) * step, stop_time)
            for k in range(n_steps):
                if not loop.advance(grid[k], grid[k + 1] - grid[k]):
                    break
            frame_state = loop.frame_serialized()
        finally:
            self.frame.free()
            self.block.free()
        rows = np.array(loop.rows)
        return CosimResult(
            time=rows[:, 0], theta=rows[:, 1], omega=rows[:, 2], a_floor=rows[:, 3], Fx=rows[:, 4],
            Fz=rows[:, 5], ag=rows[:, 6], u=rows[:, 7:7 + n], overturned=loop.overturned,
            t_overturn=loop.t_overturn, frame_state=frame_state, steps=loop.steps,
            rejected=loop.rejected, wall=_time.perf_counter() - wall,
            options=dict(floor=floor, stop_time=stop_time, step=step, scheme=scheme, inputs=inputs,
                         coupling=coupling, reject=reject, substeps=substeps, rtol=rtol,
                         vertical=vertical is not None, fmi=self.fmi, early_return=early_return,
                         ground_input=ground_input),
            messages=list(_fmu._MESSAGES), early_returns=loop.early_returns)

    def _check_rates(self, floor, inputs, ground_input, two_way, vertical):
        """The inputs whose rates the run passes must take them (FMI 3.0: a der(x) input
        each); a ValueError naming the first that does not."""
        need = [(self.frame, "ground_input", ground_input, "ag")] if ground_input == "chord" else []
        if inputs == "extrapolate":
            need.append((self.block, "inputs", inputs, "ag"))
            if two_way:
                need += [(self.frame, "inputs", inputs, f"{x}[{floor}]") for x in ("Fx", "Fz")]
        if vertical and inputs != "midpoint":
            need.append((self.block, "inputs", inputs, "av"))
        for slave, option, value, name in need:
            if not slave.takes_rate(name):
                raise ValueError(f"{option} = {value!r} needs the input der({name}) of {slave.path} "
                                 f"(FMI {self.fmi}.0), which it does not declare: use inputs = 'midpoint' "
                                 "or 'constant', ground_input = 'midpoint' or 'held'")


class _Loop:
    """The state of one coupled run between communication points."""

    def __init__(self, frame, block, j, n, ground, scheme, inputs, two_way, reject, substeps, vertical=None,
                 ground_input="chord"):
        self.frame, self.block, self.ground, self.vertical = frame, block, ground, vertical
        self.gs, self.two_way = scheme == "gauss-seidel", two_way
        self.reject, self.substeps, self.ground_input = reject, substeps, ground_input
        # the exchanged inputs' rates are used ("extrapolate": passed with the values;
        # "midpoint": to hold each input at its mean over the step instead)
        self.extrapolate = inputs != "constant"
        self.midpoint = inputs == "midpoint"
        self.r_ag = frame.refs(["ag"])
        self.r_force = frame.refs([f"Fx[{j}]", f"Fz[{j}]"])
        self.r_a = frame.refs([f"a[{j}]"])
        self.r_u = frame.refs([f"u[{i}]" for i in range(1, n + 1)])
        self.r_bag = block.refs(["ag"])
        self.r_bav = block.refs(["av"]) if vertical is not None else None
        # the block's force reaches the frame with its rate (docs/model.md §7.4: under av too)
        self.force_rates = self.extrapolate
        self.r_bf = block.refs(["Fx", "Fz"])
        self.r_th = block.refs(["theta", "omega"])
        self.rows, self.steps, self.rejected, self.early_returns = [], 0, 0, []
        self.overturned, self.t_overturn = False, math.nan

    # -- the exchanged values at the current communication point --------------
    def _block_force(self):
        """The force on the floor, -(Fx, Fz), and its rate (None unless extrapolating:
        the force is then held over the step)."""
        f = self.block.get(self.r_bf)
        if not self.force_rates:
            return [-f[0], -f[1]], None
        d = self.block.get_der(self.r_bf)
        return [-f[0], -f[1]], [-d[0], -d[1]]

    def _floor_acc(self):
        a = self.frame.get(self.r_a)[0]
        return a, (self.frame.get_der(self.r_a)[0] if self.extrapolate else 0.0)

    def _set_input(self, slave, refs, values, rates, h):
        """Inputs linear over the next step h: their values and rates (held if rates is
        None), or with inputs="midpoint" held at their mean over the step."""
        if self.midpoint and rates is not None:
            slave.set(refs, [v + 0.5 * r * h for v, r in zip(values, rates)])
        else:
            slave.set(refs, values, rates)

    def _set_frame_force(self, force, rate, h=0.0):
        if self.two_way:
            self._set_input(self.frame, self.r_force, force, rate, h)

    def _set_ground(self, t, h):
        """The frame's ag over [t, t + h], as ground_input says."""
        g0, g1 = (float(x) for x in self.ground(np.array([t, t + h])))
        if self.ground_input == "chord":
            self.frame.set(self.r_ag, [g0], [(g1 - g0) / h])
        else:
            self.frame.set(self.r_ag, [0.5 * (g0 + g1) if self.ground_input == "midpoint" else g0])

    def start(self):
        """Consistent values at t = 0: iterate the algebraic loop (a contraction for
        block/floor mass ratios below 1) until it settles."""
        g = float(self.ground(0.0))
        self.frame.set(self.r_ag, [g])
        if self.vertical is not None:
            self.block.set(self.r_bav, [float(self.vertical(0.0))])
        self._settle(rates=False)
        self._record(0.0)

    def _settle(self, rates):
        """Iterate the algebraic loop at the current point (a contraction for block/floor
        mass ratios below 1) until the block's ag is the frame's a[j] and the frame's
        force the block's, with their rates if `rates`."""
        for _ in range(50):
            a, da = self._floor_acc()
            self.block.set(self.r_bag, [a], [da] if rates else None)
            force, rate = self._block_force()
            self._set_frame_force(force, rate if rates else None)
            if abs(self._floor_acc()[0] - a) <= 1e-13 * (1 + abs(a)):
                break

    def _record(self, t):
        th = self.block.get(self.r_th)
        f = self.block.get(self.r_bf)
        self.rows.append([t, th[0], th[1], self.frame.get(self.r_a)[0], f[0], f[1],
                          float(self.ground(t)), *self.frame.get(self.r_u)])

    # -- one communication step ------------------------------------------------
    def advance(self, t, h):
        """Step both FMUs from t to t + h; False once the block has overturned. Each early
        return of the block ends a (shorter) communication step at its time, and the
        rest of [t, t + h] is stepped from there."""
        end = t + h
        while True:
            done = self._attempt(t, h, self._event_step(h)) if self.reject else self._step(t, h)
            self.steps += 1
            if done is None:
                return False
            self._record(done.time)
            if not done.early:
                return True
            self.early_returns.append(done.time)
            t, h = done.time, end - done.time

    def _event_step(self, h):
        """How short the part of a rejected step holding the event is made: h² / 0.1 s
        (the local error there is O(that), so the scheme keeps its order 2)."""
        return h * h / REJECT_TIME_SCALE if self.substeps is None else h / self.substeps

    def _attempt(self, t, h, shortest):
        """Step [t, t + h]; if the block crossed theta = 0 or changed regime in it (not
        at an early return, which puts the event at the step's end) and h is above
        `shortest`, go back (get/set FMU state) and do both halves the same way: a
        bisection that ends with the event inside a step no longer than `shortest`.
        With `substeps` set, the rejected step is redone in that many equal parts.
        Returns how the last step taken ended (a StepEnd), None at overturning."""
        fstate, bstate = self.frame.get_state(), self.block.get_state()
        before = (self.block.get_int("zeroCrossings"), self.block.get_int("regime"))
        try:
            done = self._step(t, h)
            event = (done is not None and not done.early
                     and (self.block.get_int("zeroCrossings"), self.block.get_int("regime")) != before)
            if not event or h <= shortest * (1 + 1e-9):
                return done
            self.frame.set_state(fstate)
            self.block.set_state(bstate)
            self.rejected += 1
        finally:
            self.frame.free_state(fstate)
            self.block.free_state(bstate)
        if self.substeps is not None:
            hs = h / self.substeps
            for i in range(self.substeps):
                ts = t + i * hs
                done = self._step(ts, hs if i + 1 < self.substeps else t + h - ts)
                if done is None or done.early:
                    return done
            return done
        done = self._attempt(t, h / 2, shortest)
        if done is None or done.early:
            return done
        return self._attempt(t + h / 2, h / 2, shortest)

    def _step(self, t, h):
        """Both FMUs over [t, t + h] -> the block's StepEnd (None at overturning). An
        early return at t_e brings the frame back to t and steps it to t_e."""
        self._set_ground(t, h)
        force, rate = self._block_force()
        if self.midpoint and self.force_rates and self.two_way:
            rate, da_floor = self._with_input_rates(force, rate)
        if self.gs:
            a0, _ = self._floor_acc()
            fstate = self._keep_frame()
            self._set_frame_force(force, rate, h)
            self.frame.step(t, h)
            a1, _ = self._floor_acc()
            ag = ([a0], [(a1 - a0) / h]) if self.extrapolate else ([a1], None)
        else:
            a0, da = self._floor_acc()
            if self.midpoint and self.force_rates and self.two_way:
                da = da_floor
            fstate = self._keep_frame()
            ag = ([a0], [da] if self.extrapolate else None)
            self._set_frame_force(force, rate, h)
            self.frame.step(t, h)
        self._set_input(self.block, self.r_bag, *ag, h)
        if self.vertical is not None:  # the ground's av, straight to the block (no vertical DOF in the frame)
            v0, v1 = (float(x) for x in self.vertical(np.array([t, t + h])))
            self._set_input(self.block, self.r_bav, [v0], [(v1 - v0) / h], h)
        done = self._block_step(t, h, ag)
        if done.terminated or done.early:
            self._frame_to(t, done.time, fstate, force, rate)
        else:
            self._release_frame(fstate)
        if done.terminated:
            self.overturned, self.t_overturn = True, done.time
            self._record(done.time)
            return None
        if done.event:
            self.block.handle_event()
        if self.midpoint and ag[1] is not None:
            # the block's feedthrough (Fx from ag) at the step's end sees the input's
            # end value, as an FMI 2.0 input continued along its rate does
            self.block.set(self.r_bag, [ag[0][0] + ag[1][0] * (done.time - t)])
        # the block's force at the step's end and its rate, seen by the frame's a[j] and
        # a[j]' from now on (feedthrough)
        self._set_frame_force(*self._block_force())
        if done.early and self.two_way:
            # the block's force jumped at its event (rigid law: impact, uplift), and so
            # did a[j]: without this the frame would get, over the rest of the step, the
            # force of the block's ag before the jump, an O(h) impulse per event
            self._settle(rates=self.extrapolate and not self.midpoint)
        return done

    def _block_step(self, t, h, ag):
        """The block over [t, t + h]. With inputs held at their midpoint, a step that
        returns early at t_e is redone once from t with the inputs' midpoint over
        [t, t_e]: the part of the step the block takes then sees its inputs' mean over
        that part (the event moves by far less than the step)."""
        redo = self.midpoint and ag[1] is not None and getattr(self.block, "event_mode", False)
        bstate = self.block.get_state() if redo else None
        try:
            done = self.block.step(t, h)
            if not (redo and done.early) or done.time <= t:
                return done
            self.block.set_state(bstate)
            self._set_input(self.block, self.r_bag, *ag, done.time - t)
            return self.block.step(t, h)
        finally:
            if bstate is not None:
                self.block.free_state(bstate)

    def _with_input_rates(self, force, rate):
        """inputs="midpoint": the rates of the force on the floor and of a[j], with the
        terms the FMUs' output derivatives leave out because they get no input rates. Both
        outputs feed through (a[j] from the force, the block's force from its ag), so
            a' = a'_0 + (da/df) f',   f' = f'_0 + (df/dag) a'
        with f'_0, a'_0 the FMUs' output derivatives and the two gains measured by
        changing each input by a small amount and back (both outputs are linear in
        those inputs at a given state). Returns (f', a')."""
        a0 = self.frame.get(self.r_a)[0]
        da0 = self.frame.get_der(self.r_a)[0]
        df = 1e-6 * (1.0 + abs(force[0]))
        self.frame.set(self.r_force, [force[0] + df, force[1]])
        ga = (self.frame.get(self.r_a)[0] - a0) / df
        self.frame.set(self.r_force, force)
        dag = 1e-6 * (1.0 + abs(a0))
        self.block.set(self.r_bag, [a0])
        f0 = self.block.get(self.r_bf)
        self.block.set(self.r_bag, [a0 + dag])
        gf = [-(x - y) / dag for x, y in zip(self.block.get(self.r_bf), f0)]
        da = (da0 + ga * rate[0]) / (1.0 - ga * gf[0])
        return [r + g * da for r, g in zip(rate, gf)], da

    # -- early return and overturning: the frame is brought to the block's time --
    def _keep_frame(self):
        return self.frame.get_state()

    def _release_frame(self, fstate):
        if fstate is not None:
            self.frame.free_state(fstate)

    def _frame_to(self, t, t_end, fstate, force, rate):
        """Back to the step's start t and on to t_end with the same inputs."""
        self.frame.set_state(fstate)
        self._release_frame(fstate)
        if t_end > t:
            self._set_ground(t, t_end - t)
            self._set_frame_force(force, rate, t_end - t)
            self.frame.step(t, t_end - t)

    def frame_serialized(self):
        state = self.frame.get_state()
        try:
            return self.frame.serialize(state)
        finally:
            self.frame.free_state(state)
