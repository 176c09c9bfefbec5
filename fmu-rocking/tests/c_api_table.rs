//! The variable table through the exported C functions: start values,
//! default tolerance, the GUID and type checks of fmi2Instantiate, declared
//! dependencies, the serialized state's counters (the shared host `host/`).

mod host;

use std::ffi::{c_char, CStr};
use std::ptr;

use fmi2_export::model_description::{Causality, Type};
use fmu_rocking::description::VARIABLES;
use rocking::Params;

use fmu_rocking::*;
use host::*;

/// The name of the variable with value reference `r`.
fn name(r: u32) -> &'static str {
    VARIABLES.iter().find(|v| v.vr == r).unwrap().name
}

#[test]
fn start_values_are_the_physics_defaults() {
    let p = Params::default();
    let real = |name: &str| match ROCKING_BLOCK.variable(name).unwrap().ty {
        Type::Real { start, .. } => start.unwrap(),
        _ => panic!("{name}"),
    };
    let host = Host::new();
    assert_eq!(host.enter_init(), fmi2OK);
    let pairs = [
        ("B", p.b),
        ("L", p.l),
        ("t", p.t),
        ("Ro", p.ro),
        ("Ri", p.ri),
        ("H", p.h),
        ("rho", p.rho),
        ("W", p.w),
        ("hG", p.hg),
        ("Ic", p.ic),
        ("kn", p.kn),
        ("fm", p.fm),
        ("eta", p.eta),
        ("g", p.g),
        ("theta", p.theta0),
        ("omega", p.omega0),
    ];
    for (n, x) in pairs {
        assert_eq!(real(n).to_bits(), x.to_bits(), "{n}");
    }
    // the enumeration starts are the physics defaults too
    use fmu_rocking::description::enums::*;
    use rocking::model::{LawKind, MassKind, ShapeKind};
    let expect = |kind_ok: bool, r: u32, v: i32| {
        assert!(kind_ok);
        assert_eq!(host.integer(name(r)), v, "vr {r}");
    };
    expect(
        p.shape == ShapeKind::SolidRectangle,
        vr::SHAPE,
        SOLID_RECTANGLE,
    );
    expect(p.mass_model == MassKind::Prism, vr::MASS_MODEL, PRISM);
    expect(
        p.interface == LawKind::ElastoPlastic,
        vr::INTERFACE,
        ELASTO_PLASTIC,
    );
    expect(
        p.formulation == rocking::Formulation::ShiftingPivot,
        vr::FORMULATION,
        SHIFTING_PIVOT,
    );
    expect(
        p.restitution == rocking::Restitution::Housner,
        vr::RESTITUTION,
        HOUSNER,
    );
}

#[test]
fn default_tolerance_is_the_engines() {
    assert_eq!(
        ROCKING_BLOCK.default_experiment.tolerance,
        rocking::dynamics::DEFAULT_RTOL
    );
}

#[test]
fn instantiate_checks_the_guid_and_the_type() {
    let wrong = "{00000000-0000-0000-0000-000000000000}";
    let c = bare_instance(Some("x"), fmi2CoSimulation, Some(wrong));
    assert!(c.is_null());
    // Model Exchange is supported, an unknown fmuType is not
    let c = bare_instance(Some("x"), fmi2ModelExchange, Some(GUID));
    assert!(!c.is_null());
    unsafe { fmi2FreeInstance(c) };
    assert!(bare_instance(Some("x"), 7, Some(GUID)).is_null());
    assert!(bare_instance(None, fmi2CoSimulation, Some(GUID)).is_null());
    unsafe {
        assert_eq!(
            CStr::from_ptr(fmi2GetTypesPlatform() as *const c_char)
                .to_str()
                .unwrap(),
            "default"
        );
        assert_eq!(CStr::from_ptr(fmi2GetVersion()).to_str().unwrap(), "2.0");
        // NULL and foreign components are refused, never dereferenced blindly.
        assert_eq!(fmi2Reset(ptr::null_mut()), fmi2Error);
        let mut junk = [0u64; 64];
        assert_eq!(fmi2Reset(junk.as_mut_ptr() as fmi2Component), fmi2Error);
    }
}

/// The values of every initial unknown at one configuration.
fn initial_unknowns(config: &[(u32, i32)], reals: &[(u32, f64)]) -> Vec<(u32, f64)> {
    let h = Host::new();
    for &(r, x) in config {
        assert_eq!(h.set_integer(name(r), x), fmi2OK);
    }
    for &(r, x) in reals {
        assert_eq!(h.set_real(name(r), x), fmi2OK);
    }
    assert_eq!(h.enter_init(), fmi2OK);
    VARIABLES
        .iter()
        .filter(|v| v.is_initial_unknown())
        .map(|v| {
            let x = match v.ty {
                Type::Real { .. } => h.real(v.name),
                Type::Integer { .. } => h.integer(v.name) as f64,
                Type::Boolean { .. } => {
                    let mut b = 0;
                    assert_eq!(unsafe { fmi2GetBoolean(h.c, &v.vr, 1, &mut b) }, fmi2OK);
                    b as f64
                }
                _ => unreachable!(),
            };
            (v.vr, x)
        })
        .collect()
}

/// Every real parameter, start value or input that changes an initial
/// unknown is among its declared dependencies (ModelStructure).
#[test]
fn declared_dependencies_cover_the_real_ones() {
    let knowns: Vec<_> = VARIABLES
        .iter()
        .filter(|v| {
            matches!(v.ty, Type::Real { .. })
                && (matches!(v.causality, Causality::Parameter | Causality::Input)
                    || v.initial == Some(fmi2_export::model_description::Initial::Exact))
        })
        .collect();
    for shape in 1..=4 {
        for mass in 1..=2 {
            for law in 1..=3 {
                for formulation in 1..=2 {
                    let config = [
                        (vr::SHAPE, shape),
                        (vr::MASS_MODEL, mass),
                        (vr::INTERFACE, law),
                        (vr::FORMULATION, formulation),
                    ];
                    let base_reals = [(vr::THETA, 0.02), (vr::OMEGA, 0.1), (vr::AG, 1.0)];
                    let base = initial_unknowns(&config, &base_reals);
                    for k in &knowns {
                        let x0 = base_reals
                            .iter()
                            .find(|(r, _)| *r == k.vr)
                            .map(|(_, x)| *x)
                            .unwrap_or_else(|| match k.ty {
                                Type::Real { start, .. } => start.unwrap(),
                                _ => unreachable!(),
                            });
                        let mut reals = base_reals.to_vec();
                        reals.retain(|(r, _)| *r != k.vr);
                        reals.push((k.vr, x0 * 1.01 + 1e-3));
                        let changed = initial_unknowns(&config, &reals);
                        for ((r, a), (_, b)) in base.iter().zip(&changed) {
                            if a.to_bits() != b.to_bits() {
                                let v = VARIABLES.iter().find(|v| v.vr == *r).unwrap();
                                assert!(
                                    v.depends_on.contains(&k.name),
                                    "{} changes with {} (config {config:?}) but does not declare it",
                                    v.name,
                                    k.name
                                );
                            }
                        }
                    }
                }
            }
        }
    }
}

/// The serialized state carries both counts, the opened flag, the Model
/// Exchange fields, the terminal condition and the last step's `av` (each
/// read back equal to what was written); a state claiming more impacts than
/// zero crossings is refused (every impact is a crossing).
#[test]
fn serialized_state_keeps_both_counts_and_refuses_more_impacts_than_crossings() {
    use fmi2_export::bytes::{ByteReader, ByteWriter};
    use fmi2_export::Slave;
    use fmu_rocking::slave::Saved;
    use rocking::dynamics::{OutOfRange, Terminal};
    let model = Params::default().build().unwrap();
    let sim = rocking::dynamics::Simulator::new(model, 1e-9);
    let mut c = sim.continuous(0.01, 0.0, 0.0);
    c.state.impacts = 3;
    c.state.zero_crossings = 7;
    c.state.opened = true;
    // the Model Exchange toe and last impact speed too
    c.side = -1.0;
    c.left_with = 0.25;
    let round_trip = |s: &Saved| {
        let mut w = ByteWriter::new();
        RockingSlave::write_state(s, &mut w);
        RockingSlave::read_state(&mut ByteReader::new(&w.buf))
    };
    let none = Saved {
        continuous: c,
        terminal: None,
        av_end: None,
    };
    assert_eq!(round_trip(&none).unwrap(), none);
    for condition in [
        OutOfRange::LiftOff,
        OutOfRange::BaseCrushing,
        OutOfRange::RestUnstable,
    ] {
        let ended = Saved {
            continuous: c,
            terminal: Some(Terminal {
                t: 1.25,
                condition,
                av: -9.81,
            }),
            av_end: Some(-3.5),
        };
        assert_eq!(round_trip(&ended).unwrap(), ended);
    }
    c.state.impacts = 8;
    let e = round_trip(&Saved {
        continuous: c,
        ..none
    })
    .unwrap_err();
    assert!(
        e.contains("impacts = 8") && e.contains("zero crossings = 7"),
        "{e}"
    );
}
