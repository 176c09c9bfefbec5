//! Output quantities at a state (docs/model.md §5): `theta''`, the contact,
//! the restoring moment and the forces of the support.

use super::eom::Eom;
use super::{GroundInput, Outputs, Simulator, State, VerticalInput};
use crate::interface::Regime;

impl Simulator {
    /// Outputs at `state` under ground acceleration `ag` (m/s²).
    ///
    /// A body at rest that this `ag` sets moving (see
    /// [`held_at_rest`](Self::held_at_rest)) gets the equation of motion's
    /// `theta''`, `Fx`, `Fz` at `theta = omega = 0` on the side `ag` pushes
    /// it to (the motion starts there); its contact outputs stay those at
    /// rest.
    ///
    /// The support forces (docs/model.md §5) follow from the velocity of G
    /// that the equation of motion implies, G turning about the interface
    /// resultant: `xG' = hg omega`, `zG' = s hW omega`, so
    /// `xG'' = hg theta'' + s hg' omega²`, `zG'' = s hW theta'' + hW' omega²`,
    /// `Fx = m (ag + xG'')`, `Fz = m (g + zG'')`. With `I = Ic + m (hg² +
    /// hW²)` these make the energy of a block on a moving support balance
    /// the work of `Fx`; for the rigid law they are G turning rigidly about
    /// the toe.
    pub fn outputs(&self, state: &State, ag: f64) -> Outputs {
        self.outputs_vertical(state, ag, 0.0)
    }

    /// [`outputs`](Self::outputs) under the vertical ground acceleration `av`
    /// too (docs/model.md §6.2): the contact at the apparent weight `N`,
    /// `MR = N hW(phi, N)`, `Fz = m (g + av + zG'')`; `av` held (see
    /// [`outputs_loaded`](Self::outputs_loaded)).
    pub fn outputs_vertical(&self, state: &State, ag: f64, av: f64) -> Outputs {
        self.outputs_loaded(state, ag, VerticalInput { av, dav: 0.0 })
    }

    /// [`outputs_vertical`](Self::outputs_vertical) under `av` rising at
    /// `dav` (m/s³) from the state's time: a flexible law's `theta''` in
    /// the power form of docs/model.md §6.2 has the term `(dI/dN) m dav
    /// omega / 2`, so it is the acceleration of a motion whose input goes
    /// on at that slope (the host's input derivative).
    pub fn outputs_loaded(&self, state: &State, ag: f64, v: VerticalInput) -> Outputs {
        let av = v.av;
        if !state.at_rest {
            return self.outputs_in_motion(state, ag, v);
        }
        let b = &self.model.body;
        // The contact of a body at rest is the whole base, whatever ag: the
        // contact outputs do not depend on ag (docs/model.md §5 declares
        // only angularAcceleration, Fx, Fz as depending on it).
        let c = self.model.interface.contact(0.0);
        let n = b.weight + b.mass * av;
        let rest = Outputs {
            theta_dd: 0.0,
            af: c.af,
            contact_length: c.contact_length,
            mr: 0.0,
            regime: c.regime,
            fx: b.mass * ag,
            fz: n,
            apparent_weight: n,
        };
        if self.held(ag, av) {
            return rest;
        }
        let start = self.outputs_in_motion(state, ag, v);
        Outputs {
            theta_dd: start.theta_dd,
            fx: start.fx,
            fz: start.fz,
            ..rest
        }
    }

    /// [`outputs`](Self::outputs) from the equation of motion at `state`.
    fn outputs_in_motion(&self, state: &State, ag: f64, v: VerticalInput) -> Outputs {
        let av = v.av;
        let m = &self.model;
        let b = &m.body;
        let side = self.side(state.theta, state.omega, ag);
        let eom = Eom::with_vertical(
            self,
            state.t,
            GroundInput {
                ag,
                ..Default::default()
            },
            v,
        );
        let n = eom.apparent_weight(state.t);
        let mut hint = state.a;
        let theta_dd = eom.accel(state.t, state.theta, state.omega, side, &mut hint);
        let phi = state.theta.abs();
        // rigid law in motion: the reaction is at the toe even at theta = 0
        let c = if eom.rigid {
            m.interface.contact(phi.max(f64::MIN_POSITIVE))
        } else if eom.vertical {
            m.contact_loaded(phi, n).0
        } else {
            self.contact(phi, state.a)
        };
        let l = m.levers(phi, &c);
        let w2 = state.omega * state.omega;
        let xg_dd = l.hg * theta_dd + side * l.dhg * w2;
        let zg_dd = side * l.hw * theta_dd + l.dhw * w2;
        Outputs {
            theta_dd,
            af: c.af,
            contact_length: c.contact_length,
            mr: n * l.hw,
            regime: if state.overturned {
                Regime::Overturned
            } else {
                c.regime
            },
            fx: b.mass * (ag + xg_dd),
            // av = 0: b.g + 0.0 is b.g, the same bits
            fz: b.mass * (b.g + av + zg_dd),
            apparent_weight: n,
        }
    }
}
