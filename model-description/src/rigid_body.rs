//! The table entries RockingBlock (`fmu-rocking`) and RoundBody
//! (`fmu-round-body`) share: the rigid body's section, mass model,
//! restitution and gravity parameters, the interface's law (`interface`,
//! `kn`, `fm`, `formulation`), the calculated parameters derived from them,
//! their units, enumeration types and codes, and the log categories.
//!
//! A variable's name, causality, unit and start are defined once here; where
//! its meaning differs between the two FMUs (the shape's items, the lumped
//! mass's inertias, the pivot being a toe or a rim point) the description is
//! a parameter. Value references and `depends_on` lists are each FMU's own,
//! set by its table entry in [`variables!`](crate::variables):
//! `MASS = 32 => { depends_on: D_WEIGHT, ..rigid_body::MASS }`.

use crate::schema::{
    BaseUnit, Causality, DisplayUnit, EnumItem, EnumType, Initial, LogCategory, Type, Variability,
    Variable,
};

/// Declares the value-reference constants (`vr`) and the variable table
/// (`VARIABLES`) of an FMU from one list; an entry may end with
/// `..base` to start from a shared definition instead of `Variable::DEFAULT`.
#[macro_export]
macro_rules! variables {
    (@base) => { $crate::Variable::DEFAULT };
    (@base $base:expr) => { $base };
    ($( $(#[$meta:meta])* $konst:ident = $vr:literal => { $($field:ident : $value:expr,)* $(.. $base:expr)? } )*) => {
        /// Value references, one constant per variable.
        pub mod vr {
            $( $(#[$meta])* pub const $konst: u32 = $vr; )*
        }
        /// The variables, in XML order (sorted by value reference).
        #[allow(clippy::needless_update)] // some entries set every field
        pub static VARIABLES: &[$crate::Variable] = &[
            $( $crate::Variable { vr: $vr, $($field: $value,)* ..$crate::variables!(@base $($base)?) }, )*
        ];
    };
}

/// A real of `unit` (displayed in `display_unit`) with no bounds.
pub const fn real(
    unit: Option<&'static str>,
    display_unit: Option<&'static str>,
    start: Option<f64>,
) -> Type {
    Type::Real {
        unit,
        display_unit,
        start,
        min: None,
        max: None,
    }
}

/// An enumeration of `declared_type` starting at the code `start`.
pub const fn enumeration(declared_type: &'static str, start: i32) -> Type {
    Type::Enumeration {
        declared_type,
        start: Some(start),
    }
}

/// A base unit of the SI exponents kg, m, s and rad.
pub const fn base(kg: i32, m: i32, s: i32, rad: i32) -> BaseUnit {
    BaseUnit {
        kg,
        m,
        s,
        rad,
        ..BaseUnit::ONE
    }
}

/// A display unit `name` = `factor` times the unit, no offset.
pub const fn du(name: &'static str, factor: f64) -> DisplayUnit {
    DisplayUnit {
        name,
        factor,
        offset: 0.0,
    }
}

/// An enumeration item.
pub const fn item(name: &'static str, value: i32, description: &'static str) -> EnumItem {
    EnumItem {
        name,
        value,
        description,
    }
}

/// Standard gravity for the display unit `g` (not the parameter `g`), m/s2.
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// The units both FMUs declare; each lists them in its own order.
pub mod units {
    use super::{base, du, STANDARD_GRAVITY};
    use crate::schema::{BaseUnit, Unit};

    pub const ONE: Unit = Unit {
        name: "1",
        base: BaseUnit::ONE,
        display: &[],
    };
    pub const M: Unit = Unit {
        name: "m",
        base: base(0, 1, 0, 0),
        display: &[du("mm", 1e3)],
    };
    pub const KG: Unit = Unit {
        name: "kg",
        base: base(1, 0, 0, 0),
        display: &[du("t", 1e-3)],
    };
    pub const KG_PER_M3: Unit = Unit {
        name: "kg/m3",
        base: base(1, -3, 0, 0),
        display: &[],
    };
    pub const KG_M2: Unit = Unit {
        name: "kg.m2",
        base: base(1, 2, 0, 0),
        display: &[du("t.m2", 1e-3)],
    };
    pub const N: Unit = Unit {
        name: "N",
        base: base(1, 1, -2, 0),
        display: &[du("kN", 1e-3), du("MN", 1e-6)],
    };
    pub const M_PER_S2: Unit = Unit {
        name: "m/s2",
        base: base(0, 1, -2, 0),
        display: &[du("g", 1.0 / STANDARD_GRAVITY)],
    };
    pub const RAD: Unit = Unit {
        name: "rad",
        base: base(0, 0, 0, 1),
        display: &[du("deg", 180.0 / std::f64::consts::PI)],
    };
    pub const PA: Unit = Unit {
        name: "Pa",
        base: base(1, -1, -2, 0),
        display: &[du("MPa", 1e-6)],
    };
    pub const PA_PER_M: Unit = Unit {
        name: "Pa/m",
        base: base(1, -2, -2, 0),
        display: &[du("MPa/m", 1e-6), du("GPa/m", 1e-9)],
    };
    pub const RAD_PER_S: Unit = Unit {
        name: "rad/s",
        base: base(0, 0, -1, 1),
        display: &[du("deg/s", 180.0 / std::f64::consts::PI)],
    };
}

/// Codes of the shared enumerations, as the binaries see them (RoundBody
/// keeps RockingBlock's shape codes).
pub mod enums {
    pub const SOLID_RECTANGLE: i32 = 1;
    pub const HOLLOW_RECTANGLE: i32 = 2;
    pub const SOLID_CIRCLE: i32 = 3;
    pub const HOLLOW_CIRCLE: i32 = 4;
    pub const PRISM: i32 = 1;
    pub const LUMPED: i32 = 2;
    pub const HOUSNER: i32 = 1;
    pub const GIVEN: i32 = 2;
    pub const RIGID: i32 = 1;
    pub const ELASTIC: i32 = 2;
    pub const ELASTO_PLASTIC: i32 = 3;
    pub const COSTA: i32 = 1;
    pub const SHIFTING_PIVOT: i32 = 2;
}

/// The round items of `ShapeKind`.
pub const SOLID_CIRCLE: EnumItem = item(
    "solidCircle",
    enums::SOLID_CIRCLE,
    "Solid circle of radius Ro",
);
pub const HOLLOW_CIRCLE: EnumItem = item(
    "hollowCircle",
    enums::HOLLOW_CIRCLE,
    "Concentric ring Ro, Ri",
);

/// `ShapeKind` with the FMU's `items`.
pub const fn shape_kind(description: &'static str, items: &'static [EnumItem]) -> EnumType {
    EnumType {
        name: "ShapeKind",
        description,
        items,
    }
}

/// `MassModelKind`; `lumped` says which quantities the lumped model gives.
pub const fn mass_model_kind(lumped: &'static str) -> [EnumItem; 2] {
    [
        item(
            "prism",
            enums::PRISM,
            "The section extruded to height H, density rho",
        ),
        item("lumped", enums::LUMPED, lumped),
    ]
}

/// The `MassModelKind` type of `items` ([`mass_model_kind`]).
pub const fn mass_model_type(items: &'static [EnumItem]) -> EnumType {
    EnumType {
        name: "MassModelKind",
        description: "How the body's mass is described",
        items,
    }
}

/// `RestitutionKind`'s two items, described by the FMU.
pub const fn restitution_kind(housner: &'static str, given: &'static str) -> [EnumItem; 2] {
    [
        item("housner", enums::HOUSNER, housner),
        item("given", enums::GIVEN, given),
    ]
}

/// The `RestitutionKind` type of `items` ([`restitution_kind`]).
pub const fn restitution_type(description: &'static str, items: &'static [EnumItem]) -> EnumType {
    EnumType {
        name: "RestitutionKind",
        description,
        items,
    }
}

/// `InterfaceLaw`: the bed's law under the base.
pub const INTERFACE_LAW: EnumType = EnumType {
    name: "InterfaceLaw",
    description: "Law of the base interface",
    items: &[
        item(
            "rigid",
            enums::RIGID,
            "Rigid contact (Housner): the reaction at the toe",
        ),
        item(
            "elastic",
            enums::ELASTIC,
            "Elastic no-tension Winkler bed of stiffness kn",
        ),
        item(
            "elastoPlastic",
            enums::ELASTO_PLASTIC,
            "Elastic no-tension, perfectly plastic at fm",
        ),
    ],
};

/// `FormulationKind`: the equation of motion on a flexible interface.
pub const FORMULATION_KIND: EnumType = EnumType {
    name: "FormulationKind",
    description: "Equation of motion",
    items: &[
        item(
            "costa",
            enums::COSTA,
            "The paper's Eq. 1 (Costa 2012), without the dI/dphi term",
        ),
        item(
            "shiftingPivot",
            enums::SHIFTING_PIVOT,
            "The paper's Eq. 9, Lagrangian, energy-consistent",
        ),
    ],
};

/// The log categories; `events` says which events `logEvents` reports.
pub const fn log_categories(events: &'static str) -> [LogCategory; 4] {
    [
        LogCategory {
            name: "logEvents",
            description: events,
        },
        LogCategory {
            name: "logStatusWarning",
            description: "Messages that accompany fmi2Warning and fmi2Discard",
        },
        LogCategory {
            name: "logStatusError",
            description: "Messages that accompany fmi2Error and fmi2Fatal",
        },
        LogCategory {
            name: "logAll",
            description: "Everything, including a trace of the FMI calls",
        },
    ]
}

/// A fixed parameter with an exact start.
const fn parameter(name: &'static str, description: &'static str, ty: Type) -> Variable {
    Variable {
        name,
        description,
        causality: Causality::Parameter,
        variability: Variability::Fixed,
        initial: Some(Initial::Exact),
        ty,
        ..Variable::DEFAULT
    }
}

/// A calculated parameter (its `depends_on` is the FMU's).
const fn calculated(name: &'static str, description: &'static str, ty: Type) -> Variable {
    Variable {
        name,
        description,
        causality: Causality::CalculatedParameter,
        variability: Variability::Fixed,
        initial: Some(Initial::Calculated),
        ty,
        ..Variable::DEFAULT
    }
}

/// `shape`, enumeration `ShapeKind` starting at `start`.
pub const fn shape(description: &'static str, start: i32) -> Variable {
    parameter("shape", description, enumeration("ShapeKind", start))
}

/// `Ro`, m.
pub const fn ro(description: &'static str) -> Variable {
    parameter("Ro", description, real(Some("m"), None, Some(0.5)))
}

/// `Ri`, m.
pub const fn ri(description: &'static str) -> Variable {
    parameter("Ri", description, real(Some("m"), None, Some(0.3)))
}

/// `massModel`, enumeration `MassModelKind` starting at prism.
pub const fn mass_model(description: &'static str) -> Variable {
    parameter(
        "massModel",
        description,
        enumeration("MassModelKind", enums::PRISM),
    )
}

/// `H`, m, starting at `start`.
pub const fn h(start: f64) -> Variable {
    parameter(
        "H",
        "Prism height (hG = H/2)",
        real(Some("m"), None, Some(start)),
    )
}

/// `rho`, kg/m3.
pub const RHO: Variable = parameter(
    "rho",
    "Prism density",
    real(Some("kg/m3"), None, Some(1800.0)),
);

/// `W`, N.
pub const W: Variable = parameter(
    "W",
    "Lumped weight",
    real(Some("N"), Some("kN"), Some(1.0e5)),
);

/// `hG`, m, starting at `start`.
pub const fn hg(description: &'static str, start: f64) -> Variable {
    parameter("hG", description, real(Some("m"), None, Some(start)))
}

/// `Ic`, kg.m2.
pub const fn ic(description: &'static str) -> Variable {
    parameter("Ic", description, real(Some("kg.m2"), None, Some(1.0e4)))
}

/// `interface`, enumeration `InterfaceLaw` starting at the code `start`
/// (RockingBlock's elastoPlastic; RoundBody's rigid, on which its Model
/// Exchange runs).
pub const fn interface(start: i32) -> Variable {
    parameter(
        "interface",
        "Interface law: rigid (Housner), elastic no-tension Winkler bed (kn), elastoPlastic (kn, crushing at fm)",
        enumeration("InterfaceLaw", start),
    )
}

/// `kn`, Pa/m.
pub const KN: Variable = parameter(
    "kn",
    "Normal stiffness of the interface (stress per unit closure)",
    real(Some("Pa/m"), Some("MPa/m"), Some(5.0e9)),
);

/// `fm`, Pa.
pub const FM: Variable = parameter(
    "fm",
    "Compressive strength of the interface (inf: no crushing)",
    real(Some("Pa"), Some("MPa"), Some(5.0e6)),
);

/// `formulation`, enumeration `FormulationKind` starting at shiftingPivot.
pub const FORMULATION: Variable = parameter(
    "formulation",
    "Equation of motion: costa (the paper's Eq. 1) or shiftingPivot (Eq. 9, Lagrangian, energy-consistent)",
    enumeration("FormulationKind", enums::SHIFTING_PIVOT),
);

/// `restitution`, enumeration `RestitutionKind` starting at housner.
pub const fn restitution(description: &'static str) -> Variable {
    parameter(
        "restitution",
        description,
        enumeration("RestitutionKind", enums::HOUSNER),
    )
}

/// `eta`, dimensionless (`unit` `Some("1")` or no unit attribute).
pub const fn eta(unit: Option<&'static str>) -> Variable {
    parameter(
        "eta",
        "Coefficient of restitution used when restitution = given (0 <= eta <= 1)",
        real(unit, None, Some(0.9)),
    )
}

/// `g`, m/s2.
pub const G: Variable = parameter(
    "g",
    "Gravitational acceleration",
    real(Some("m/s2"), None, Some(9.81)),
);

/// `mass`, kg.
pub const MASS: Variable = calculated("mass", "Mass m = W/g", real(Some("kg"), None, None));

/// `weight`, N.
pub const WEIGHT: Variable = calculated(
    "weight",
    "Weight W (rho g A H for the prism)",
    real(Some("N"), Some("kN"), None),
);

/// `R0`, m.
pub const fn r0(description: &'static str) -> Variable {
    calculated("R0", description, real(Some("m"), None, None))
}

/// `alpha`, rad.
pub const fn alpha(description: &'static str) -> Variable {
    calculated("alpha", description, real(Some("rad"), Some("deg"), None))
}

/// `IO`, kg.m2.
pub const fn io(description: &'static str) -> Variable {
    calculated("IO", description, real(Some("kg.m2"), None, None))
}

/// `etaHousner`, dimensionless.
pub const fn eta_housner(description: &'static str) -> Variable {
    calculated("etaHousner", description, real(Some("1"), None, None))
}

/// `thetaOv`, rad.
pub const fn theta_ov(description: &'static str) -> Variable {
    calculated("thetaOv", description, real(Some("rad"), Some("deg"), None))
}
