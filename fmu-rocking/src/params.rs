//! The FMU's parameters and start values as the physics' [`Params`]: one
//! table, [`FIELDS`], read by the slave (from the stored values) and by the
//! `run_direct` binary (from `NAME=VALUE` arguments).

use fmi2_export::model_description::BaseType;
use rocking::model::{LawKind, MassKind, ShapeKind};
use rocking::{Formulation, Params, Restitution, RestraintKind};

use crate::description::{enums::*, vr, ROCKING_BLOCK};

/// The physics' enumerations by FMU enumeration value (the items of
/// `description::TYPES`).
pub const SHAPES: &[(i32, ShapeKind)] = &[
    (SOLID_RECTANGLE, ShapeKind::SolidRectangle),
    (HOLLOW_RECTANGLE, ShapeKind::HollowRectangle),
    (SOLID_CIRCLE, ShapeKind::SolidCircle),
    (HOLLOW_CIRCLE, ShapeKind::HollowCircle),
];
pub const MASS_MODELS: &[(i32, MassKind)] = &[(PRISM, MassKind::Prism), (LUMPED, MassKind::Lumped)];
pub const INTERFACES: &[(i32, LawKind)] = &[
    (RIGID, LawKind::Rigid),
    (ELASTIC, LawKind::Elastic),
    (ELASTO_PLASTIC, LawKind::ElastoPlastic),
];
pub const FORMULATIONS: &[(i32, Formulation)] = &[
    (COSTA, Formulation::Costa),
    (SHIFTING_PIVOT, Formulation::ShiftingPivot),
];
pub const RESTITUTIONS: &[(i32, Restitution)] =
    &[(HOUSNER, Restitution::Housner), (GIVEN, Restitution::Given)];
pub const RESTRAINTS: &[(i32, RestraintKind)] = &[
    (NONE, RestraintKind::None),
    (ONE_SIDED, RestraintKind::OneSided),
];

/// The physics value of the enumeration value `x`, if it is an item.
fn item<T: Copy>(table: &[(i32, T)], x: i32) -> Option<T> {
    table.iter().find(|(v, _)| *v == x).map(|(_, t)| *t)
}

/// How a variable sets its field of [`Params`].
#[derive(Clone, Copy)]
pub enum Field {
    Real(fn(&mut Params, f64)),
    Integer(fn(&mut Params, i32)),
    /// An enumeration: `None` if the value is no item.
    Enumeration(fn(&mut Params, i32) -> Option<()>),
}

/// The [`Field`] that sets `Params::$f`: a Real, or an enumeration of
/// the items `$items`.
macro_rules! field {
    ($f:ident) => {
        Field::Real(|p, x| p.$f = x)
    };
    (integer $f:ident) => {
        Field::Integer(|p, x| p.$f = x)
    };
    ($f:ident in $items:ident) => {
        Field::Enumeration(|p, x| item($items, x).map(|v| p.$f = v))
    };
}

/// Every field of [`Params`], by the value reference of its variable, in the
/// order of `Params`.
pub static FIELDS: &[(u32, Field)] = &[
    (vr::SHAPE, field!(shape in SHAPES)),
    (vr::B, field!(b)),
    (vr::L, field!(l)),
    (vr::T, field!(t)),
    (vr::RO, field!(ro)),
    (vr::RI, field!(ri)),
    (vr::MASS_MODEL, field!(mass_model in MASS_MODELS)),
    (vr::H, field!(h)),
    (vr::RHO, field!(rho)),
    (vr::W, field!(w)),
    (vr::HG, field!(hg)),
    (vr::IC, field!(ic)),
    (vr::INTERFACE, field!(interface in INTERFACES)),
    (vr::KN, field!(kn)),
    (vr::FM, field!(fm)),
    (vr::FORMULATION, field!(formulation in FORMULATIONS)),
    (vr::RESTITUTION, field!(restitution in RESTITUTIONS)),
    (vr::ETA, field!(eta)),
    (vr::G, field!(g)),
    (vr::THETA, field!(theta0)),
    (vr::OMEGA, field!(omega0)),
    (vr::RESTRAINT, field!(restraint in RESTRAINTS)),
    (vr::SIDE, field!(integer side)),
    (vr::E_RESTRAINT, field!(e_restraint)),
];

/// The name of the variable `vr` of the type of `field`.
pub fn name(vr: u32, field: Field) -> &'static str {
    let base = match field {
        Field::Real(_) => BaseType::Real,
        Field::Enumeration(_) | Field::Integer(_) => BaseType::Integer,
    };
    ROCKING_BLOCK
        .by_vr(base, vr)
        .expect("a variable of the table")
        .1
        .name
}

/// Parameters of the run, not of the body (the integrator's work limit,
/// the sliding check's friction coefficient): read by the slave itself, not
/// mapped to `Params`.
pub const RUN: &[u32] = &[vr::MAX_STEPS, vr::MU];

/// The field the variable `name` sets, if it is a parameter or start value.
pub fn field(name: &str) -> Option<(u32, Field)> {
    let v = ROCKING_BLOCK.variable(name)?;
    FIELDS.iter().copied().find(|(r, _)| *r == v.vr)
}

/// The physics parameters from the values of the variables: `real(vr)` and
/// `integer(vr)` read one; `Err` names an enumeration value that is no item.
pub fn params(real: impl Fn(u32) -> f64, integer: impl Fn(u32) -> i32) -> Result<Params, String> {
    let mut p = Params::default();
    for &(vr, f) in FIELDS {
        match f {
            Field::Real(set) => set(&mut p, real(vr)),
            Field::Integer(set) => set(&mut p, integer(vr)),
            Field::Enumeration(set) => {
                let x = integer(vr);
                set(&mut p, x).ok_or_else(|| {
                    format!("{} = {x}: not an item of its enumeration", name(vr, f))
                })?
            }
        }
    }
    Ok(p)
}

#[cfg(test)]
mod tests {
    use super::*;
    use fmi2_export::model_description::{Causality, Type};

    /// Every parameter and start value of the table has a field, once, and
    /// every enumeration item of the table maps to a physics value.
    #[test]
    fn the_table_and_the_fields_agree() {
        let mut vrs: Vec<u32> = FIELDS.iter().map(|(r, _)| *r).collect();
        vrs.sort();
        vrs.dedup();
        assert_eq!(vrs.len(), FIELDS.len(), "a variable set twice");
        for v in ROCKING_BLOCK.variables {
            let settable = (v.causality == Causality::Parameter
                || (v.causality != Causality::Input
                    && v.initial == Some(fmi2_export::model_description::Initial::Exact)))
                && !RUN.contains(&v.vr);
            let has = field(v.name).is_some();
            assert_eq!(settable, has, "{}", v.name);
            if let (true, Type::Enumeration { declared_type, .. }) = (has, v.ty) {
                let (_, f) = field(v.name).unwrap();
                let Field::Enumeration(set) = f else {
                    panic!("{}", v.name)
                };
                let t = ROCKING_BLOCK.enum_type(declared_type).unwrap();
                for i in t.items {
                    assert!(
                        set(&mut Params::default(), i.value).is_some(),
                        "{} = {}",
                        v.name,
                        i.name
                    );
                }
                assert!(set(&mut Params::default(), 0).is_none(), "{}", v.name);
            }
        }
    }
}
