//! What `impacts` and `zeroCrossings` count (docs/model.md §5): every zero
//! crossing of `theta` applies the restitution rule and is counted in
//! `zero_crossings`; an impact is a return to `theta = 0` after an uplift,
//! a crossing after which `|theta|` had exceeded `thetaJo` (the joint had
//! opened). The expected counts come from the sampled trajectory itself
//! (sign changes and peaks of `theta`), not from the counters.

mod support;

use rocking::dynamics::{GroundInput, Simulator, State};
use rocking::model::{LawKind, Restitution};
use rocking::{Model, Params};
use support::{moment_breaks, potential};

/// The default 0.5 m x 1 m x 2.5 m block on an elastic joint of stiffness `kn`.
fn elastic(kn: f64, eta: Option<f64>) -> Model {
    Params {
        interface: LawKind::Elastic,
        kn,
        restitution: if eta.is_some() {
            Restitution::Given
        } else {
            Restitution::Housner
        },
        eta: eta.unwrap_or(1.0),
        ..Params::default()
    }
    .build()
    .unwrap()
}

/// States every `dt` up to `t_end` under `ag(t)` (linear within each call).
fn sample(sim: &Simulator, st: State, ag: impl Fn(f64) -> f64, dt: f64, t_end: f64) -> Vec<State> {
    let mut st = st;
    let mut out = vec![st];
    let n = (t_end / dt).round() as usize;
    for k in 0..n {
        let (t0, t1) = (k as f64 * dt, (k + 1) as f64 * dt);
        let input = GroundInput {
            ag: ag(t0),
            dag: (ag(t1) - ag(t0)) / dt,
        };
        sim.advance(&mut st, t1, input);
        assert!(!st.overturned);
        out.push(st);
    }
    out
}

/// The half-cycles of the sampled motion, each ended by a sign change of
/// `theta` (or by rest at `theta = 0`): their peaks `max |theta|` over the
/// samples. The last, unfinished one is left out.
fn completed_half_cycle_peaks(samples: &[State]) -> Vec<f64> {
    let mut peaks = Vec::new();
    let mut peak = 0.0f64;
    let mut sign = 0.0;
    for s in samples {
        let sg = if s.theta > 0.0 {
            1.0
        } else if s.theta < 0.0 {
            -1.0
        } else {
            0.0
        };
        if sg != 0.0 && sign != 0.0 && sg != sign {
            peaks.push(peak);
            peak = 0.0;
        }
        if sg != 0.0 {
            sign = sg;
        }
        peak = peak.max(s.theta.abs());
    }
    // a body that settled at theta = 0 ended its last half-cycle there
    let last = samples.last().unwrap();
    if last.theta == 0.0 && last.omega == 0.0 && peak > 0.0 {
        peaks.push(peak);
    }
    peaks
}

#[test]
fn a_stiff_joint_vibrating_in_full_contact_crosses_zero_without_impacts() {
    // kn = 5e9 Pa/m: thetaJo = 3.5e-5 rad, full-contact frequency 17 Hz.
    // A 5 Hz ground motion of 0.2 m/s² drives theta to about 1e-5 rad
    // either side of zero: it crosses zero every half period and the joint
    // never opens.
    let m = elastic(5e9, None);
    let jo = m.interface.theta_jo();
    let sim = Simulator::new(m, 1e-9);
    let ag = |t: f64| 0.2 * (2.0 * std::f64::consts::PI * 5.0 * t).sin();
    let samples = sample(&sim, sim.initial_state(0.0, 0.0), ag, 1e-3, 2.0);
    let peak = samples.iter().map(|s| s.theta.abs()).fold(0.0, f64::max);
    let last = samples.last().unwrap();
    let sign_changes = completed_half_cycle_peaks(&samples).len() as u64;
    eprintln!(
        "thetaJo {jo:.2e} rad, max |theta| {peak:.2e} rad: {} zero crossings ({sign_changes} sign changes in the samples), {} impacts",
        last.zero_crossings, last.impacts
    );
    // 1 ms samples resolve the 17 Hz vibration to 2 % of its amplitude
    assert!(peak < 0.5 * jo, "the joint must stay closed: {peak:e}");
    assert!(sign_changes >= 10);
    assert_eq!(last.zero_crossings, sign_changes);
    assert_eq!(last.impacts, 0);
}

#[test]
fn impacts_count_the_half_cycles_whose_peak_exceeds_thetajo() {
    // kn = 5e7 Pa/m: thetaJo = 3.5e-3 rad. Released at 0.03 rad with
    // eta = 0.5 the rocking half-cycles lose three quarters of their energy
    // at each crossing: a few rock beyond thetaJo, then the block vibrates
    // in full contact (a half period of 0.3 s) until it settles.
    let m = elastic(5e7, Some(0.5));
    let jo = m.interface.theta_jo();
    let sim = Simulator::new(m, 1e-10);
    let samples = sample(&sim, sim.initial_state(0.03, 0.0), |_| 0.0, 2e-4, 12.0);
    let peaks = completed_half_cycle_peaks(&samples);
    let last = samples.last().unwrap();
    // the samples' peaks are below the true ones by at most
    // theta'' dt²/2 / theta ~ 1e-5 relative: clear of thetaJo by far more
    for p in &peaks {
        assert!(
            (p / jo - 1.0).abs() > 1e-3,
            "a peak {p:e} too close to thetaJo {jo:e} to decide"
        );
    }
    let opened = peaks.iter().filter(|&&p| p > jo).count() as u64;
    eprintln!(
        "thetaJo {jo:.2e} rad, half-cycle peaks {:?}: {} zero crossings, {} impacts, {opened} peaks above thetaJo",
        peaks.iter().map(|p| format!("{p:.2e}")).collect::<Vec<_>>(),
        last.zero_crossings,
        last.impacts
    );
    assert!(opened >= 2 && (peaks.len() as u64) > opened + 5);
    assert_eq!(last.zero_crossings, peaks.len() as u64);
    assert_eq!(last.impacts, opened);
}

#[test]
fn a_half_cycle_peaking_just_above_thetajo_is_an_impact_and_just_below_is_not() {
    // Launched from theta = 0 with the omega0 whose energy reaches the peak
    // phi: I(0) omega0²/2 = ∫_0^phi W hW (shiftingPivot conserves energy
    // without ground motion). With phi = (1 +- 1e-4) thetaJo the peak lies
    // inside a step (between two step ends on thetaJo, where the steps are
    // cut at the kink, or inside a long stiff step): only the turning point
    // search sees it.
    for kn in [5e7, 5e9] {
        let m = elastic(kn, None);
        let b = m.body;
        let jo = m.interface.theta_jo();
        let breaks = moment_breaks(&m, m.theta_ov);
        let i0 = b.ic + b.mass * b.hg * b.hg;
        for (ratio, expected) in [(1.0 + 1e-4, 1), (1.0 - 1e-4, 0)] {
            let v = potential(&m, ratio * jo, &breaks);
            let omega0 = (2.0 * v / i0).sqrt();
            let sim = Simulator::new(m, 1e-10);
            let mut st = sim.initial_state(0.0, omega0);
            let mut steps = 0;
            while st.zero_crossings == 0 {
                let t_end = st.t + 1.0;
                steps += sim
                    .advance_to_event(&mut st, t_end, GroundInput::default())
                    .stats
                    .steps;
            }
            eprintln!(
                "kn {kn:e}: peak {ratio} thetaJo: {} impacts after {steps} steps",
                st.impacts
            );
            assert_eq!(st.zero_crossings, 1);
            assert_eq!(st.impacts, expected, "kn {kn:e}, peak {ratio} thetaJo");
        }
    }
}
