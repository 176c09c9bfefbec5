//! The round body of the spatial tests: a masonry drum on the rigid bed,
//! and a ground motion that rocks it hard without overturning it.

use rocking::model::{LawKind, MassKind, Restitution, ShapeKind};
use rocking::Params;

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
