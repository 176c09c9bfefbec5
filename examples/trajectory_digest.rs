//! One SHA-256 over the bits of every trajectory of a broad grid run through
//! the public API: the proof that a refactor of the physics changed no
//! result (docs/dynamics.md, "Proving a refactor"). Run it before and after
//! the change and compare the two lines it prints:
//!
//! ```sh
//! cargo run --release --example trajectory_digest
//! ```
//!
//! The grid: the 4 shapes x 3 laws x both Runge-Kutta pairs x both
//! formulations x stiff mode on and off x {free rocking, a sine pulse, a
//! synthetic record on a soft interface; shaking below uplift on a stiff
//! one} x start time {0, 1e9 s}, each driven by `advance` at 100 Hz and
//! again by `advance_to_event`, plus runs stopped by a small work limit. After every call it hashes each field of the `State`, the `Events`
//! and the `Outputs` (`f64::to_bits`, integers, flags, enum tags).

use rocking::dynamics::{
    Events, GroundInput, Limited, Method, Outputs, Simulator, State, Stats, WorkLimit,
};
use rocking::model::{Formulation, LawKind, ShapeKind};
use rocking::{Model, Params};
use sha2::{Digest, Sha256};

/// Communication step of the forced runs, s (a record sampled at 100 Hz).
const DT: f64 = 0.01;
/// Length of each run, s.
const SPAN: f64 = 3.0;

/// The ground acceleration of a run, m/s², at `k` samples after its start.
#[derive(Clone, Copy, Debug)]
enum Drive {
    /// From an initial tilt, no ground motion.
    Free,
    /// One cycle of a sine of amplitude 0.4 g and period 1 s.
    Sine,
    /// A deterministic noise (a linear congruential generator) under a
    /// decaying envelope, 0.3 g at the most: a stand-in for a record.
    Record,
    /// Shaking below uplift, `0.5 g tan(alpha) sin(2 t)`: on a stiff
    /// interface, the case of the stiff mode (docs/dynamics.md §4).
    Tremble,
}

impl Drive {
    fn samples(self, g: f64, tan_alpha: f64) -> Vec<f64> {
        let n = (SPAN / DT) as usize + 1;
        match self {
            Drive::Free => vec![0.0; n],
            Drive::Sine => (0..n)
                .map(|k| {
                    let t = k as f64 * DT;
                    if t < 1.0 {
                        -0.4 * g * (std::f64::consts::TAU * t).sin()
                    } else {
                        0.0
                    }
                })
                .collect(),
            Drive::Record => {
                let mut x: u64 = 0x2545_f491_4f6c_dd1d;
                (0..n)
                    .map(|k| {
                        x = x
                            .wrapping_mul(6_364_136_223_846_793_005)
                            .wrapping_add(1_442_695_040_888_963_407);
                        let u = (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
                        let t = k as f64 * DT;
                        0.6 * g * u * (-t / 1.5).exp()
                    })
                    .collect()
            }
            Drive::Tremble => (0..n)
                .map(|k| 0.5 * g * tan_alpha * (2.0 * k as f64 * DT).sin())
                .collect(),
        }
    }
}

struct Hasher {
    sha: Sha256,
    runs: u64,
    calls: u64,
    /// What the grid reached, to show it is broad: zero crossings, stiff
    /// (RODAS) steps, calls ended at rest, overturned, at the work limit.
    reached: [u64; 5],
}

impl Hasher {
    fn f(&mut self, x: f64) {
        self.sha.update(x.to_bits().to_le_bytes());
    }

    fn u(&mut self, x: u64) {
        self.sha.update(x.to_le_bytes());
    }

    fn state(&mut self, s: &State) {
        let State {
            t,
            theta,
            omega,
            impacts,
            zero_crossings,
            opened,
            at_rest,
            overturned,
            h,
            a,
            stiff,
            switch_count,
        } = *s;
        for x in [t, theta, omega, h, a] {
            self.f(x);
        }
        for x in [impacts, zero_crossings, switch_count as u64] {
            self.u(x);
        }
        for x in [opened, at_rest, overturned, stiff] {
            self.u(x as u64);
        }
    }

    fn events(&mut self, e: &Events) {
        let Events {
            impacts,
            zero_crossings,
            uplift,
            came_to_rest,
            overturned_at,
            stats,
            limited,
            terminal,
            // not hashed: the digest predates it, and it restates how the
            // call ended (state.t below)
            stopped_at_event: _,
        } = *e;
        // without a vertical input the model's range is never left
        assert!(terminal.is_none());
        let Stats {
            steps,
            rejected,
            evals,
            stiff_steps,
        } = stats;
        for x in [impacts, zero_crossings, steps, rejected, evals, stiff_steps] {
            self.u(x as u64);
        }
        self.u(uplift as u64);
        self.u(came_to_rest as u64);
        self.u(overturned_at.is_some() as u64);
        self.f(overturned_at.unwrap_or(0.0));
        self.u(limited.is_some() as u64);
        if let Some(Limited {
            t,
            budget,
            steps,
            zero_crossings,
            h,
            stiff,
        }) = limited
        {
            self.f(t);
            self.f(h);
            for x in [budget, steps, zero_crossings, stiff as u64] {
                self.u(x);
            }
        }
    }

    fn outputs(&mut self, o: &Outputs) {
        let Outputs {
            theta_dd,
            af,
            contact_length,
            mr,
            regime,
            fx,
            fz,
            // the weight without a vertical input (not hashed: the digest
            // predates it)
            apparent_weight: _,
        } = *o;
        for x in [theta_dd, af, contact_length, mr, fx, fz] {
            self.f(x);
        }
        self.u(regime as u64);
    }

    /// One call's results.
    fn call(&mut self, sim: &Simulator, s: &State, e: &Events, ag: f64) {
        self.state(s);
        self.events(e);
        self.outputs(&sim.outputs(s, ag));
        self.calls += 1;
        let reached = [
            e.zero_crossings as u64,
            e.stats.stiff_steps as u64,
            e.came_to_rest as u64,
            e.overturned_at.is_some() as u64,
            e.limited.is_some() as u64,
        ];
        for (r, x) in self.reached.iter_mut().zip(reached) {
            *r += x;
        }
    }
}

/// The input of the call that starts at sample `k`: linear to the next.
fn input_at(samples: &[f64], k: usize) -> GroundInput {
    let ag = samples[k];
    let next = samples.get(k + 1).copied().unwrap_or(ag);
    GroundInput {
        ag,
        dag: (next - ag) / DT,
    }
}

/// `SPAN` seconds from `t0`, one `advance` per sample.
fn run_sampled(hs: &mut Hasher, sim: &Simulator, mut st: State, t0: f64, samples: &[f64]) {
    for k in 0..samples.len() - 1 {
        let input = input_at(samples, k);
        let e = sim.advance(&mut st, t0 + (k + 1) as f64 * DT, input);
        hs.call(
            sim,
            &st,
            &e,
            input.ag + input.dag * (st.t - (t0 + k as f64 * DT)),
        );
        if st.overturned {
            break;
        }
    }
}

/// `SPAN` seconds from `t0` by `advance_to_event` within each sample.
fn run_to_events(hs: &mut Hasher, sim: &Simulator, mut st: State, t0: f64, samples: &[f64]) {
    for k in 0..samples.len() - 1 {
        let (tk, t_end) = (t0 + k as f64 * DT, t0 + (k + 1) as f64 * DT);
        let sample = input_at(samples, k);
        let ag_at = |t: f64| sample.ag + sample.dag * (t - tk);
        // a vibration through theta = 0 may stop a call at every crossing
        for _ in 0..1000 {
            if st.t >= t_end || st.overturned {
                break;
            }
            let input = GroundInput {
                ag: ag_at(st.t),
                dag: sample.dag,
            };
            let e = sim.advance_to_event(&mut st, t_end, input);
            hs.call(sim, &st, &e, ag_at(st.t));
        }
    }
}

/// The parameters of a grid point: a 2.5 m prism on each base (`b = 0.5 m`
/// or `Ro = 0.5 m`) on an interface of normal stiffness `kn`, Pa/m.
fn params(shape: ShapeKind, law: LawKind, formulation: Formulation, kn: f64) -> Params {
    Params {
        shape,
        interface: law,
        formulation,
        kn,
        fm: 5.0e6,
        ..Params::default()
    }
}

fn main() {
    let mut hs = Hasher {
        sha: Sha256::new(),
        runs: 0,
        calls: 0,
        reached: [0; 5],
    };
    let shapes = [
        ShapeKind::SolidRectangle,
        ShapeKind::HollowRectangle,
        ShapeKind::SolidCircle,
        ShapeKind::HollowCircle,
    ];
    let laws = [LawKind::Rigid, LawKind::Elastic, LawKind::ElastoPlastic];
    // rocking on a soft interface at the default tolerance; trembling on a
    // stiff one at a loose tolerance, where the stiff mode takes over
    let cases = [
        (5e10, 1e-9, &[Drive::Free, Drive::Sine, Drive::Record][..]),
        (1e13, 1e-6, &[Drive::Tremble][..]),
    ];
    for shape in shapes {
        for law in laws {
            for formulation in [Formulation::Costa, Formulation::ShiftingPivot] {
                for (kn, rtol, drives) in cases {
                    let model = params(shape, law, formulation, kn).build().expect("valid");
                    for method in [Method::Dp5, Method::Dop853] {
                        for stiff_mode in [false, true] {
                            let mut sim = Simulator::with_method(model, rtol, method);
                            sim.stiff_mode = stiff_mode;
                            grid_point(&mut hs, &sim, drives);
                        }
                    }
                }
                let model = params(shape, law, formulation, 5e10)
                    .build()
                    .expect("valid");
                limited_runs(&mut hs, model);
            }
        }
    }
    let digest = hs.sha.finalize();
    let hex: String = digest.iter().map(|b| format!("{b:02x}")).collect();
    let [crossings, stiff_steps, rests, overturns, limited] = hs.reached;
    println!("runs {} calls {}", hs.runs, hs.calls);
    println!(
        "reached: {crossings} zero crossings, {stiff_steps} stiff steps, {rests} rests, {overturns} overturns, {limited} work limits"
    );
    println!("sha256 {hex}");
}

/// Each drive from both start times, through both entry points.
fn grid_point(hs: &mut Hasher, sim: &Simulator, drives: &[Drive]) {
    let b = &sim.model.body;
    for &drive in drives {
        let samples = drive.samples(b.g, b.b / b.hg);
        let theta0 = match drive {
            Drive::Free => 0.6 * b.alpha,
            _ => 0.0,
        };
        for t0 in [0.0, 1e9] {
            let mut st = sim.initial_state(theta0, 0.0);
            st.t = t0;
            run_sampled(hs, sim, st, t0, &samples);
            run_to_events(hs, sim, st, t0, &samples);
            hs.runs += 2;
        }
    }
}

/// Free rocking in 1 s calls under a work limit small enough to stop them.
fn limited_runs(hs: &mut Hasher, model: Model) {
    let mut sim = Simulator::new(model, 1e-9);
    sim.work_limit = Some(WorkLimit { per_call: 40 });
    let mut st = sim.initial_state(-0.6 * model.body.alpha, 0.0);
    for k in 1..=3 {
        let e = sim.advance(&mut st, k as f64, GroundInput::default());
        hs.call(&sim, &st, &e, 0.0);
    }
    hs.runs += 1;
}
