//! A Model Exchange host for the round body in space, written here
//! independently of the code under test: the derivatives, indicators and
//! event update of `rocking::spatial::continuous` integrated by RK4 with
//! step doubling, each event located by bisection to 1e-14 s; and
//! co-simulation (`Spatial::advance`) on the same sampled input, to
//! compare with. Used by tests/spatial_continuous.rs (rigid bed) and
//! tests/spatial_flexible_me.rs (flexible and crushing beds).

use rocking::dynamics::VerticalInput;
use rocking::spatial::continuous::{EVENT_INDICATORS, STATES};
use rocking::spatial::{PlanInput, Spatial, SpatialState};

use super::drum::DT;

/// The horizontal input (both components, m/s²) and the vertical one
/// (m/s², up) at `t` s.
pub type Input = dyn Fn(f64) -> ([f64; 2], f64);

thread_local! {
    /// The vertical input held at each sample (`dav = 0` in between, a jump
    /// at each sample) instead of linear: `N` is then constant over each
    /// interval for both runs, as Model Exchange takes it (no input
    /// derivatives). One test thread each.
    pub static HOLD_AV: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

thread_local! {
    /// The host integrates `omega` with `Spatial::derivatives` (`dN/dt`
    /// taken as 0) instead of `omegaW`: what Model Exchange of
    /// `shiftingPivot` on a flexible bed did before `omegaW`, kept to show
    /// the comparison sees it. One test thread each.
    pub static OMEGA_STATE: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// The input at `t`: the samples at multiples of `DT`, linear in between
/// (`av` held if `HOLD_AV`).
pub fn sampled(f: &Input, t: f64) -> ([f64; 2], f64) {
    let k = (t / DT).floor();
    let (t0, t1) = (k * DT, (k + 1.0) * DT);
    let (a0, v0) = f(t0);
    let (a1, v1) = f(t1);
    let s = (t - t0) / DT;
    let hold = if HOLD_AV.get() { 0.0 } else { 1.0 };
    (
        [a0[0] + s * (a1[0] - a0[0]), a0[1] + s * (a1[1] - a0[1])],
        v0 + hold * s * (v1 - v0),
    )
}

/// Co-simulation: one `advance` per sample interval; the state at each sample.
pub fn cs_run(body: &Spatial, mut st: SpatialState, f: &Input, t_end: f64) -> Vec<SpatialState> {
    let n = (t_end / DT).round() as usize;
    let mut out = vec![];
    for k in 0..n {
        let (t0, t1) = (k as f64 * DT, (k + 1) as f64 * DT);
        let ((a0, v0), (a1, v1)) = (f(t0), f(t1));
        let h = PlanInput {
            a: a0,
            da: [(a1[0] - a0[0]) / DT, (a1[1] - a0[1]) / DT],
        };
        let v = VerticalInput {
            av: v0,
            dav: if HOLD_AV.get() { 0.0 } else { (v1 - v0) / DT },
        };
        body.advance(&mut st, t1, h, v);
        out.push(st);
    }
    out
}

/// The host's state `sw` (its `omega` holding Model Exchange's `omegaW`,
/// the angular velocity referred to the weight) as the body's, with the
/// angular velocity, at its own time.
pub fn physical(body: &Spatial, sw: &SpatialState, f: &Input) -> SpatialState {
    if OMEGA_STATE.get() {
        return *sw;
    }
    body.from_weight_referred(*sw, sampled(f, sw.t).1)
}

/// The body's state `st` as the host's (the inverse of [`physical`]).
pub fn referred(body: &Spatial, st: &SpatialState, f: &Input) -> SpatialState {
    if OMEGA_STATE.get() {
        return *st;
    }
    body.to_weight_referred(*st, sampled(f, st.t).1)
}

/// One classical RK4 step of `h` from the host's state `st` (the discrete
/// state held).
pub fn rk4(body: &Spatial, st: &SpatialState, h: f64, f: &Input) -> SpatialState {
    let rates = |t: f64, y: &[f64; STATES]| {
        let mut s = *st;
        s.t = t;
        s.set_continuous_states(y);
        let (ag, av) = sampled(f, t);
        if OMEGA_STATE.get() {
            body.derivatives(&s, ag, av)
        } else {
            body.derivatives_weight_referred(&s, ag, av)
        }
    };
    let add = |y: &[f64; STATES], k: &[f64; STATES], c: f64| {
        let mut r = *y;
        for i in 0..STATES {
            r[i] += c * k[i];
        }
        r
    };
    let (t, y) = (st.t, st.continuous_states());
    let k1 = rates(t, &y);
    let k2 = rates(t + 0.5 * h, &add(&y, &k1, 0.5 * h));
    let k3 = rates(t + 0.5 * h, &add(&y, &k2, 0.5 * h));
    let k4 = rates(t + h, &add(&y, &k3, h));
    let mut y1 = y;
    for i in 0..STATES {
        y1[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
    let mut s = *st;
    s.t = t + h;
    s.set_continuous_states(&y1);
    s
}

/// The event indicators at the host's state `sw`.
pub fn indicators(body: &Spatial, sw: &SpatialState, f: &Input) -> [f64; EVENT_INDICATORS] {
    let (ag, av) = sampled(f, sw.t);
    body.event_indicators(&physical(body, sw, f), ag, av)
}

/// Whether an indicator went from positive to `<= 0`.
pub fn fired(z0: &[f64; EVENT_INDICATORS], z1: &[f64; EVENT_INDICATORS]) -> bool {
    z0.iter().zip(z1).any(|(a, b)| *a > 0.0 && *b <= 0.0)
}

/// `a + c b`, componentwise.
pub fn axpy(a: &[f64; STATES], c: f64, b: &[f64; STATES]) -> [f64; STATES] {
    let mut r = *a;
    for i in 0..STATES {
        r[i] += c * b[i];
    }
    r
}

/// Model Exchange by the host written here: RK4 with step doubling (the
/// difference of one step and two half steps estimates the error, kept
/// within `tol` of each state's size, at least `tol` times a billionth of
/// its nominal; the two half steps, extrapolated, are taken), cut at the
/// samples, where the input has kinks; an event located by bisection on
/// one RK4 step from the step's start to 1e-14 s and updated on its far
/// side; the host also asks `completed_step` after each step. The host
/// integrates `omegaW` (`omega` where the model makes it so); the event
/// updates and indicators take the body's state. Returns the body's state
/// at each sample and the number of events.
pub fn me_run(
    body: &Spatial,
    st0: SpatialState,
    f: &Input,
    t_end: f64,
    tol: f64,
) -> (Vec<SpatialState>, u32) {
    let update = |sw: &mut SpatialState| {
        let (ag, av) = sampled(f, sw.t);
        let mut st = physical(body, sw, f);
        let u = body.event_update(&mut st, ag, av);
        *sw = referred(body, &st, f);
        u
    };
    let mut st = referred(body, &st0, f);
    let nominal = body.nominals();
    let mut events = 0;
    update(&mut st);
    let n = (t_end / DT).round() as usize;
    let mut out = vec![];
    let mut h = 1e-4;
    for k in 0..n {
        let t1 = (k + 1) as f64 * DT;
        while st.t < t1 && !st.overturned && !st.out_of_range {
            let last = t1 - st.t <= h * (1.0 + 1e-9);
            let hh = if last { t1 - st.t } else { h };
            let big = rk4(body, &st, hh, f);
            let mid = rk4(body, &st, 0.5 * hh, f);
            let mut end = rk4(body, &mid, 0.5 * hh, f);
            let (y0, y1, y2) = (
                st.continuous_states(),
                big.continuous_states(),
                end.continuous_states(),
            );
            let mut err = 0.0f64;
            for i in 0..STATES {
                let scale = tol * (y0[i].abs().max(y2[i].abs()) + 1e-9 * nominal[i]);
                err = err.max((y2[i] - y1[i]).abs() / 15.0 / scale);
            }
            let factor = (0.9 * err.powf(-0.2)).clamp(0.2, 4.0);
            if err > 1.0 {
                h = hh * factor;
                continue;
            }
            h = if last {
                h.max(hh * factor)
            } else {
                hh * factor
            };
            end.set_continuous_states(&axpy(&y2, 1.0 / 15.0, &axpy(&y2, -1.0, &y1)));
            if last {
                end.t = t1;
            }
            let z0 = indicators(body, &st, f);
            if fired(&z0, &indicators(body, &end, f)) {
                let (mut lo, mut hi) = (0.0, hh);
                while hi - lo > 1e-14 {
                    let m = 0.5 * (lo + hi);
                    if fired(&z0, &indicators(body, &rk4(body, &st, m, f), f)) {
                        hi = m;
                    } else {
                        lo = m;
                    }
                }
                st = rk4(body, &st, hi, f);
                update(&mut st);
                events += 1;
                continue;
            }
            st = end;
            let (ag, av) = sampled(f, st.t);
            if body.completed_step(&physical(body, &st, f), ag, av) {
                update(&mut st);
                events += 1;
            }
        }
        if !st.overturned && !st.out_of_range {
            st.t = t1;
        }
        out.push(physical(body, &st, f));
    }
    (out, events)
}

/// The largest differences of `theta` (rad), of `psi` where `theta` is
/// above a tenth of its peak (rad), and of `(xG, yG)` (m) over the samples.
pub fn compare(a: &[SpatialState], b: &[SpatialState]) -> (f64, f64, f64, f64) {
    let peak = a.iter().map(|s| s.theta()).fold(0.0, f64::max);
    let (mut th, mut psi, mut x) = (0.0f64, 0.0f64, 0.0f64);
    for (p, q) in a.iter().zip(b) {
        th = th.max((p.theta() - q.theta()).abs());
        if p.theta() > 0.1 * peak {
            let d = p.contact_direction();
            let e = q.contact_direction();
            psi = psi.max(
                (d[1] * e[0] - d[0] * e[1])
                    .atan2(d[0] * e[0] + d[1] * e[1])
                    .abs(),
            );
        }
        x = x.max((p.xg[0] - q.xg[0]).hypot(p.xg[1] - q.xg[1]));
    }
    (th, psi, x, peak)
}

/// Both runs have the same discrete state at every sample: the impacts
/// (applications of the restitution rule), rest and overturning.
pub fn assert_same_discrete_states(name: &str, a: &[SpatialState], b: &[SpatialState]) {
    for (p, q) in a.iter().zip(b) {
        assert_eq!(
            (p.impacts, p.at_rest, p.overturned),
            (q.impacts, q.at_rest, q.overturned),
            "{name} at t = {}",
            p.t
        );
    }
}
