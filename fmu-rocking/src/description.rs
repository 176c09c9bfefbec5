//! The RockingBlock FMU: the one definition of its variables (docs/model.md §5),
//! units, enumeration types, capabilities and default experiment.
//!
//! The value references the binary uses ([`vr`]), the `modelDescription.xml`
//! and the variable table of `documentation/index.html` all come from here.

use model_description::rigid_body::{self, base, du, enumeration, item, real, units};
use model_description::*;
use model_description::{common, variables};

/// Relative tolerance of the integrator when the master gives none
/// (`DefaultExperiment/@tolerance`).
pub const DEFAULT_TOLERANCE: f64 = 1e-9;

/// Event indicators of the Model Exchange interface: the zero crossing of
/// theta, overturning, uplift from rest, six kinks of af, the range of the
/// apparent weight and two kinks of the inertia at the weight
/// (`rocking::dynamics::continuous::EVENT_INDICATORS`, checked by the FMU).
pub const EVENT_INDICATORS: u32 = 16;

use Causality::{CalculatedParameter as CalcParam, Input, Local, Output, Parameter};
use Initial::{Calculated, Exact};
use Variability::{Continuous, Discrete, Fixed};

// Dependencies at initialization (ModelStructure/InitialUnknowns); their
// inputs are the output's dependencies in ModelStructure/Outputs.
const D_WEIGHT: &[&str] = &[
    "shape",
    "B",
    "L",
    "t",
    "Ro",
    "Ri",
    "massModel",
    "H",
    "rho",
    "W",
    "g",
];
const D_LEVER: &[&str] = &["shape", "B", "Ro", "massModel", "H", "hG"];
const D_INERTIA: &[&str] = &[
    "shape",
    "B",
    "L",
    "t",
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
const D_THRESHOLD: &[&str] = &[
    "shape",
    "B",
    "L",
    "t",
    "Ro",
    "Ri",
    "massModel",
    "H",
    "rho",
    "W",
    "interface",
    "kn",
    "fm",
    "g",
];
const D_OVERTURN: &[&str] = &[
    "shape",
    "B",
    "L",
    "t",
    "Ro",
    "Ri",
    "massModel",
    "H",
    "rho",
    "W",
    "hG",
    "interface",
    "kn",
    "fm",
    "g",
];
const D_THETA_ALPHA: &[&str] = &["shape", "B", "Ro", "massModel", "H", "hG", "theta"];
const D_CONTACT: &[&str] = &[
    "shape",
    "B",
    "L",
    "t",
    "Ro",
    "Ri",
    "massModel",
    "H",
    "rho",
    "W",
    "interface",
    "kn",
    "fm",
    "g",
    "av",
    "theta",
];
const D_MOMENT: &[&str] = &[
    "shape",
    "B",
    "L",
    "t",
    "Ro",
    "Ri",
    "massModel",
    "H",
    "rho",
    "W",
    "hG",
    "interface",
    "kn",
    "fm",
    "g",
    "av",
    "theta",
];
const D_DYNAMIC: &[&str] = &[
    "shape",
    "B",
    "L",
    "t",
    "Ro",
    "Ri",
    "massModel",
    "H",
    "rho",
    "W",
    "hG",
    "Ic",
    "interface",
    "kn",
    "fm",
    "formulation",
    "g",
    "ag",
    "av",
    "restraint",
    "side",
    "theta",
    "omega",
];
const D_APPARENT: &[&str] = &[
    "shape",
    "B",
    "L",
    "t",
    "Ro",
    "Ri",
    "massModel",
    "H",
    "rho",
    "W",
    "g",
    "av",
];

variables! {
    /// `shape` (enumeration `ShapeKind`).
    SHAPE = 0 => {
        ..rigid_body::shape("Base section: solidRectangle (B, L), hollowRectangle (B, L, t), solidCircle (Ro), hollowCircle (Ro, Ri)", 1)
    }
    B = 1 => {
        name: "B",
        description: "Rectangle depth along the rocking direction (base depth D = B)",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: real(Some("m"), None, Some(0.5)),
    }
    L = 2 => {
        name: "L",
        description: "Rectangle width perpendicular to the rocking plane",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: real(Some("m"), None, Some(1.0)),
    }
    T = 3 => {
        name: "t",
        description: "Wall thickness of the hollow rectangle (2 t < min(B, L))",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: real(Some("m"), None, Some(0.1)),
    }
    RO = 4 => {
        ..rigid_body::ro("Outer radius of the circular sections (base depth D = 2 Ro)")
    }
    RI = 5 => {
        ..rigid_body::ri("Inner radius of the hollow circle (Ri < Ro), concentric")
    }
    MASS_MODEL = 6 => {
        ..rigid_body::mass_model("Mass model: prism (the section extruded to height H with density rho) or lumped (W, hG, Ic given)")
    }
    H = 7 => {
        ..rigid_body::h(2.5)
    }
    RHO = 8 => {
        ..rigid_body::RHO
    }
    W = 9 => {
        ..rigid_body::W
    }
    HG = 10 => {
        ..rigid_body::hg("Lumped height of the centre of mass above the base (G over the section centroid)", 1.25)
    }
    IC = 11 => {
        ..rigid_body::ic("Lumped inertia about the centre of mass, about the rocking axis")
    }
    INTERFACE = 12 => {
        ..rigid_body::interface(enums::ELASTO_PLASTIC)
    }
    KN = 13 => {
        ..rigid_body::KN
    }
    FM = 14 => {
        ..rigid_body::FM
    }
    FORMULATION = 15 => {
        ..rigid_body::FORMULATION
    }
    RESTITUTION = 16 => {
        ..rigid_body::restitution("Coefficient of restitution at impacts: housner (1 - 2 m b^2/IO) or given (eta)")
    }
    ETA = 17 => {
        ..rigid_body::eta(None)
    }
    G = 18 => {
        ..rigid_body::G
    }
    AG = 19 => {
        name: "ag",
        description: "Horizontal ground acceleration, positive along +x of the theta > 0 toe (interpolated with its first derivative when given)",
        causality: Input, variability: Continuous,
        ty: real(Some("m/s2"), Some("g"), Some(0.0)),
    }
    THETA = 20 => {
        name: "theta",
        description: "Rotation of the body, positive about the +x toe; its start value is the initial rotation",
        causality: Output, variability: Continuous, initial: Some(Exact),
        ty: real(Some("rad"), Some("deg"), Some(0.0)),
    }
    OMEGA = 21 => {
        name: "omega",
        description: "Angular velocity dtheta/dt; its start value is the initial angular velocity",
        causality: Output, variability: Continuous, initial: Some(Exact),
        ty: real(Some("rad/s"), Some("deg/s"), Some(0.0)),
        // Model Exchange: omegaW sqrt(I(phi, W)/I(phi, N)) at the present av
        run_depends_on: &["theta", "omegaW", "av"],
    }
    ANGULAR_ACCELERATION = 22 => {
        name: "angularAcceleration",
        description: "Angular acceleration d2theta/dt2 from the equation of motion at the current state and ag",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("rad/s2"), Some("deg/s2"), None),
        depends_on: D_DYNAMIC,
    }
    THETA_OVER_ALPHA = 23 => {
        name: "thetaOverAlpha",
        description: "Normalised rotation theta/alpha",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("1"), None, None),
        depends_on: D_THETA_ALPHA,
    }
    AF = 24 => {
        name: "af",
        description: "Position of the interface reaction from the active toe (D/2 at rest)",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("m"), None, None),
        depends_on: D_CONTACT,
    }
    CONTACT_LENGTH = 25 => {
        name: "contactLength",
        description: "Length of the closed part of the base, min(a, D)",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("m"), None, None),
        depends_on: D_CONTACT,
    }
    MR = 26 => {
        name: "MR",
        description: "Restoring moment N hW(|theta|, N) about the shifted pivot (N the apparent weight; W without av)",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("N.m"), Some("kN.m"), None),
        depends_on: D_MOMENT,
    }
    REGIME = 27 => {
        name: "regime",
        description: "Contact regime: 0 full contact, 1 partial contact, 2 partial contact with crushing, 3 full contact with crushing, 4 overturned, 5 out of the model's range (liftOff, baseCrushing or restUnstable under av)",
        causality: Output, variability: Discrete, initial: Some(Calculated),
        ty: Type::Integer { start: None },
        depends_on: D_CONTACT,
    }
    IMPACTS = 28 => {
        name: "impacts",
        description: "Impacts so far: returns to theta = 0 after an uplift, i.e. zero crossings of theta after which |theta| had exceeded thetaJo (the joint had opened) since the previous crossing; every zero crossing for the rigid interface (see zeroCrossings)",
        causality: Output, variability: Discrete, initial: Some(Calculated),
        ty: Type::Integer { start: None },
    }
    OVERTURNED = 29 => {
        name: "overturned",
        description: "True once |theta| has reached thetaOv: the run is over",
        causality: Output, variability: Discrete, initial: Some(Calculated),
        ty: Type::Boolean { start: None },
    }
    FX = 30 => {
        name: "Fx",
        description: "Horizontal force of the support on the body, m (ag + xG'')",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("N"), Some("kN"), None),
        depends_on: D_DYNAMIC,
    }
    FZ = 31 => {
        name: "Fz",
        description: "Vertical force of the support on the body, m (g + av + zG'')",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("N"), Some("kN"), None),
        depends_on: D_DYNAMIC,
    }
    MASS = 32 => {
        depends_on: D_WEIGHT,
        ..rigid_body::MASS
    }
    WEIGHT = 33 => {
        depends_on: D_WEIGHT,
        ..rigid_body::WEIGHT
    }
    R0 = 34 => {
        depends_on: D_LEVER,
        ..rigid_body::r0("Distance from the toe to the centre of mass, sqrt(b^2 + hG^2)")
    }
    ALPHA = 35 => {
        depends_on: D_LEVER,
        ..rigid_body::alpha("Slenderness atan(b/hG)")
    }
    IO = 36 => {
        depends_on: D_INERTIA,
        ..rigid_body::io("Inertia about the toe, Ic + m R0^2")
    }
    ETA_HOUSNER = 37 => {
        depends_on: D_INERTIA,
        ..rigid_body::eta_housner("Housner's coefficient of restitution 1 - 2 m b^2/IO")
    }
    THETA_JO = 38 => {
        name: "thetaJo",
        description: "Rotation at which the heel opens (0 for the rigid interface)",
        causality: CalcParam, variability: Fixed, initial: Some(Calculated),
        ty: real(Some("rad"), Some("deg"), None),
        depends_on: D_THRESHOLD,
    }
    THETA_C = 39 => {
        name: "thetaC",
        description: "Rotation at which the toe starts to crush; 1e60 (Modelica's inf: never) for the rigid and elastic interfaces",
        causality: CalcParam, variability: Fixed, initial: Some(Calculated),
        ty: real(Some("rad"), Some("deg"), None),
        depends_on: D_THRESHOLD,
    }
    THETA_OV = 40 => {
        depends_on: D_OVERTURN,
        ..rigid_body::theta_ov("Overturning rotation, the first root of hW(phi) = 0 (alpha for the rigid interface)")
    }
    ZERO_CROSSINGS = 41 => {
        name: "zeroCrossings",
        description: "Zero crossings of theta so far (every crossing applies the restitution rule); a stiff interface vibrating in full contact crosses without impacts",
        causality: Output, variability: Discrete, initial: Some(Calculated),
        ty: Type::Integer { start: None },
    }
    MAX_STEPS = 42 => {
        name: "maxSteps",
        description: "Work limit of one fmi2DoStep: integrator steps (accepted or rejected) and zero crossings for a step of up to 1 s, proportionally more for longer steps up to 1.5 times as many; past it fmi2DoStep returns fmi2Discard at the time reached (>= 1)",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: Type::Integer { start: Some(100_000) },
    }
    DER_THETA = 43 => {
        name: "der(theta)",
        description: "Model Exchange: derivative of the continuous state theta, equal to omega",
        causality: Local, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("rad/s"), Some("deg/s"), None),
        depends_on: &["omega"],
        derivative: Some("theta"),
        run_depends_on: &["theta", "omegaW", "av"],
    }
    DER_OMEGA_W = 44 => {
        name: "der(omegaW)",
        description: "Model Exchange: derivative of the continuous state omegaW; the angular acceleration of the equation of motion where omegaW is omega (0 while a rigid body rests and after overturning)",
        causality: Local, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("rad/s2"), Some("deg/s2"), None),
        depends_on: D_DYNAMIC,
        derivative: Some("omegaW"),
        run_depends_on: &["theta", "omegaW", "ag", "av"],
    }
    AV = 45 => {
        name: "av",
        description: "Vertical ground acceleration, positive up (interpolated with its first derivative when given); the apparent weight is m (g + av)",
        causality: Input, variability: Continuous,
        ty: real(Some("m/s2"), Some("g"), Some(0.0)),
    }
    RESTRAINT = 46 => {
        name: "restraint",
        description: "none: the body rocks both ways; oneSided: it may rotate only with sgn(theta) = side, held at theta = 0 by a restraint (restitution eRestraint)",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: enumeration("RestraintKind", 1),
    }
    SIDE = 47 => {
        name: "side",
        description: "One-sided rocking: the sign of theta allowed, 1 or -1",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: Type::Integer { start: Some(1) },
    }
    E_RESTRAINT = 48 => {
        name: "eRestraint",
        description: "One-sided rocking: coefficient of restitution at the restraint, omega <- -eRestraint omega (0 <= eRestraint <= 1; 1: no loss, set it)",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: real(Some("1"), None, Some(1.0)),
    }
    APPARENT_WEIGHT = 49 => {
        name: "apparentWeight",
        description: "Apparent weight N = W + m av, the resultant of the bed",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("N"), Some("kN"), None),
        depends_on: D_APPARENT,
    }
    FRICTION_DEMAND = 50 => {
        name: "frictionDemand",
        description: "Friction coefficient the no-sliding assumption needs, |Fx|/Fz, at most 1e60 (Modelica's inf), which it is where Fz <= 0; compare with the base's friction coefficient mu",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("1"), None, None),
        depends_on: D_DYNAMIC,
    }
    MU = 51 => {
        name: "mu",
        description: "Friction coefficient of the base for the sliding check: the first time frictionDemand exceeds it, a warning names the time (0: no check; >= 0)",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: real(Some("1"), None, Some(0.0)),
    }
    FX_SUPPORT = 52 => {
        name: "FxSupport",
        description: "Horizontal force of the body on its support, -Fx: the load to apply to the support, with no sign change in the connection",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("N"), Some("kN"), None),
        depends_on: D_DYNAMIC,
    }
    FZ_SUPPORT = 53 => {
        name: "FzSupport",
        description: "Vertical force of the body on its support, -Fz (positive up: -W at rest): the load to apply to the support, with no sign change in the connection",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("N"), Some("kN"), None),
        depends_on: D_DYNAMIC,
    }
    OMEGA_W = 54 => {
        name: "omegaW",
        description: "Angular velocity referred to the inertia at the weight, omega sqrt(I(phi, N)/I(phi, W)): Model Exchange's continuous state beside theta, exact under a varying av with no derivative of it; equal to omega when av = 0, for interface = rigid and for formulation = costa",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("rad/s"), Some("deg/s"), None),
        depends_on: D_DYNAMIC,
        run_depends_on: &["av"],
    }
}

/// Standard gravity for the display unit `g` (not the parameter `g`).
pub const STANDARD_GRAVITY: f64 = rigid_body::STANDARD_GRAVITY;

pub static UNITS: &[Unit] = &[
    units::ONE,
    units::M,
    units::KG,
    units::KG_PER_M3,
    units::KG_M2,
    units::N,
    Unit {
        name: "N.m",
        base: base(1, 2, -2, 0),
        display: &[du("kN.m", 1e-3), du("MN.m", 1e-6)],
    },
    units::PA,
    units::PA_PER_M,
    units::M_PER_S2,
    units::RAD,
    units::RAD_PER_S,
    Unit {
        name: "rad/s2",
        base: base(0, 0, -2, 1),
        display: &[du("deg/s2", 180.0 / std::f64::consts::PI)],
    },
];

/// Values of the enumerations, as the binary sees them.
pub mod enums {
    // the build script, which includes this file, uses none of them
    #[allow(unused_imports)]
    pub use model_description::rigid_body::enums::{
        COSTA, ELASTIC, ELASTO_PLASTIC, GIVEN, HOLLOW_CIRCLE, HOLLOW_RECTANGLE, HOUSNER, LUMPED,
        PRISM, RIGID, SHIFTING_PIVOT, SOLID_CIRCLE, SOLID_RECTANGLE,
    };
    pub const NONE: i32 = 1;
    pub const ONE_SIDED: i32 = 2;
}

pub static TYPES: &[EnumType] = &[
    rigid_body::shape_kind(
        "Base section shape",
        &[
            item(
                "solidRectangle",
                enums::SOLID_RECTANGLE,
                "Solid rectangle B x L",
            ),
            item(
                "hollowRectangle",
                enums::HOLLOW_RECTANGLE,
                "Hollow rectangle B x L, wall t",
            ),
            rigid_body::SOLID_CIRCLE,
            rigid_body::HOLLOW_CIRCLE,
        ],
    ),
    rigid_body::mass_model_type(&rigid_body::mass_model_kind("W, hG and Ic given directly")),
    rigid_body::INTERFACE_LAW,
    rigid_body::FORMULATION_KIND,
    rigid_body::restitution_type(
        "Coefficient of restitution at impacts",
        &rigid_body::restitution_kind("eta = 1 - 2 m b^2 / IO", "eta = the parameter eta"),
    ),
    EnumType {
        name: "RestraintKind",
        description: "Whether the body rocks both ways",
        items: &[
            item("none", enums::NONE, "Rocks on both toes"),
            item(
                "oneSided",
                enums::ONE_SIDED,
                "Held on one side: rotates only with sgn(theta) = side",
            ),
        ],
    },
];

pub static LOG_CATEGORIES: &[LogCategory] =
    &rigid_body::log_categories("Impacts, uplift, coming to rest, regime changes and overturning");

pub static ROCKING_BLOCK: ModelDescription = ModelDescription {
    model_name: "RockingBlock",
    description: "Rocking of a masonry body on a flexible, no-tension interface that can crush (co-simulation and model exchange)",
    author: common::AUTHOR,
    version: env!("CARGO_PKG_VERSION"),
    copyright: common::COPYRIGHT,
    license: common::LICENSE,
    generation_tool: common::GENERATION_TOOL,
    co_simulation: CoSimulation {
        // FMI 3.0: fmi3DoStep stops at impacts, uplift, rest and overturning
        has_event_mode: true,
        might_return_early_from_do_step: true,
        ..common::co_simulation("RockingBlock")
    },
    model_exchange: Some(common::model_exchange("RockingBlock", EVENT_INDICATORS)),
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
    use model_description::xml;

    #[test]
    fn table_is_consistent() {
        ROCKING_BLOCK.check().unwrap();
    }

    /// The enumeration codes fmu-rocking/README.md gives fmpy users ("From
    /// fmpy, on the first try") are this table's, for every enumeration
    /// parameter.
    #[test]
    fn the_readme_lists_every_enumeration_code() {
        let readme = include_str!("../README.md");
        for v in VARIABLES {
            if let Type::Enumeration { declared_type, .. } = v.ty {
                let t = ROCKING_BLOCK.enum_type(declared_type).unwrap();
                let items: Vec<String> = t
                    .items
                    .iter()
                    .map(|i| format!("{}: `{}`", i.value, i.name))
                    .collect();
                let row = format!("| `{}` | {} |", v.name, items.join(", "));
                assert!(readme.contains(&row), "README.md lacks the row {row}");
            }
        }
    }

    #[test]
    fn sorted_by_value_reference() {
        for (i, v) in VARIABLES.iter().enumerate() {
            assert_eq!(v.vr as usize, i, "{}", v.name);
        }
    }

    /// `by_vr`'s lookup from index `vr` down gives what a scan of the table
    /// gives, for every value reference (and some that are none) and base:
    /// on this table, on it reversed, and with every third variable left out.
    #[test]
    fn lookup_by_value_reference_is_a_scan() {
        let scan = |md: &ModelDescription, base: BaseType, vr: u32| {
            md.variables
                .iter()
                .enumerate()
                .find(|(_, v)| v.vr == vr && v.ty.base() == base)
        };
        let reversed: Vec<Variable> = VARIABLES.iter().rev().copied().collect();
        let holes: Vec<Variable> = VARIABLES.iter().step_by(3).copied().collect();
        for vars in [VARIABLES, &*reversed.leak(), &*holes.leak()] {
            let md = ModelDescription {
                variables: vars,
                ..ROCKING_BLOCK
            };
            for vr in 0..VARIABLES.len() as u32 + 3 {
                for base in [
                    BaseType::Real,
                    BaseType::Integer,
                    BaseType::Boolean,
                    BaseType::String,
                ] {
                    let (got, want) = (md.by_vr(base, vr), scan(&md, base, vr));
                    assert_eq!(
                        got.map(|(i, _)| i),
                        want.map(|(i, _)| i),
                        "vr {vr}, {base:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn every_model_md_variable_is_there() {
        for n in [
            "shape",
            "B",
            "L",
            "t",
            "Ro",
            "Ri",
            "massModel",
            "H",
            "rho",
            "W",
            "hG",
            "Ic",
            "interface",
            "kn",
            "fm",
            "formulation",
            "restitution",
            "eta",
            "g",
            "ag",
            "theta",
            "omega",
            "thetaOverAlpha",
            "af",
            "contactLength",
            "MR",
            "regime",
            "impacts",
            "zeroCrossings",
            "overturned",
            "Fx",
            "Fz",
            "FxSupport",
            "FzSupport",
            "mass",
            "weight",
            "R0",
            "alpha",
            "IO",
            "etaHousner",
            "thetaJo",
            "thetaC",
            "thetaOv",
            "av",
            "restraint",
            "side",
            "eRestraint",
            "apparentWeight",
        ] {
            assert!(ROCKING_BLOCK.variable(n).is_some(), "{n}");
        }
    }

    #[test]
    fn guid_is_stable_and_in_the_xml() {
        let (xml, g) = xml::model_description_xml(&ROCKING_BLOCK, None);
        assert_eq!(g, xml::guid(&ROCKING_BLOCK));
        assert!(xml.contains(&format!("guid=\"{g}\"")));
        assert!(xml.starts_with("<?xml"));
        assert!(xml.contains("<CoSimulation modelIdentifier=\"RockingBlock\" needsExecutionTool=\"false\" canHandleVariableCommunicationStepSize=\"true\" canInterpolateInputs=\"true\" maxOutputDerivativeOrder=\"2\" canBeInstantiatedOnlyOncePerProcess=\"false\""));
        assert!(!xml.contains("canRunAsynchronuously"));
        assert!(!xml.contains("providesDirectionalDerivative"));
    }

    #[test]
    fn structure_lists() {
        let xml = xml::render(&ROCKING_BLOCK, "x", None);
        // Fx (index 31) depends on ag (index 20) and av (index 46) only
        // among the inputs.
        assert!(xml.contains("<Unknown index=\"31\" dependencies=\"20 46\"/>"));
        // theta (21) is an output with no direct feedthrough.
        assert!(xml.contains("<Unknown index=\"21\" dependencies=\"\"/>"));
    }
}
