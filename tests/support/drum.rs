//! The round body of the spatial tests: a masonry drum on the rigid bed or
//! on a flexible one, and ground motions that rock it hard without
//! overturning it, sampled every [`DT`].

use rocking::model::{Formulation, LawKind, MassKind, Restitution, ShapeKind};
use rocking::Params;

/// The inputs' sampling, s: linear in between.
pub const DT: f64 = 0.01;

/// A drum of radius 0.5 m and height 3 m (tan alpha = 1/3), solid or a
/// ring of inner radius 0.35 m, prism mass model, 2000 kg/m³, on the
/// rigid bed.
pub fn drum(restitution: Restitution, hollow: bool) -> Params {
    Params {
        shape: if hollow {
            ShapeKind::HollowCircle
        } else {
            ShapeKind::SolidCircle
        },
        ro: 0.5,
        ri: 0.35,
        mass_model: MassKind::Prism,
        h: 3.0,
        rho: 2000.0,
        interface: LawKind::Rigid,
        restitution,
        eta: 0.8,
        ..Params::default()
    }
}

/// 1.6 times the drum's uplift threshold `g tan(alpha)` at 1.3 Hz, decaying
/// at 0.25 /s: m/s² at `t` s.
pub fn pulse_train(t: f64) -> f64 {
    let g_tan_alpha = 9.81 / 3.0;
    1.6 * g_tan_alpha * (2.0 * std::f64::consts::PI * 1.3 * t).sin() * (-0.25 * t).exp()
}

/// The drum of [`drum`] on a bed of `kn = 1e8 Pa/m` (`thetaJo` 1.2e-3
/// rad), crushing at `fm = 0.3 MPa` if `crushing`.
pub fn on_bed(crushing: bool, formulation: Formulation) -> Params {
    Params {
        interface: if crushing {
            LawKind::ElastoPlastic
        } else {
            LawKind::Elastic
        },
        kn: 1e8,
        fm: 3e5,
        formulation,
        ..drum(Restitution::Housner, false)
    }
}

/// A vertical input of 2 m/s² at 3.1 Hz: m/s² (up) at `t` s.
pub fn vertical(t: f64) -> f64 {
    2.0 * (2.0 * std::f64::consts::PI * 3.1 * t).sin()
}
