//! The ground motion of the Model Exchange against co-simulation
//! comparisons (`tests/continuous.rs`, and `fmu-rocking/tests/model_exchange.rs`,
//! which includes this file with `#[path]`).

/// A one-sine pulse of amplitude `a` (m/s²) and period `tp` (s), sampled on
/// a grid of `dt` (s) and linear in between: what a co-simulation host
/// feeds, and so what both hosts see. A time on the grid (to 1e-9 of a
/// step) starts its own interval.
pub fn pulse(a: f64, tp: f64, dt: f64) -> impl Fn(f64) -> f64 {
    let s = move |t: f64| {
        if t < tp {
            a * (2.0 * std::f64::consts::PI * t / tp).sin()
        } else {
            0.0
        }
    };
    move |t: f64| {
        let k = (t / dt + 1e-9).floor();
        let (t0, t1) = (k * dt, (k + 1.0) * dt);
        s(t0) + (s(t1) - s(t0)) * (t - t0) / dt
    }
}
