//! The ShearFrame FMU: the one definition of its variables (docs/shear-frame.md),
//! units, enumeration types, capabilities and default experiment.
//!
//! The arrays `m[i]`, `k[i]`, `Fx[i]`, `Fz[i]`, `u[i]`, `v[i]`, `a[i]`,
//! `drift[i]` and `period[i]` have [`MAX_STOREYS`] elements each (FMI 2.0
//! has no arrays: one scalar variable per element, named with the
//! structured naming convention); the table is built once, at first use,
//! from loops over the floors. Value references: [`vr`].

use std::sync::LazyLock;

use model_description::common;
use model_description::fmi3::Arrays3;
use model_description::*;

/// Length of every per-floor array: the most storeys a frame may have.
pub const MAX_STOREYS: usize = 20;

/// Value references. Per-floor variables are `BASE + i` for floor `i` in
/// `1..=MAX_STOREYS`.
pub mod vr {
    pub const N: u32 = 0;
    pub const DAMPING: u32 = 1;
    pub const ZETA: u32 = 2;
    pub const RAYLEIGH_ALPHA: u32 = 3;
    pub const RAYLEIGH_BETA: u32 = 4;
    pub const AG: u32 = 5;
    pub const M: u32 = 100;
    pub const K: u32 = 200;
    pub const FX: u32 = 300;
    pub const FZ: u32 = 400;
    pub const U: u32 = 500;
    pub const V: u32 = 600;
    pub const A: u32 = 700;
    pub const DRIFT: u32 = 800;
    pub const PERIOD: u32 = 900;

    /// The value reference of element `i` (1-based) of the array at `base`.
    pub const fn at(base: u32, i: usize) -> u32 {
        base + i as u32
    }

    /// The array base and the 1-based element of a per-floor value reference.
    pub const fn split(vr: u32) -> (u32, usize) {
        (vr / 100 * 100, (vr % 100) as usize)
    }
}

/// Values of the enumeration `DampingKind`.
pub mod enums {
    pub const MODAL: i32 = 1;
    pub const RAYLEIGH: i32 = 2;
}

/// Relative tolerance in `DefaultExperiment` (the step is exact: the
/// integration ignores it).
pub const DEFAULT_TOLERANCE: f64 = 1e-9;

fn leak(s: String) -> &'static str {
    Box::leak(s.into_boxed_str())
}

fn names(base: &str) -> Vec<&'static str> {
    (1..=MAX_STOREYS)
        .map(|i| leak(format!("{base}[{i}]")))
        .collect()
}

const fn real(unit: &'static str, display: Option<&'static str>, start: Option<f64>) -> Type {
    Type::Real {
        unit: Some(unit),
        display_unit: display,
        start,
        min: None,
        max: None,
    }
}

fn build_variables() -> Vec<Variable> {
    use Causality::{CalculatedParameter as CalcParam, Input, Output, Parameter};
    use Initial::{Calculated, Exact};
    use Variability::{Continuous, Fixed};
    let param = |name, vr, description, ty| Variable {
        name,
        vr,
        description,
        causality: Parameter,
        variability: Fixed,
        initial: Some(Exact),
        ty,
        depends_on: &[],
        derivative: None,
        run_depends_on: &[],
    };
    let mut v = vec![
        param(
            "n",
            vr::N,
            "Number of storeys (floors above the ground), 1 to 20; the array elements past n are unused",
            Type::Integer { start: Some(3) },
        ),
        param(
            "damping",
            vr::DAMPING,
            "Damping model: modal (the ratio zeta in every mode) or rayleigh (C = rayleighAlpha M + rayleighBeta K)",
            Type::Enumeration {
                declared_type: "DampingKind",
                start: Some(enums::MODAL),
            },
        ),
        param(
            "zeta",
            vr::ZETA,
            "Damping ratio of every mode (damping = modal), >= 0",
            real("1", None, Some(0.05)),
        ),
        param(
            "rayleighAlpha",
            vr::RAYLEIGH_ALPHA,
            "Mass-proportional Rayleigh coefficient (damping = rayleigh), >= 0",
            real("1/s", None, Some(0.0)),
        ),
        param(
            "rayleighBeta",
            vr::RAYLEIGH_BETA,
            "Stiffness-proportional Rayleigh coefficient (damping = rayleigh), >= 0",
            real("s", None, Some(0.0)),
        ),
        Variable {
            name: "ag",
            vr: vr::AG,
            description: "Horizontal ground acceleration, +x (interpolated with its first derivative when given)",
            causality: Input,
            variability: Continuous,
            initial: None,
            ty: real("m/s2", Some("g"), Some(0.0)),
            depends_on: &[],
            derivative: None,
            run_depends_on: &[],
        },
    ];
    let (m, k, fx, fz) = (names("m"), names("k"), names("Fx"), names("Fz"));
    let (u, vel, a, drift, period) = (
        names("u"),
        names("v"),
        names("a"),
        names("drift"),
        names("period"),
    );
    let structural: Vec<&'static str> = ["n", "damping", "zeta", "rayleighAlpha", "rayleighBeta"]
        .into_iter()
        .chain(m.iter().copied())
        .chain(k.iter().copied())
        .collect();
    let modal: &'static [&'static str] = Box::leak(
        std::iter::once("n")
            .chain(m.iter().copied())
            .chain(k.iter().copied())
            .collect::<Vec<_>>()
            .into_boxed_slice(),
    );
    for (i, &name) in m.iter().enumerate() {
        v.push(param(
            name,
            vr::at(vr::M, i + 1),
            leak(format!("Mass of floor {}", i + 1)),
            real("kg", Some("t"), Some(1.0e5)),
        ));
    }
    for (i, &name) in k.iter().enumerate() {
        v.push(param(
            name,
            vr::at(vr::K, i + 1),
            leak(format!(
                "Lateral stiffness of storey {} (between floor {} and floor {})",
                i + 1,
                i,
                i + 1
            )),
            real("N/m", Some("kN/mm"), Some(1.0e8)),
        ));
    }
    for (names, base, what) in [
        (&fx, vr::FX, "Horizontal external force on floor {i}, +x"),
        (
            &fz,
            vr::FZ,
            "Vertical external force on floor {i}, up (accepted for coupling; no effect on the lateral model)",
        ),
    ] {
        for (i, name) in names.iter().enumerate() {
            v.push(Variable {
                name,
                vr: vr::at(base, i + 1),
                description: leak(what.replace("{i}", &(i + 1).to_string())),
                causality: Input,
                variability: Continuous,
                initial: None,
                ty: real("N", Some("kN"), Some(0.0)),
                depends_on: &[],
                derivative: None,
                run_depends_on: &[],
            });
        }
    }
    for (i, &name) in u.iter().enumerate() {
        v.push(Variable {
            name,
            vr: vr::at(vr::U, i + 1),
            description: leak(format!(
                "Displacement of floor {} relative to the ground, +x; its start value is the initial displacement",
                i + 1
            )),
            causality: Output,
            variability: Continuous,
            initial: Some(Exact),
            ty: real("m", Some("mm"), Some(0.0)),
            depends_on: &[],
            derivative: None,
            run_depends_on: &[],
        });
    }
    for (i, &name) in vel.iter().enumerate() {
        v.push(Variable {
            name,
            vr: vr::at(vr::V, i + 1),
            description: leak(format!(
                "Velocity of floor {} relative to the ground, du/dt; its start value is the initial velocity",
                i + 1
            )),
            causality: Output,
            variability: Continuous,
            initial: Some(Exact),
            ty: real("m/s", None, Some(0.0)),
            depends_on: &[],
            derivative: None,
            run_depends_on: &[],
        });
    }
    for i in 0..MAX_STOREYS {
        let deps: Vec<&'static str> = structural
            .iter()
            .copied()
            .chain(u.iter().copied())
            .chain(vel.iter().copied())
            .chain([fx[i]])
            .collect();
        v.push(Variable {
            name: a[i],
            vr: vr::at(vr::A, i + 1),
            description: leak(format!(
                "Absolute acceleration of floor {} (ground plus relative), +x",
                i + 1
            )),
            causality: Output,
            variability: Continuous,
            initial: Some(Calculated),
            ty: real("m/s2", Some("g"), None),
            depends_on: Box::leak(deps.into_boxed_slice()),
            derivative: None,
            run_depends_on: &[],
        });
    }
    for i in 0..MAX_STOREYS {
        let deps: Vec<&'static str> = if i == 0 {
            vec!["n", u[0]]
        } else {
            vec!["n", u[i - 1], u[i]]
        };
        v.push(Variable {
            name: drift[i],
            vr: vr::at(vr::DRIFT, i + 1),
            description: leak(format!(
                "Drift of storey {}: u[{}] - u[{}] (u[0] = 0, the ground)",
                i + 1,
                i + 1,
                i
            )),
            causality: Output,
            variability: Continuous,
            initial: Some(Calculated),
            ty: real("m", Some("mm"), None),
            depends_on: Box::leak(deps.into_boxed_slice()),
            derivative: None,
            run_depends_on: &[],
        });
    }
    for (i, name) in period.iter().enumerate() {
        v.push(Variable {
            name,
            vr: vr::at(vr::PERIOD, i + 1),
            description: leak(format!(
                "Natural period of mode {} (descending; 0 past n)",
                i + 1
            )),
            causality: CalcParam,
            variability: Fixed,
            initial: Some(Calculated),
            ty: real("s", None, None),
            depends_on: modal,
            derivative: None,
            run_depends_on: &[],
        });
    }
    v
}

const fn base(kg: i32, m: i32, s: i32) -> BaseUnit {
    BaseUnit {
        kg,
        m,
        s,
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

/// Standard gravity for the display unit `g`.
pub const STANDARD_GRAVITY: f64 = 9.80665;

pub static UNITS: &[Unit] = &[
    Unit {
        name: "1",
        base: BaseUnit::ONE,
        display: &[],
    },
    Unit {
        name: "1/s",
        base: base(0, 0, -1),
        display: &[],
    },
    Unit {
        name: "s",
        base: base(0, 0, 1),
        display: &[],
    },
    Unit {
        name: "m",
        base: base(0, 1, 0),
        display: &[du("mm", 1e3)],
    },
    Unit {
        name: "m/s",
        base: base(0, 1, -1),
        display: &[],
    },
    Unit {
        name: "m/s2",
        base: base(0, 1, -2),
        display: &[du("g", 1.0 / STANDARD_GRAVITY)],
    },
    Unit {
        name: "kg",
        base: base(1, 0, 0),
        display: &[du("t", 1e-3)],
    },
    Unit {
        name: "N",
        base: base(1, 1, -2),
        display: &[du("kN", 1e-3)],
    },
    Unit {
        name: "N/m",
        base: base(1, 0, -2),
        display: &[du("kN/mm", 1e-6)],
    },
];

pub static TYPES: &[EnumType] = &[EnumType {
    name: "DampingKind",
    description: "How the damping matrix is built",
    items: &[
        EnumItem {
            name: "modal",
            value: enums::MODAL,
            description: "The ratio zeta in every mode",
        },
        EnumItem {
            name: "rayleigh",
            value: enums::RAYLEIGH,
            description: "C = rayleighAlpha M + rayleighBeta K",
        },
    ],
}];

pub static LOG_CATEGORIES: &[LogCategory] = &[
    LogCategory {
        name: "logEvents",
        description: "Events (none: the model is linear and smooth)",
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

/// FMI 3.0: each per-floor variable is one array of `n` elements
/// (`Fx[i]` is element `i` of `Fx`), `n` a structural parameter.
pub const ARRAYS3: Arrays3 = Arrays3 {
    size: "n",
    size_description: "Number of storeys (floors above the ground), 1 to 20: the length of every per-floor array (set in configuration mode)",
    len: MAX_STOREYS,
    arrays: &[
        ("m", "Mass of each floor, floor 1 first"),
        ("k", "Lateral stiffness of each storey (storey i between floor i-1 and floor i)"),
        ("Fx", "Horizontal external force on each floor, +x"),
        ("Fz", "Vertical external force on each floor, up (accepted for coupling; no effect on the lateral model)"),
        ("u", "Displacement of each floor relative to the ground, +x; its start value is the initial displacement"),
        ("v", "Velocity of each floor relative to the ground, du/dt; its start value is the initial velocity"),
        ("a", "Absolute acceleration of each floor (ground plus relative), +x"),
        ("drift", "Drift of each storey: u[i] - u[i-1] (u[0] = 0, the ground)"),
        ("period", "Natural period of each mode (descending)"),
    ],
};

pub static SHEAR_FRAME: LazyLock<ModelDescription> = LazyLock::new(|| {
    ModelDescription {
    model_name: "ShearFrame",
    description: "A linear n-storey shear building under ground acceleration and floor forces, stepped exactly (co-simulation)",
    author: common::AUTHOR,
    version: env!("CARGO_PKG_VERSION"),
    copyright: common::COPYRIGHT,
    license: common::LICENSE,
    generation_tool: common::GENERATION_TOOL,
    co_simulation: common::co_simulation("ShearFrame"),
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
    variables: Box::leak(build_variables().into_boxed_slice()),
    documentation: include_str!("description.html"),
    arrays3: Some(ARRAYS3),
}
});

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_is_consistent() {
        SHEAR_FRAME.check().unwrap();
    }

    #[test]
    fn issue_names_and_value_references() {
        for i in 1..=MAX_STOREYS {
            for (base, name) in [
                (vr::M, "m"),
                (vr::K, "k"),
                (vr::FX, "Fx"),
                (vr::FZ, "Fz"),
                (vr::U, "u"),
                (vr::V, "v"),
                (vr::A, "a"),
                (vr::DRIFT, "drift"),
                (vr::PERIOD, "period"),
            ] {
                let v = SHEAR_FRAME.variable(&format!("{name}[{i}]")).unwrap();
                assert_eq!(v.vr, vr::at(base, i));
                assert_eq!(vr::split(v.vr), (base, i));
            }
        }
        for n in [
            "n",
            "zeta",
            "ag",
            "damping",
            "rayleighAlpha",
            "rayleighBeta",
        ] {
            assert!(SHEAR_FRAME.variable(n).is_some(), "{n}");
        }
        assert_eq!(SHEAR_FRAME.variables.len(), 6 + 9 * MAX_STOREYS);
    }

    /// FMI 3.0: `x[i]` is element `i` of the array `x`, whose value
    /// reference is `x[1]`'s; elements past the first are no variables.
    #[test]
    fn fmi3_arrays_are_the_2_0_scalars() {
        use model_description::fmi3::ArrayAt;
        let md = &*SHEAR_FRAME;
        assert_eq!(md.fmi3_type(md.variable("n").unwrap()), "UInt64");
        assert_eq!(md.fmi3_type(md.variable("Fx[3]").unwrap()), "Float64");
        for (name, base) in [("Fx", vr::FX), ("u", vr::U), ("period", vr::PERIOD)] {
            for i in [1, 7, MAX_STOREYS] {
                let element = format!("{name}[{i}]");
                assert_eq!(md.fmi3_vr(&element), Some(vr::at(base, 1)), "{element}");
                let at = md.fmi3_array_at(vr::at(base, i));
                let want = ArrayAt {
                    array: md.fmi3_element(&element).unwrap().0,
                    derivative: false,
                    element: i,
                };
                assert_eq!(at, Some(want));
                assert_eq!(want.array, name);
            }
        }
        for bad in ["Fx[0]", "Fx[21]", "Fx", "x[1]", "Fx[1", "ag"] {
            assert!(md.fmi3_element(bad).is_none(), "{bad}");
        }
        assert_eq!(md.fmi3_vr("ag"), Some(vr::AG));
        assert!(
            md.fmi3_array_at(vr::AG).is_none() && md.fmi3_array_at(md.fmi3_time_vr()).is_none()
        );
        // der(Fx[i]): the inputs' derivatives in table order after der(ag)
        let der_fx = md.fmi3_input_derivative_vr(1);
        let at = md.fmi3_array_at(der_fx + 4).unwrap();
        assert_eq!((at.array, at.derivative, at.element), ("Fx", true, 5));
        let at = md.fmi3_array_at(der_fx + MAX_STOREYS as u32).unwrap();
        assert_eq!((at.array, at.derivative, at.element), ("Fz", true, 1));
    }

    #[test]
    fn floor_acceleration_feeds_through_only_its_own_force() {
        let a3 = SHEAR_FRAME.variable("a[3]").unwrap();
        let inputs: Vec<&str> = a3
            .depends_on
            .iter()
            .copied()
            .filter(|d| SHEAR_FRAME.variable(d).unwrap().causality == Causality::Input)
            .collect();
        assert_eq!(inputs, ["Fx[3]"]);
    }
}
