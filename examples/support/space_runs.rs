//! One record pair run on the round tower in space and planar along an
//! azimuth, for the examples that compare them on any bed
//! (`#[path = "support/space_runs.rs"] mod space_runs;`, beside
//! `pair_file`): peak tilt, overturning, crossings, the integrator's work
//! and, when asked, the path of the top.

#![allow(dead_code)] // each example uses part of it

use rocking::dynamics::{Events, GroundInput, Simulator, State, VerticalInput};
use rocking::spatial::{PlanInput, Spatial, SpatialEvents, SpatialState};
use rocking::Params;

use super::dharahara::{RI, RO};
use super::pair_file::PairFile;

/// Both integrators' relative tolerance.
pub const RTOL: f64 = 1e-10;
/// Seconds of quiet after the record.
pub const TAIL_S: f64 = 10.0;

/// What a run did.
#[derive(Default)]
pub struct Run {
    /// Peak tilt, rad.
    pub peak: f64,
    /// Overturning time, s.
    pub overturned: Option<f64>,
    /// Returns to upright that applied the restitution rule: the planar
    /// model's `zeroCrossings`, the spatial state's `impacts`
    /// (docs/model.md §11.3).
    pub crossings: u64,
    /// Time the vertical input reached -g (the run ends there), s.
    pub lift_off: Option<f64>,
    /// Samples advanced, the one it ended in included.
    pub samples: usize,
    /// Integrator steps, accepted and rejected.
    pub steps: u64,
    pub rejected: u64,
    /// When kept, every `every` samples: `[t, tilt (rad, signed for a
    /// planar run), top x, top y]`, the top relative to the base's centre
    /// at rest, m (here 2 hG times the axis's horizontal part; the rigid
    /// tower of `dharahara_space` adds the pivot's and the centre's travel).
    pub history: Vec<[f64; 4]>,
}

impl Run {
    /// One sample: its integrator steps (accepted, rejected) and tilt
    /// (rad); the run ends at an overturning (`overturned`, at
    /// `overturned_at` s) or at liftOff (at `lift_off` s). Returns whether
    /// it ended.
    pub fn sample(
        &mut self,
        steps: u32,
        rejected: u32,
        tilt: f64,
        overturned: bool,
        overturned_at: Option<f64>,
        lift_off: Option<f64>,
    ) -> bool {
        self.samples += 1;
        self.steps += u64::from(steps + rejected);
        self.rejected += u64::from(rejected);
        self.peak = self.peak.max(tilt);
        if overturned {
            self.overturned = overturned_at;
            return true;
        }
        if lift_off.is_some() {
            self.lift_off = lift_off;
            return true;
        }
        false
    }

    /// [`Run::sample`] after a planar call.
    pub fn after_planar(&mut self, st: &State, ev: &Events) -> bool {
        let lift_off = ev.terminal.map(|term| term.t);
        let (steps, rejected) = (ev.stats.steps, ev.stats.rejected);
        self.sample(
            steps,
            rejected,
            st.theta.abs(),
            st.overturned,
            ev.overturned_at,
            lift_off,
        )
    }

    /// [`Run::sample`] after a call in space.
    pub fn after_space(&mut self, st: &SpatialState, ev: &SpatialEvents) -> bool {
        let lift_off = ev.terminal.map(|term| term.t);
        self.sample(
            ev.steps,
            ev.rejected,
            st.theta(),
            st.overturned,
            ev.overturned_at,
            lift_off,
        )
    }
}

/// The tower on `params` (case `id`, named when it does not build), planar
/// and in space, both at `RTOL`; in space with the axial moment of inertia
/// of a hollow cylinder of radii `RO` and `RI` (kg m²).
pub fn tower(id: &str, params: &Params) -> (Simulator, Spatial) {
    let model = params.build().unwrap_or_else(|e| panic!("case {id}: {e}"));
    let b = model.body;
    // a hollow cylinder about its axis
    let c_axial = b.mass * (RO.powi(2) + RI.powi(2)) / 2.0;
    let sim = Simulator::new(model, RTOL);
    let body =
        Spatial::new(params, Some(c_axial), RTOL).unwrap_or_else(|e| panic!("case {id}: {e}"));
    (sim, body)
}

/// Sample `k` of the pair times `scale` (zero past the record): `[agx,
/// agy, av]`, m/s².
pub fn at(p: &PairFile, k: usize, scale: f64) -> [f64; 3] {
    p.samples.get(k).map_or([0.0; 3], |s| s.map(|x| scale * x))
}

/// The planar input over sample interval `k` along the azimuth `az` (rad
/// from x toward y): the horizontal components projected on it, and the
/// vertical, linear between the samples.
pub fn planar_input(p: &PairFile, k: usize, scale: f64, az: f64) -> (GroundInput, VerticalInput) {
    let (s, c) = az.sin_cos();
    let (a0, a1) = (at(p, k, scale), at(p, k + 1, scale));
    let (g0, g1) = (c * a0[0] + s * a0[1], c * a1[0] + s * a1[1]);
    (
        GroundInput {
            ag: g0,
            dag: (g1 - g0) / p.dt,
        },
        VerticalInput {
            av: a0[2],
            dav: (a1[2] - a0[2]) / p.dt,
        },
    )
}

/// Samples of the record plus `tail_s` of quiet.
pub fn samples(p: &PairFile, tail_s: f64) -> usize {
    p.samples.len() + (tail_s / p.dt).round() as usize
}

/// Planar along the azimuth `az` (rad from x toward y), with the vertical;
/// the history every `every` samples if `every > 0`.
pub fn planar(
    sim: &Simulator,
    p: &PairFile,
    scale: f64,
    az: f64,
    tail_s: f64,
    every: usize,
) -> Run {
    let (s, c) = az.sin_cos();
    let hg = sim.model.body.hg;
    let mut st = sim.initial_state(0.0, 0.0);
    let mut run = Run::default();
    for k in 0..samples(p, tail_s) {
        let (ga, v) = planar_input(p, k, scale, az);
        // no work limit is set: one call reaches t_end
        let ev = sim.advance_vertical(&mut st, (k + 1) as f64 * p.dt, ga, v);
        if run.after_planar(&st, &ev) {
            break;
        }
        if every > 0 && (k + 1) % every == 0 {
            let lean = 2.0 * hg * st.theta.sin();
            run.history.push([st.t, st.theta, lean * c, lean * s]);
        }
    }
    run.crossings = st.zero_crossings;
    run
}

/// In space under both components and the vertical (`both`; else x and the
/// vertical, the planar run's input along x); the history every `every`
/// samples if `every > 0`.
pub fn space(
    body: &Spatial,
    p: &PairFile,
    scale: f64,
    both: bool,
    tail_s: f64,
    every: usize,
) -> Run {
    space_for(body, p, scale, both, samples(p, tail_s), every)
}

/// [`space`] over the first `n` samples only (as long as a planar run that
/// ended early, to compare the cost of the same span).
pub fn space_for(
    body: &Spatial,
    p: &PairFile,
    scale: f64,
    both: bool,
    n: usize,
    every: usize,
) -> Run {
    let on = if both { 1.0 } else { 0.0 };
    let hg = body.model.body.hg;
    let mut st = SpatialState::at_rest();
    let mut run = Run::default();
    for k in 0..n {
        let (a0, a1) = (at(p, k, scale), at(p, k + 1, scale));
        let h = PlanInput {
            a: [a0[0], on * a0[1]],
            da: [(a1[0] - a0[0]) / p.dt, on * (a1[1] - a0[1]) / p.dt],
        };
        let v = VerticalInput {
            av: a0[2],
            dav: (a1[2] - a0[2]) / p.dt,
        };
        // no max_steps is set: one call reaches the sample's end
        let ev = body.advance(&mut st, (k + 1) as f64 * p.dt, h, v);
        if run.after_space(&st, &ev) {
            break;
        }
        if every > 0 && (k + 1) % every == 0 {
            run.history
                .push([st.t, st.theta(), 2.0 * hg * st.e[0], 2.0 * hg * st.e[1]]);
        }
    }
    run.crossings = st.impacts;
    run
}
