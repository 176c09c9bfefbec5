//! The parameters every rigid-body FMU shares (`model_description::rigid_body`),
//! mapped to `rocking::Params` by their names, independently of the FMU's
//! own binding.

use fmi2_export::model_description::rigid_body::enums::*;
use rocking::model::{MassKind, ShapeKind};
use rocking::{Params, Restitution};

use crate::{Model, Stored};

/// The shapes of `model_description::rigid_body`, by code.
pub const SHAPES: [(i32, ShapeKind); 4] = [
    (SOLID_RECTANGLE, ShapeKind::SolidRectangle),
    (HOLLOW_RECTANGLE, ShapeKind::HollowRectangle),
    (SOLID_CIRCLE, ShapeKind::SolidCircle),
    (HOLLOW_CIRCLE, ShapeKind::HollowCircle),
];

/// `base` with the shared parameters (shape, Ro, Ri, massModel, H, rho, W,
/// hG, Ic, restitution, eta, g) as the driver stored them; `None` for a
/// code that is no item of its enumeration or a shape the FMU does not
/// have (`shapes`, a part of [`SHAPES`]).
pub fn rigid_body_params<M: Model>(
    stored: &Stored,
    shapes: &[(i32, ShapeKind)],
    base: Params,
) -> Option<Params> {
    let vr = |name: &str| {
        M::VARIABLES
            .iter()
            .find(|v| v.name == name)
            .unwrap_or_else(|| panic!("the FMU has no variable {name}"))
            .vr as usize
    };
    let r = |name: &str| stored.real[vr(name)];
    let i = |name: &str| stored.int[vr(name)];
    let shape = i("shape");
    Some(Params {
        shape: shapes.iter().find(|(code, _)| *code == shape)?.1,
        ro: r("Ro"),
        ri: r("Ri"),
        mass_model: match i("massModel") {
            PRISM => MassKind::Prism,
            LUMPED => MassKind::Lumped,
            _ => return None,
        },
        h: r("H"),
        rho: r("rho"),
        w: r("W"),
        hg: r("hG"),
        ic: r("Ic"),
        restitution: match i("restitution") {
            HOUSNER => Restitution::Housner,
            GIVEN => Restitution::Given,
            _ => return None,
        },
        eta: r("eta"),
        g: r("g"),
        ..base
    })
}
