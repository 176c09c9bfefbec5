//! The RoundBody FMU: the one definition of its variables
//! (docs/round-body.md), units, enumeration types, capabilities and default
//! experiment.
//!
//! The value references the binary uses ([`vr`]), the `modelDescription.xml`
//! and the variable table of `documentation/index.html` all come from here.
//! Names shared with RockingBlock (`shape`, `Ro`, `massModel`, `Fx`,
//! `frictionDemand`, ...) mean the same there and here.

use model_description::common;
use model_description::*;

/// Relative tolerance of the integrator when the master gives none
/// (`DefaultExperiment/@tolerance`), as RockingBlock's.
pub const DEFAULT_TOLERANCE: f64 = 1e-9;

/// Declares the value-reference constants ([`vr`]) and the variable table
/// ([`VARIABLES`]) from one list.
macro_rules! variables {
    ($( $(#[$meta:meta])* $konst:ident = $vr:literal => { $($field:ident : $value:expr),* $(,)? } )*) => {
        /// Value references, one constant per variable.
        pub mod vr {
            $( $(#[$meta])* pub const $konst: u32 = $vr; )*
        }
        /// The variables, in XML order (sorted by value reference).
        #[allow(clippy::needless_update)] // some entries set every field
        pub static VARIABLES: &[Variable] = &[
            $( Variable { vr: $vr, $($field: $value,)* ..Variable::DEFAULT }, )*
        ];
    };
}

const fn real(
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

const fn enumeration(declared_type: &'static str, start: i32) -> Type {
    Type::Enumeration {
        declared_type,
        start: Some(start),
    }
}

use Causality::{CalculatedParameter as CalcParam, Input, Output, Parameter};
use Initial::{Calculated, Exact};
use Variability::{Continuous, Discrete, Fixed};

// Dependencies at initialization (ModelStructure/InitialUnknowns); their
// inputs are the output's dependencies in ModelStructure/Outputs.
const D_WEIGHT: &[&str] = &["shape", "Ro", "Ri", "massModel", "H", "rho", "W", "g"];
const D_LEVER: &[&str] = &["shape", "Ro", "massModel", "H", "hG"];
const D_INERTIA: &[&str] = &[
    "shape",
    "Ro",
    "Ri",
    "massModel",
    "H",
    "rho",
    "W",
    "hG",
    "Ic",
    "g",
];
const D_THETA_ALPHA: &[&str] = &["shape", "Ro", "massModel", "H", "hG", "theta0"];
const D_LEAN: &[&str] = &["theta0", "psi0"];
const D_POSITION: &[&str] = &["shape", "Ro", "massModel", "H", "hG", "theta0", "psi0"];
const D_REGIME: &[&str] = &["theta0", "omegaX0", "omegaY0", "omegaZ0"];
const D_DYNAMIC: &[&str] = &[
    "shape",
    "Ro",
    "Ri",
    "massModel",
    "H",
    "rho",
    "W",
    "hG",
    "Ic",
    "IcAxial",
    "g",
    "theta0",
    "psi0",
    "omegaX0",
    "omegaY0",
    "omegaZ0",
    "agx",
    "agy",
    "av",
];

variables! {
    /// `shape` (enumeration `ShapeKind`, its round items only).
    SHAPE = 0 => {
        name: "shape",
        description: "Base section: solidCircle (Ro) or hollowCircle (Ro, Ri); RockingBlock's codes (its rectangles are no body of revolution)",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: enumeration("ShapeKind", 3),
    }
    RO = 1 => {
        name: "Ro",
        description: "Outer radius of the base (base depth D = 2 Ro), > 0",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: real(Some("m"), None, Some(0.5)),
    }
    RI = 2 => {
        name: "Ri",
        description: "Inner radius of the hollow circle (0 < Ri < Ro), concentric",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: real(Some("m"), None, Some(0.3)),
    }
    MASS_MODEL = 3 => {
        name: "massModel",
        description: "Mass model: prism (the section extruded to height H with density rho) or lumped (W, hG, Ic and IcAxial given)",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: enumeration("MassModelKind", 1),
    }
    H = 4 => {
        name: "H",
        description: "Prism height (hG = H/2)",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: real(Some("m"), None, Some(3.0)),
    }
    RHO = 5 => {
        name: "rho",
        description: "Prism density",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: real(Some("kg/m3"), None, Some(1800.0)),
    }
    W = 6 => {
        name: "W",
        description: "Lumped weight",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: real(Some("N"), Some("kN"), Some(1.0e5)),
    }
    HG = 7 => {
        name: "hG",
        description: "Lumped height of the centre of mass above the base, on the axis",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: real(Some("m"), None, Some(1.5)),
    }
    IC = 8 => {
        name: "Ic",
        description: "Lumped inertia about a horizontal axis through the centre of mass",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: real(Some("kg.m2"), None, Some(1.0e4)),
    }
    IC_AXIAL = 9 => {
        name: "IcAxial",
        description: "Lumped inertia about the body's axis (massModel = lumped only; a prism's is m (Ro^2 + Ri^2)/2, computed), > 0",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: real(Some("kg.m2"), None, Some(1.0e4)),
    }
    RESTITUTION = 10 => {
        name: "restitution",
        description: "Restitution at impacts: housner (the planar limit is Housner's 1 - 2 m b^2/IO; in space the angular momentum about the striking rim point is kept) or given (the planar limit is eta)",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: enumeration("RestitutionKind", 1),
    }
    ETA = 11 => {
        name: "eta",
        description: "Coefficient of restitution used when restitution = given (0 <= eta <= 1)",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: real(Some("1"), None, Some(0.9)),
    }
    G = 12 => {
        name: "g",
        description: "Gravitational acceleration",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: real(Some("m/s2"), None, Some(9.81)),
    }
    THETA0 = 13 => {
        name: "theta0",
        description: "Initial tilt of the axis from the vertical about the rim (|theta0| < alpha; theta0 < 0 leans toward psi0 + pi)",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: real(Some("rad"), Some("deg"), Some(0.0)),
    }
    PSI0 = 14 => {
        name: "psi0",
        description: "Azimuth of the initial lean, from +x toward +y",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: real(Some("rad"), Some("deg"), Some(0.0)),
    }
    OMEGA_X0 = 15 => {
        name: "omegaX0",
        description: "Initial angular velocity about the ground's x axis",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: real(Some("rad/s"), Some("deg/s"), Some(0.0)),
    }
    OMEGA_Y0 = 16 => {
        name: "omegaY0",
        description: "Initial angular velocity about the ground's y axis",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: real(Some("rad/s"), Some("deg/s"), Some(0.0)),
    }
    OMEGA_Z0 = 17 => {
        name: "omegaZ0",
        description: "Initial angular velocity about the vertical",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: real(Some("rad/s"), Some("deg/s"), Some(0.0)),
    }
    MAX_STEPS = 18 => {
        name: "maxSteps",
        description: "Work limit of one doStep: integrator steps, accepted or rejected; past it the step returns Discard at the time reached (>= 1)",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: Type::Integer { start: Some(100_000) },
    }
    AGX = 19 => {
        name: "agx",
        description: "Ground acceleration along x (interpolated with its first derivative when given)",
        causality: Input, variability: Continuous,
        ty: real(Some("m/s2"), Some("g"), Some(0.0)),
    }
    AGY = 20 => {
        name: "agy",
        description: "Ground acceleration along y, counterclockwise of x seen from above (interpolated with its first derivative when given)",
        causality: Input, variability: Continuous,
        ty: real(Some("m/s2"), Some("g"), Some(0.0)),
    }
    AV = 21 => {
        name: "av",
        description: "Vertical ground acceleration, positive up (interpolated with its first derivative when given); the apparent weight is m (g + av)",
        causality: Input, variability: Continuous,
        ty: real(Some("m/s2"), Some("g"), Some(0.0)),
    }
    THETA = 22 => {
        name: "theta",
        description: "Tilt of the axis from the vertical, asin(sqrt(ex^2 + ey^2)), >= 0",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("rad"), Some("deg"), None),
        depends_on: &["theta0"],
    }
    PSI = 23 => {
        name: "psi",
        description: "Azimuth of the lean (and of the contact on the rim), from +x toward +y, in (-pi, pi]; upright, the contact's last direction",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("rad"), Some("deg"), None),
        depends_on: D_LEAN,
    }
    THETA_OVER_ALPHA = 24 => {
        name: "thetaOverAlpha",
        description: "Normalised tilt theta/alpha (1: overturning)",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("1"), None, None),
        depends_on: D_THETA_ALPHA,
    }
    EX = 25 => {
        name: "ex",
        description: "x component of the body's axis (unit, base to top): sin(theta) cos(psi)",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("1"), None, None),
        depends_on: D_LEAN,
    }
    EY = 26 => {
        name: "ey",
        description: "y component of the body's axis (unit, base to top): sin(theta) sin(psi)",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("1"), None, None),
        depends_on: D_LEAN,
    }
    OMEGA_X = 27 => {
        name: "omegaX",
        description: "Angular velocity about the ground's x axis",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("rad/s"), Some("deg/s"), None),
        depends_on: &["theta0", "omegaX0", "omegaY0", "omegaZ0"],
    }
    OMEGA_Y = 28 => {
        name: "omegaY",
        description: "Angular velocity about the ground's y axis",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("rad/s"), Some("deg/s"), None),
        depends_on: &["theta0", "omegaX0", "omegaY0", "omegaZ0"],
    }
    OMEGA_Z = 29 => {
        name: "omegaZ",
        description: "Angular velocity about the vertical",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("rad/s"), Some("deg/s"), None),
        depends_on: &["theta0", "omegaX0", "omegaY0", "omegaZ0"],
    }
    XG = 30 => {
        name: "xG",
        description: "x of the centre of mass relative to the ground, from its place at rest upright at the start",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("m"), Some("mm"), None),
        depends_on: D_POSITION,
    }
    YG = 31 => {
        name: "yG",
        description: "y of the centre of mass relative to the ground, from its place at rest upright at the start",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("m"), Some("mm"), None),
        depends_on: D_POSITION,
    }
    FX = 32 => {
        name: "Fx",
        description: "Force of the bed on the body along x, m (agx + xG'')",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("N"), Some("kN"), None),
        depends_on: D_DYNAMIC,
    }
    FY = 33 => {
        name: "Fy",
        description: "Force of the bed on the body along y, m (agy + yG'')",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("N"), Some("kN"), None),
        depends_on: D_DYNAMIC,
    }
    FZ = 34 => {
        name: "Fz",
        description: "Vertical force of the bed on the body, m (g + av + zG'')",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("N"), Some("kN"), None),
        depends_on: D_DYNAMIC,
    }
    FRICTION_DEMAND = 35 => {
        name: "frictionDemand",
        description: "Friction coefficient the no-sliding assumption needs, sqrt(Fx^2 + Fy^2)/Fz, at most 1e60 (Modelica's inf), which it is where Fz <= 0",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("1"), None, None),
        depends_on: D_DYNAMIC,
    }
    REGIME = 36 => {
        name: "regime",
        description: "rest (upright on the whole base) or rocking (on a point of the rim: rocking, wobbling, rolling; and after overturning)",
        causality: Output, variability: Discrete, initial: Some(Calculated),
        ty: Type::Enumeration { declared_type: "RegimeKind", start: None },
        depends_on: D_REGIME,
    }
    IMPACTS = 37 => {
        name: "impacts",
        description: "Impacts so far: returns of the base to the bed (the tilt crossing upright)",
        causality: Output, variability: Discrete, initial: Some(Calculated),
        ty: Type::Integer { start: None },
    }
    OVERTURNED = 38 => {
        name: "overturned",
        description: "True once theta has reached thetaOv: the run is over",
        causality: Output, variability: Discrete, initial: Some(Calculated),
        ty: Type::Boolean { start: None },
    }
    MASS = 39 => {
        name: "mass",
        description: "Mass m = W/g",
        causality: CalcParam, variability: Fixed, initial: Some(Calculated),
        ty: real(Some("kg"), None, None),
        depends_on: D_WEIGHT,
    }
    WEIGHT = 40 => {
        name: "weight",
        description: "Weight W (rho g A H for the prism)",
        causality: CalcParam, variability: Fixed, initial: Some(Calculated),
        ty: real(Some("N"), Some("kN"), None),
        depends_on: D_WEIGHT,
    }
    R0 = 41 => {
        name: "R0",
        description: "Distance from the rim to the centre of mass, sqrt(Ro^2 + hG^2)",
        causality: CalcParam, variability: Fixed, initial: Some(Calculated),
        ty: real(Some("m"), None, None),
        depends_on: D_LEVER,
    }
    ALPHA = 42 => {
        name: "alpha",
        description: "Slenderness atan(Ro/hG)",
        causality: CalcParam, variability: Fixed, initial: Some(Calculated),
        ty: real(Some("rad"), Some("deg"), None),
        depends_on: D_LEVER,
    }
    IO = 43 => {
        name: "IO",
        description: "Inertia about a horizontal tangent to the rim, Ic + m R0^2",
        causality: CalcParam, variability: Fixed, initial: Some(Calculated),
        ty: real(Some("kg.m2"), None, None),
        depends_on: D_INERTIA,
    }
    ETA_HOUSNER = 44 => {
        name: "etaHousner",
        description: "Housner's coefficient of restitution 1 - 2 m Ro^2/IO (the planar impact's)",
        causality: CalcParam, variability: Fixed, initial: Some(Calculated),
        ty: real(Some("1"), None, None),
        depends_on: D_INERTIA,
    }
    THETA_OV = 45 => {
        name: "thetaOv",
        description: "Overturning tilt: alpha on the rigid bed",
        causality: CalcParam, variability: Fixed, initial: Some(Calculated),
        ty: real(Some("rad"), Some("deg"), None),
        depends_on: D_LEVER,
    }
}

const fn base(kg: i32, m: i32, s: i32, rad: i32) -> BaseUnit {
    BaseUnit {
        kg,
        m,
        s,
        rad,
        ..BaseUnit::ONE
    }
}

const fn du(name: &'static str, factor: f64) -> DisplayUnit {
    DisplayUnit {
        name,
        factor,
        offset: 0.0,
    }
}

/// Standard gravity for the display unit `g` (not the parameter `g`).
pub const STANDARD_GRAVITY: f64 = 9.80665;

pub static UNITS: &[Unit] = &[
    Unit {
        name: "1",
        base: BaseUnit::ONE,
        display: &[],
    },
    Unit {
        name: "m",
        base: base(0, 1, 0, 0),
        display: &[du("mm", 1e3)],
    },
    Unit {
        name: "kg",
        base: base(1, 0, 0, 0),
        display: &[du("t", 1e-3)],
    },
    Unit {
        name: "kg/m3",
        base: base(1, -3, 0, 0),
        display: &[],
    },
    Unit {
        name: "kg.m2",
        base: base(1, 2, 0, 0),
        display: &[du("t.m2", 1e-3)],
    },
    Unit {
        name: "N",
        base: base(1, 1, -2, 0),
        display: &[du("kN", 1e-3), du("MN", 1e-6)],
    },
    Unit {
        name: "m/s2",
        base: base(0, 1, -2, 0),
        display: &[du("g", 1.0 / STANDARD_GRAVITY)],
    },
    Unit {
        name: "rad",
        base: base(0, 0, 0, 1),
        display: &[du("deg", 180.0 / std::f64::consts::PI)],
    },
    Unit {
        name: "rad/s",
        base: base(0, 0, -1, 1),
        display: &[du("deg/s", 180.0 / std::f64::consts::PI)],
    },
];

const fn item(name: &'static str, value: i32, description: &'static str) -> EnumItem {
    EnumItem {
        name,
        value,
        description,
    }
}

/// Values of the enumerations, as the binary sees them (the shape and mass
/// codes are RockingBlock's).
pub mod enums {
    pub const SOLID_CIRCLE: i32 = 3;
    pub const HOLLOW_CIRCLE: i32 = 4;
    pub const PRISM: i32 = 1;
    pub const LUMPED: i32 = 2;
    pub const HOUSNER: i32 = 1;
    pub const GIVEN: i32 = 2;
    pub const REST: i32 = 1;
    pub const ROCKING: i32 = 2;
}

pub static TYPES: &[EnumType] = &[
    EnumType {
        name: "ShapeKind",
        description: "Base section shape (RockingBlock's round items, with its codes)",
        items: &[
            item(
                "solidCircle",
                enums::SOLID_CIRCLE,
                "Solid circle of radius Ro",
            ),
            item(
                "hollowCircle",
                enums::HOLLOW_CIRCLE,
                "Concentric ring Ro, Ri",
            ),
        ],
    },
    EnumType {
        name: "MassModelKind",
        description: "How the body's mass is described",
        items: &[
            item(
                "prism",
                enums::PRISM,
                "The section extruded to height H, density rho",
            ),
            item(
                "lumped",
                enums::LUMPED,
                "W, hG, Ic and IcAxial given directly",
            ),
        ],
    },
    EnumType {
        name: "RestitutionKind",
        description: "Restitution at impacts",
        items: &[
            item(
                "housner",
                enums::HOUSNER,
                "Angular momentum about the striking rim point kept (planar: 1 - 2 m b^2 / IO)",
            ),
            item(
                "given",
                enums::GIVEN,
                "Planar limit eta = the parameter eta",
            ),
        ],
    },
    EnumType {
        name: "RegimeKind",
        description: "How the body stands on the bed",
        items: &[
            item("rest", enums::REST, "Upright at rest on the whole base"),
            item(
                "rocking",
                enums::ROCKING,
                "On a point of the rim: rocking, wobbling or rolling",
            ),
        ],
    },
];

pub static LOG_CATEGORIES: &[LogCategory] = &[
    LogCategory {
        name: "logEvents",
        description: "Uplift, impacts, coming to rest and overturning",
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
];

pub static ROUND_BODY: ModelDescription = ModelDescription {
    model_name: "RoundBody",
    description: "A round body (solid or hollow circle) rocking, wobbling and rolling in space on a rigid bed under two horizontal ground accelerations and the vertical one (co-simulation)",
    author: common::AUTHOR,
    version: env!("CARGO_PKG_VERSION"),
    copyright: common::COPYRIGHT,
    license: common::LICENSE,
    generation_tool: common::GENERATION_TOOL,
    co_simulation: CoSimulation {
        // no output derivatives: the spatial physics gives none yet
        max_output_derivative_order: 0,
        ..common::co_simulation("RoundBody")
    },
    model_exchange: None,
    units: UNITS,
    types: TYPES,
    log_categories: LOG_CATEGORIES,
    default_experiment: DefaultExperiment {
        start_time: 0.0,
        stop_time: 10.0,
        tolerance: DEFAULT_TOLERANCE,
        step_size: 0.01,
    },
    variables: VARIABLES,
    documentation: include_str!("description.html"),
    arrays3: None,
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_is_consistent() {
        ROUND_BODY.check().unwrap();
    }

    #[test]
    fn sorted_by_value_reference() {
        for (i, v) in VARIABLES.iter().enumerate() {
            assert_eq!(v.vr as usize, i, "{}", v.name);
        }
    }

    /// The names the issue and RockingBlock give, each once.
    #[test]
    fn the_issue_names_are_there() {
        for n in [
            "shape",
            "Ro",
            "Ri",
            "massModel",
            "H",
            "rho",
            "W",
            "hG",
            "Ic",
            "IcAxial",
            "restitution",
            "eta",
            "g",
            "theta0",
            "psi0",
            "omegaX0",
            "omegaY0",
            "omegaZ0",
            "maxSteps",
            "agx",
            "agy",
            "av",
            "theta",
            "psi",
            "thetaOverAlpha",
            "ex",
            "ey",
            "omegaX",
            "omegaY",
            "omegaZ",
            "xG",
            "yG",
            "Fx",
            "Fy",
            "Fz",
            "frictionDemand",
            "regime",
            "impacts",
            "overturned",
            "mass",
            "weight",
            "R0",
            "alpha",
            "IO",
            "etaHousner",
            "thetaOv",
        ] {
            assert!(ROUND_BODY.variable(n).is_some(), "{n}");
        }
        assert_eq!(VARIABLES.len(), 46);
    }

    /// docs/round-body.md has one row per variable, with its causality and
    /// unit as the table says.
    #[test]
    fn the_docs_page_lists_every_variable() {
        let page = include_str!("../../docs/round-body.md");
        for v in VARIABLES {
            let row = page
                .lines()
                .find(|l| l.starts_with(&format!("| `{}` |", v.name)))
                .unwrap_or_else(|| panic!("docs/round-body.md has no row for {}", v.name));
            let causality = match v.causality {
                Causality::Parameter => "parameter",
                Causality::CalculatedParameter => "calculatedParameter",
                Causality::Input => "input",
                Causality::Output => "output",
                _ => unreachable!(),
            };
            assert!(row.contains(causality), "{row}");
            if let Some(u) = v.ty.unit() {
                assert!(row.contains(&format!("| {u} |")), "{row}: unit {u}");
            }
        }
    }
}
