//! Rotated inputs for the round body in space: its response to a horizontal
//! input turned by an azimuth is the response to the input, turned (the
//! body is axisymmetric), which tests/spatial.rs checks on the rigid bed
//! and tests/spatial_flexible.rs on the flexible one.

use rocking::dynamics::VerticalInput;
use rocking::spatial::{PlanInput, Spatial, SpatialState};

use super::drum::DT;

/// Rotate a horizontal vector by `beta` (rad).
pub fn rot(v: [f64; 2], beta: f64) -> [f64; 2] {
    let (s, c) = beta.sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

/// The horizontal input (both components) and the vertical one, m/s² at `t` s.
pub type Inputs<'a> = (&'a dyn Fn(f64) -> [f64; 2], &'a dyn Fn(f64) -> f64);

/// Run `spatial` from `st` under `ag(t)` (both components) rotated by
/// `beta` and `av(t)`, sampled every `DT`.
pub fn run_rotated(
    spatial: &Spatial,
    mut st: SpatialState,
    (ag, av): Inputs,
    beta: f64,
    t_end: f64,
) -> Vec<SpatialState> {
    let n = (t_end / DT).round() as usize;
    let mut out = vec![];
    for k in 0..n {
        let (t0, t1) = (k as f64 * DT, (k + 1) as f64 * DT);
        let (a0, a1) = (rot(ag(t0), beta), rot(ag(t1), beta));
        let h = PlanInput {
            a: a0,
            da: [(a1[0] - a0[0]) / DT, (a1[1] - a0[1]) / DT],
        };
        let v = VerticalInput {
            av: av(t0),
            dav: (av(t1) - av(t0)) / DT,
        };
        spatial.advance(&mut st, t1, h, v);
        out.push(st);
    }
    out
}

/// `turned`, the run under the input rotated by `beta` (rad), is `base`
/// rotated: the same impacts at every sample, the tilt's direction and
/// the horizontal angular velocity rotated, the vertical one the same,
/// within 1e-9; and `base` rocks (peak tilt above 0.05 rad).
pub fn assert_rotates(name: &str, beta: f64, base: &[SpatialState], turned: &[SpatialState]) {
    let mut worst = 0.0f64;
    for (a, b) in base.iter().zip(turned) {
        let e = rot(a.e, beta);
        let w = rot([a.omega[0], a.omega[1]], beta);
        worst = worst
            .max((e[0] - b.e[0]).abs() + (e[1] - b.e[1]).abs())
            .max((w[0] - b.omega[0]).abs() + (w[1] - b.omega[1]).abs())
            .max((a.omega[2] - b.omega[2]).abs());
        assert_eq!(a.impacts, b.impacts, "{name}, beta {beta}, t = {}", a.t);
    }
    let peak = base.iter().map(|s| s.theta()).fold(0.0, f64::max);
    eprintln!(
        "{name} beta {beta}: worst {worst:.2e}, peak tilt {peak:.3} rad, impacts {}",
        base.last().unwrap().impacts
    );
    assert!(peak > 0.05);
    assert!(worst <= 1e-9, "{name}, beta {beta}: {worst:e}");
}
