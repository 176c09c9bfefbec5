//! The tilted body's geometry on a rigid bed (docs/model.md §10.1): the
//! axis `e3`, the contact on the rim, the lever `r = G - P` and the rate `Omega`
//! of the frame that tilts with the body but does not spin with it.

use nalgebra::Vector3;

use super::run::UPRIGHT;

/// The geometry at one tilt.
///
/// The tilt is the horizontal part `e = (e3x, e3y)` of the body's axis. The
/// contact is the rim point below the axis's lean, in the horizontal
/// direction `d` with `e = sigma d`: `sigma = sin(theta)` is the tilt, signed
/// relative to the reference `d0` of the current step, so that a step that
/// crosses upright continues the motion about the old contact analytically
/// (the planar model's side, `docs/dynamics.md`) and is then cut there.
/// Within [`UPRIGHT`] of upright the contact stays on that side and the
/// precession is zero: a crossing there is a plane's.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame {
    /// The body's axis, unit.
    pub e3: Vector3<f64>,
    /// `G - P`, m: from the contact to the centre of mass.
    pub r: Vector3<f64>,
}

impl Frame {
    /// The geometry of a body of base radius `radius` (m) and centre of mass
    /// `hg` (m) above the base, at the tilt `e`, with the step's reference
    /// contact direction `d0` (unit).
    #[inline]
    pub fn at(e: [f64; 2], d0: [f64; 2], radius: f64, hg: f64) -> Frame {
        let s2 = e[0] * e[0] + e[1] * e[1];
        let cos_theta = (1.0 - s2).sqrt();
        let e3 = Vector3::new(e[0], e[1], cos_theta);
        let (d, sigma) = if s2 > UPRIGHT * UPRIGHT {
            let s = s2.sqrt();
            let sigma = if e[0] * d0[0] + e[1] * d0[1] >= 0.0 {
                s
            } else {
                -s
            };
            ([e[0] / sigma, e[1] / sigma], sigma)
        } else {
            // within the crossing's tolerance of upright: the crossing of a
            // plane, whatever round-off left off it
            (d0, e[0] * d0[0] + e[1] * d0[1])
        };
        // e1 = (cos(theta) d, -sin(theta)): down the base plane toward the contact
        let e1 = Vector3::new(cos_theta * d[0], cos_theta * d[1], -sigma);
        Frame {
            e3,
            r: hg * e3 - radius * e1,
        }
    }

    /// `Omega = omega - (omega . e3) e3 + psi' cos(theta) e3`, rad/s: the rate of
    /// the frame `(e1, e2, e3)`, which turns with the precession `psi'` and the
    /// tilt rate but not with the spin; `r` is fixed in it, so `dr/dt = Omega x r`.
    /// `psi' = (e x de/dt)_z / |e|²` grows as `1/theta` when the tilt passes
    /// near upright off a plane (the contact runs round the rim).
    #[inline]
    pub fn frame_rate(&self, omega: &Vector3<f64>, de: [f64; 2]) -> Vector3<f64> {
        let e = [self.e3.x, self.e3.y];
        let s2 = e[0] * e[0] + e[1] * e[1];
        let psi_dot = if s2 > UPRIGHT * UPRIGHT {
            (e[0] * de[1] - e[1] * de[0]) / s2
        } else {
            0.0
        };
        omega - (omega.dot(&self.e3) - psi_dot * self.e3.z) * self.e3
    }

    /// Height of the centre of mass above the bed, m: `hg cos(theta) + R sin(theta)`.
    #[inline]
    pub fn height(&self) -> f64 {
        self.r.z
    }
}
