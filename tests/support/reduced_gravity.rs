//! A body under a constant vertical input `av` against the same body under
//! gravity `g + av` without one: the same apparent weight, so the same
//! motion (docs/model.md §6.1), the second with the fixed kinks of `av = 0`.

use rocking::dynamics::{GroundInput, Simulator, VerticalInput};
use rocking::Params;

/// What the two free-rocking runs of [`rock_both`] did.
pub struct Rocked {
    /// Impacts of each (equal at every one: asserted).
    pub impacts: u64,
    /// The largest difference of their impact times, s.
    pub max_dt: f64,
    /// The work of each (steps, rejected steps, crossings): under `av`,
    /// under `g + av`.
    pub work_av: u64,
    pub work_g: u64,
}

impl Rocked {
    /// The two runs rocked alike: at least 3 impacts, their times within
    /// 1e-7 s, the run under `av` at most `work_ratio` times the other's
    /// work. `what` names the case in the messages.
    pub fn assert_alike(&self, what: &str, work_ratio: f64) {
        assert!(self.impacts >= 3, "{what}: {} impacts", self.impacts);
        assert!(
            self.max_dt <= 1e-7,
            "{what}: impacts {} s apart",
            self.max_dt
        );
        assert!(
            (self.work_av as f64) <= work_ratio * self.work_g as f64,
            "{what}: {} steps under av, {} under g'",
            self.work_av,
            self.work_g
        );
    }
}

/// Free rocking from `theta0` (rad) until 6 impacts, rest or overturning,
/// event to event at `rtol`, of `params(g + av)` and of `params(g)` under
/// `av` (m/s²).
pub fn rock_both(
    params: &dyn Fn(f64) -> Params,
    g: f64,
    av: f64,
    theta0: f64,
    rtol: f64,
) -> Rocked {
    let shifted = Simulator::new(params(g + av).build().unwrap(), rtol);
    let vertical = Simulator::new(params(g).build().unwrap(), rtol);
    let (mut a, mut b) = (
        shifted.initial_state(theta0, 0.0),
        vertical.initial_state(theta0, 0.0),
    );
    let mut r = Rocked {
        impacts: 0,
        max_dt: 0.0,
        work_av: 0,
        work_g: 0,
    };
    while a.impacts < 6 && !a.at_rest && !a.overturned {
        let ea = shifted.advance_to_event(&mut a, 100.0, GroundInput::default());
        let eb = vertical.advance_to_event_vertical(
            &mut b,
            100.0,
            GroundInput::default(),
            VerticalInput { av, dav: 0.0 },
        );
        r.work_g += ea.work();
        r.work_av += eb.work();
        if a.impacts > r.impacts {
            r.impacts = a.impacts;
            assert_eq!(b.impacts, r.impacts, "av {av}: impacts at t = {}", a.t);
            r.max_dt = r.max_dt.max((a.t - b.t).abs());
        }
    }
    r
}
