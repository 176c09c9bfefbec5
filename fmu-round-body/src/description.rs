//! The RoundBody FMU: the one definition of its variables
//! (docs/round-body.md), units, enumeration types, capabilities and default
//! experiment.
//!
//! The value references the binary uses ([`vr`]), the `modelDescription.xml`
//! and the variable table of `documentation/index.html` all come from here.
//! Names shared with RockingBlock (`shape`, `Ro`, `massModel`, `Fx`,
//! `frictionDemand`, ...) mean the same there and here.

use model_description::rigid_body::{self, base, du, real, units};
use model_description::*;
use model_description::{common, variables};

/// Relative tolerance of the integrator when the master gives none
/// (`DefaultExperiment/@tolerance`), as RockingBlock's.
pub const DEFAULT_TOLERANCE: f64 = 1e-9;

use Causality::{Input, Local, Output, Parameter};
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
const D_OVERTURN: &[&str] = &[
    "shape",
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
// the lean of the initial tilt: on a flexible bed the resultant's place
// under the weight (docs/model.md §11.2)
const D_POSITION: &[&str] = &[
    "shape",
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
    "theta0",
    "psi0",
];
// the bed's reaction at the tilt under the apparent weight m (g + av)
const D_CONTACT: &[&str] = &[
    "shape",
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
    "theta0",
    "omegaX0",
    "omegaY0",
    "omegaZ0",
    "av",
];
/// Number of Model Exchange event indicators (`rocking::spatial::continuous`:
/// the quarter turn or crossing, overturning, uplift, lift-off).
pub const EVENT_INDICATORS: u32 = 4;

/// What a state derivative depends on in a run: the continuous states and
/// the inputs (`ModelStructure/Derivatives`).
const D_RATES: &[&str] = &[
    "ex", "ey", "omegaWX", "omegaWY", "omegaWZ", "agx", "agy", "av",
];

/// What the tilt's and the centre of mass's rates and the angular velocity
/// depend on in a run: the states and `av` (the angular velocity is
/// `omegaW` turned back under the present `av`, docs/model.md §11.5).
const D_MOTION: &[&str] = &["ex", "ey", "omegaWX", "omegaWY", "omegaWZ", "av"];

/// `omegaWX`'s description (a constant: the table takes an expression).
const OMEGA_W_DESCRIPTION_X: &str = "Angular velocity referred to the weight, x component (docs/model.md 11.5): Model Exchange's continuous state beside ex, ey, xG, yG, exact under a varying av with no derivative of it; equal to omegaX for interface = rigid, for formulation = costa and when av = 0";

/// What `omegaW` depends on at initialization: the start of the motion and
/// the bed (its transform), and `av`.
const D_OMEGA_W: &[&str] = &[
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
    "interface",
    "kn",
    "fm",
    "formulation",
    "g",
    "theta0",
    "psi0",
    "omegaX0",
    "omegaY0",
    "omegaZ0",
    "av",
];

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
    "interface",
    "kn",
    "fm",
    "formulation",
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
        ..rigid_body::shape("Base section: solidCircle (Ro) or hollowCircle (Ro, Ri); RockingBlock's codes (its rectangles are no body of revolution)", 3)
    }
    RO = 1 => {
        ..rigid_body::ro("Outer radius of the base (base depth D = 2 Ro), > 0")
    }
    RI = 2 => {
        ..rigid_body::ri("Inner radius of the hollow circle (0 < Ri < Ro), concentric")
    }
    MASS_MODEL = 3 => {
        ..rigid_body::mass_model("Mass model: prism (the section extruded to height H with density rho) or lumped (W, hG, Ic and IcAxial given)")
    }
    H = 4 => {
        ..rigid_body::h(3.0)
    }
    RHO = 5 => {
        ..rigid_body::RHO
    }
    W = 6 => {
        ..rigid_body::W
    }
    HG = 7 => {
        ..rigid_body::hg("Lumped height of the centre of mass above the base, on the axis", 1.5)
    }
    IC = 8 => {
        ..rigid_body::ic("Lumped inertia about a horizontal axis through the centre of mass")
    }
    IC_AXIAL = 9 => {
        name: "IcAxial",
        description: "Lumped inertia about the body's axis (massModel = lumped only; a prism's is m (Ro^2 + Ri^2)/2, computed), > 0",
        causality: Parameter, variability: Fixed, initial: Some(Exact),
        ty: real(Some("kg.m2"), None, Some(1.0e4)),
    }
    RESTITUTION = 10 => {
        ..rigid_body::restitution("Restitution at impacts: housner (the planar limit is Housner's 1 - 2 m b^2/IO; in space the angular momentum about the striking rim point is kept) or given (the planar limit is eta)")
    }
    ETA = 11 => {
        ..rigid_body::eta(Some("1"))
    }
    G = 12 => {
        ..rigid_body::G
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
        run_depends_on: D_MOTION,
    }
    OMEGA_Y = 28 => {
        name: "omegaY",
        description: "Angular velocity about the ground's y axis",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("rad/s"), Some("deg/s"), None),
        depends_on: &["theta0", "omegaX0", "omegaY0", "omegaZ0"],
        run_depends_on: D_MOTION,
    }
    OMEGA_Z = 29 => {
        name: "omegaZ",
        description: "Angular velocity about the vertical",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("rad/s"), Some("deg/s"), None),
        depends_on: &["theta0", "omegaX0", "omegaY0", "omegaZ0"],
        run_depends_on: D_MOTION,
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
        description: "On the rigid bed: rest (upright on the whole base) or rocking (on a point of the rim: rocking, wobbling, rolling; and after overturning). On a flexible bed the planar contact along the lean: fullContact, partialContact, partialCrushing, fullCrushing, or outOfRange (g + av <= 0, liftOff, or the apparent weight crushing the whole base)",
        causality: Output, variability: Discrete, initial: Some(Calculated),
        ty: Type::Enumeration { declared_type: "RegimeKind", start: None },
        depends_on: D_CONTACT,
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
        depends_on: D_WEIGHT,
        ..rigid_body::MASS
    }
    WEIGHT = 40 => {
        depends_on: D_WEIGHT,
        ..rigid_body::WEIGHT
    }
    R0 = 41 => {
        depends_on: D_LEVER,
        ..rigid_body::r0("Distance from the rim to the centre of mass, sqrt(Ro^2 + hG^2)")
    }
    ALPHA = 42 => {
        depends_on: D_LEVER,
        ..rigid_body::alpha("Slenderness atan(Ro/hG)")
    }
    IO = 43 => {
        depends_on: D_INERTIA,
        ..rigid_body::io("Inertia about a horizontal tangent to the rim, Ic + m R0^2")
    }
    ETA_HOUSNER = 44 => {
        depends_on: D_INERTIA,
        ..rigid_body::eta_housner("Housner's coefficient of restitution 1 - 2 m Ro^2/IO (the planar impact's)")
    }
    THETA_OV = 45 => {
        depends_on: D_OVERTURN,
        ..rigid_body::theta_ov("Overturning tilt: alpha on the rigid bed; on a flexible bed RockingBlock's, the first root of hW(phi) = 0")
    }
    DER_EX = 46 => {
        name: "der(ex)",
        description: "Model Exchange: derivative of the continuous state ex (0 at rest and after overturning)",
        causality: Local, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("1/s"), None, None),
        depends_on: D_DYNAMIC,
        derivative: Some("ex"),
        run_depends_on: D_MOTION,
    }
    DER_EY = 47 => {
        name: "der(ey)",
        description: "Model Exchange: derivative of the continuous state ey (0 at rest and after overturning)",
        causality: Local, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("1/s"), None, None),
        depends_on: D_DYNAMIC,
        derivative: Some("ey"),
        run_depends_on: D_MOTION,
    }
    DER_OMEGA_X = 48 => {
        name: "der(omegaWX)",
        description: "Model Exchange: derivative of the continuous state omegaWX; the angular acceleration about x where omegaW is omega (0 at rest and after overturning)",
        causality: Local, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("rad/s2"), Some("deg/s2"), None),
        depends_on: D_DYNAMIC,
        derivative: Some("omegaWX"),
        run_depends_on: D_RATES,
    }
    DER_OMEGA_Y = 49 => {
        name: "der(omegaWY)",
        description: "Model Exchange: derivative of the continuous state omegaWY; the angular acceleration about y where omegaW is omega (0 at rest and after overturning)",
        causality: Local, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("rad/s2"), Some("deg/s2"), None),
        depends_on: D_DYNAMIC,
        derivative: Some("omegaWY"),
        run_depends_on: D_RATES,
    }
    DER_OMEGA_Z = 50 => {
        name: "der(omegaWZ)",
        description: "Model Exchange: derivative of the continuous state omegaWZ; the angular acceleration about the vertical where omegaW is omega (0 at rest and after overturning)",
        causality: Local, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("rad/s2"), Some("deg/s2"), None),
        depends_on: D_DYNAMIC,
        derivative: Some("omegaWZ"),
        run_depends_on: D_RATES,
    }
    DER_XG = 51 => {
        name: "der(xG)",
        description: "Model Exchange: derivative of the continuous state xG, the centre of mass's velocity along x (0 at rest and after overturning)",
        causality: Local, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("m/s"), None, None),
        depends_on: D_DYNAMIC,
        derivative: Some("xG"),
        run_depends_on: D_MOTION,
    }
    DER_YG = 52 => {
        name: "der(yG)",
        description: "Model Exchange: derivative of the continuous state yG, the centre of mass's velocity along y (0 at rest and after overturning)",
        causality: Local, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("m/s"), None, None),
        depends_on: D_DYNAMIC,
        derivative: Some("yG"),
        run_depends_on: D_MOTION,
    }
    CONTACT_AREA = 53 => {
        name: "contactArea",
        description: "Area of the base in contact with the bed. Rigid bed: the whole section at rest, 0 on a point of the rim (rocking, wobbling, rolling; and after overturning). Flexible bed: the closed part of the base under the apparent weight m (g + av), 0 where g + av <= 0",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("m2"), None, None),
        depends_on: D_CONTACT,
    }
    INTERFACE = 54 => {
        ..rigid_body::interface(rigid_body::enums::RIGID)
    }
    KN = 55 => {
        ..rigid_body::KN
    }
    FM = 56 => {
        ..rigid_body::FM
    }
    FORMULATION = 57 => {
        ..rigid_body::FORMULATION
    }
    AF = 58 => {
        name: "af",
        description: "Distance of the bed's resultant from the toe (the rim point toward the lean), along the lean: Ro at rest on the rigid bed, 0 on its rim point; on a flexible bed RockingBlock's af at the tilt under the apparent weight m (g + av), 0 where g + av <= 0",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("m"), None, None),
        depends_on: D_CONTACT,
    }
    CRUSHED_AREA = 59 => {
        name: "crushedArea",
        description: "Area of the crushed (plastic) part of the base: 0 on the rigid and elastic beds; on elastoPlastic the part at fm under the apparent weight m (g + av)",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("m2"), None, None),
        depends_on: D_CONTACT,
    }
    OMEGA_WX = 60 => {
        name: "omegaWX",
        description: OMEGA_W_DESCRIPTION_X,
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("rad/s"), Some("deg/s"), None),
        depends_on: D_OMEGA_W,
        run_depends_on: &["av"],
    }
    OMEGA_WY = 61 => {
        name: "omegaWY",
        description: "Angular velocity referred to the weight, y component: Model Exchange's continuous state (see omegaWX)",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("rad/s"), Some("deg/s"), None),
        depends_on: D_OMEGA_W,
        run_depends_on: &["av"],
    }
    OMEGA_WZ = 62 => {
        name: "omegaWZ",
        description: "Angular velocity referred to the weight, vertical component: Model Exchange's continuous state (see omegaWX)",
        causality: Output, variability: Continuous, initial: Some(Calculated),
        ty: real(Some("rad/s"), Some("deg/s"), None),
        depends_on: D_OMEGA_W,
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
    // kn, fm
    units::PA,
    units::PA_PER_M,
    units::M_PER_S2,
    units::RAD,
    units::RAD_PER_S,
    // contactArea, crushedArea
    Unit {
        name: "m2",
        base: base(0, 2, 0, 0),
        display: &[],
    },
    // Model Exchange's state derivatives
    Unit {
        name: "1/s",
        base: base(0, 0, -1, 0),
        display: &[],
    },
    Unit {
        name: "m/s",
        base: base(0, 1, -1, 0),
        display: &[du("mm/s", 1e3)],
    },
    Unit {
        name: "rad/s2",
        base: base(0, 0, -2, 1),
        display: &[du("deg/s2", 180.0 / std::f64::consts::PI)],
    },
];

/// Values of the enumerations, as the binary sees them (the shape and mass
/// codes are RockingBlock's).
pub mod enums {
    // the build script, which includes this file, uses none of them
    #[allow(unused_imports)]
    pub use model_description::rigid_body::enums::{
        COSTA, ELASTIC, ELASTO_PLASTIC, GIVEN, HOLLOW_CIRCLE, HOUSNER, LUMPED, PRISM, RIGID,
        SHIFTING_PIVOT, SOLID_CIRCLE,
    };
    pub const REST: i32 = 1;
    pub const ROCKING: i32 = 2;
    pub const FULL_CONTACT: i32 = 3;
    pub const PARTIAL_CONTACT: i32 = 4;
    pub const PARTIAL_CRUSHING: i32 = 5;
    pub const FULL_CRUSHING: i32 = 6;
    pub const OUT_OF_RANGE: i32 = 7;
}

pub static TYPES: &[EnumType] = &[
    rigid_body::shape_kind(
        "Base section shape (RockingBlock's round items, with its codes)",
        &[rigid_body::SOLID_CIRCLE, rigid_body::HOLLOW_CIRCLE],
    ),
    rigid_body::mass_model_type(&rigid_body::mass_model_kind(
        "W, hG, Ic and IcAxial given directly",
    )),
    rigid_body::INTERFACE_LAW,
    rigid_body::FORMULATION_KIND,
    rigid_body::restitution_type(
        "Restitution at impacts",
        &rigid_body::restitution_kind(
            "Angular momentum about the striking rim point kept (planar: 1 - 2 m b^2 / IO)",
            "Planar limit eta = the parameter eta",
        ),
    ),
    EnumType {
        name: "RegimeKind",
        description: "How the body stands on the bed",
        items: &[
            rigid_body::item("rest", enums::REST, "Upright at rest on the whole base"),
            rigid_body::item(
                "rocking",
                enums::ROCKING,
                "On a point of the rim: rocking, wobbling or rolling",
            ),
            rigid_body::item(
                "fullContact",
                enums::FULL_CONTACT,
                "Flexible bed: the whole base closed, elastic",
            ),
            rigid_body::item(
                "partialContact",
                enums::PARTIAL_CONTACT,
                "Flexible bed: the heel open, the contact elastic",
            ),
            rigid_body::item(
                "partialCrushing",
                enums::PARTIAL_CRUSHING,
                "Flexible bed: the heel open, the toe crushed",
            ),
            rigid_body::item(
                "fullCrushing",
                enums::FULL_CRUSHING,
                "Flexible bed: the whole base closed, the toe crushed",
            ),
            rigid_body::item(
                "outOfRange",
                enums::OUT_OF_RANGE,
                "Flexible bed: g + av <= 0 (liftOff) or the apparent weight crushes the whole base",
            ),
        ],
    },
];

pub static LOG_CATEGORIES: &[LogCategory] =
    &rigid_body::log_categories("Uplift, impacts, coming to rest and overturning");

pub static ROUND_BODY: ModelDescription = ModelDescription {
    model_name: "RoundBody",
    description: "A round body (solid or hollow circle) rocking, wobbling and rolling in space on a rigid or flexible, crushing bed under two horizontal ground accelerations and the vertical one (co-simulation; model exchange on the rigid bed)",
    author: common::AUTHOR,
    version: env!("CARGO_PKG_VERSION"),
    copyright: common::COPYRIGHT,
    license: common::LICENSE,
    generation_tool: common::GENERATION_TOOL,
    co_simulation: CoSimulation {
        // no output derivatives: the spatial physics gives none yet
        max_output_derivative_order: 0,
        // FMI 3.0: fmi3DoStep stops at uplift, impacts, rest and overturning
        has_event_mode: true,
        might_return_early_from_do_step: true,
        ..common::co_simulation("RoundBody")
    },
    model_exchange: Some(common::model_exchange("RoundBody", EVENT_INDICATORS)),
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
            "der(ex)",
            "der(ey)",
            "der(omegaWX)",
            "der(omegaWY)",
            "der(omegaWZ)",
            "der(xG)",
            "der(yG)",
            "contactArea",
            "interface",
            "kn",
            "fm",
            "formulation",
            "af",
            "crushedArea",
            "omegaWX",
            "omegaWY",
            "omegaWZ",
        ] {
            assert!(ROUND_BODY.variable(n).is_some(), "{n}");
        }
        assert_eq!(VARIABLES.len(), 63);
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
                Causality::Local => "local",
                _ => unreachable!(),
            };
            assert!(row.contains(causality), "{row}");
            if let Some(u) = v.ty.unit() {
                assert!(row.contains(&format!("| {u} |")), "{row}: unit {u}");
            }
        }
    }
}
