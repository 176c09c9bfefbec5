//! RoundBody on the flexible beds (`interface` elastic and elastoPlastic,
//! `kn`, `fm`, `formulation`): the FMU against `rocking::spatial` run
//! directly with the same parameters and inputs, FMI 2.0 against 3.0, the
//! contact outputs against the bed's law, bad values refused naming the
//! variable. The planar limit against RockingBlock is in `tests/planar.rs`;
//! Model Exchange on these beds in `tests_me.rs`.

use fmi2_export::test_host;
use fmi2_export::types::*;
use rocking::dynamics::VerticalInput;
use rocking::interface::RoundBed;
use rocking::model::{LawKind, MassKind, ShapeKind};
use rocking::spatial::{PlanInput, Spatial, SpatialState};
use rocking::{Formulation, Params, Restitution};

use crate::description::{enums, vr, DEFAULT_TOLERANCE};
use crate::tests::{step_inputs, Fmi3, DT, INPUTS};

type Host = test_host::Host<crate::RoundBodySlave>;

/// A bed of `kn = 1e8 Pa/m` under the default drum (Ro 0.5 m, H 3 m, 1800
/// kg/m3: W = 41.6 kN), crushing at `fm = 0.3 MPa` (fm A = 236 kN).
const KN: f64 = 1e8;
const FM: f64 = 3e5;

/// Steps of the comparisons: 3 s of `tests::ground`.
const STEPS: usize = 300;

/// The four beds: (interface, formulation).
const BEDS: [(i32, i32); 4] = [
    (enums::ELASTIC, enums::SHIFTING_PIVOT),
    (enums::ELASTIC, enums::COSTA),
    (enums::ELASTO_PLASTIC, enums::SHIFTING_PIVOT),
    (enums::ELASTO_PLASTIC, enums::COSTA),
];

/// The FMU's start values with the bed, as `rocking::Params` written out
/// here (not through the slave's mapping).
fn physics_params(interface: i32, formulation: i32) -> Params {
    Params {
        shape: ShapeKind::SolidCircle,
        ro: 0.5,
        ri: 0.3,
        mass_model: MassKind::Prism,
        h: 3.0,
        rho: 1800.0,
        w: 1e5,
        hg: 1.5,
        ic: 1e4,
        interface: match interface {
            enums::ELASTIC => LawKind::Elastic,
            _ => LawKind::ElastoPlastic,
        },
        kn: KN,
        fm: FM,
        formulation: match formulation {
            enums::COSTA => Formulation::Costa,
            _ => Formulation::ShiftingPivot,
        },
        restitution: Restitution::Housner,
        eta: 0.9,
        g: 9.81,
        theta0: 0.0,
        ..Params::default()
    }
}

fn on_bed(interface: i32, formulation: i32) -> Host {
    let h = Host::named("flexible");
    h.check("interface", h.set_integer("interface", interface));
    h.check("formulation", h.set_integer("formulation", formulation));
    h.check("kn", h.set_real("kn", KN));
    h.check("fm", h.set_real("fm", FM));
    h.init_with(None);
    h
}

/// Reals compared bit for bit, then the contact's.
const STATE: [u32; 10] = [
    vr::THETA,
    vr::PSI,
    vr::EX,
    vr::EY,
    vr::OMEGA_X,
    vr::OMEGA_Y,
    vr::OMEGA_Z,
    vr::XG,
    vr::YG,
    vr::FZ,
];
const CONTACT: [u32; 3] = [vr::CONTACT_AREA, vr::CRUSHED_AREA, vr::AF];

/// Sets step `k`'s inputs and their slopes on a 2.0 instance.
fn set_inputs(h: &Host, k: usize) {
    let (a, da) = step_inputs(k);
    h.check(
        "fmi2SetReal",
        h.set_reals(&INPUTS.iter().copied().zip(a).collect::<Vec<_>>()),
    );
    for (r, d) in INPUTS.iter().zip(da) {
        h.check("derivative", h.set_input_derivative_vr(*r, 1, d));
    }
}

/// The FMU in co-simulation on each bed against `Spatial::advance` with the
/// same parameters and inputs (two components and av, with their slopes):
/// the same state bits at every communication point, the same impacts; the
/// contact outputs are the bed's law (`RoundBed::reaction` at the tilt under
/// m (g + av)) bit for bit. The runs rock, and the crushing ones crush.
#[test]
fn co_simulation_is_the_physics_run_directly() {
    for (interface, formulation) in BEDS {
        let p = physics_params(interface, formulation);
        let body = Spatial::new(&p, None, DEFAULT_TOLERANCE).unwrap();
        let bed = RoundBed::new(body.model.interface).unwrap();
        let mut st = SpatialState::tilted(&body, 0.0, 0.0, [0.0; 3]);
        let h = on_bed(interface, formulation);
        let (mut peak, mut crushed, mut open) = (0.0f64, 0.0f64, 0);
        for k in 0..STEPS {
            set_inputs(&h, k);
            let (a, da) = step_inputs(k);
            let t0 = k as f64 * DT;
            h.check("fmi2DoStep", h.do_step(t0, DT));
            body.advance(
                &mut st,
                t0 + DT,
                PlanInput {
                    a: [a[0], a[1]],
                    da: [da[0], da[1]],
                },
                VerticalInput {
                    av: a[2],
                    dav: da[2],
                },
            );
            // the inputs at the communication point: step k + 1's
            let (next, _) = step_inputs(k + 1);
            h.check(
                "fmi2SetReal",
                h.set_reals(&INPUTS.iter().copied().zip(next).collect::<Vec<_>>()),
            );
            let (s, x) = h.get_reals_vr(&STATE);
            assert_eq!(s, fmi2OK, "{:?}", h.messages());
            let want = [
                st.theta(),
                {
                    let d = st.contact_direction();
                    d[1].atan2(d[0])
                },
                st.e[0],
                st.e[1],
                st.omega[0],
                st.omega[1],
                st.omega[2],
                st.xg[0],
                st.xg[1],
                body.contact_force(&st, [next[0], next[1]], next[2])[2],
            ];
            for (i, (got, want)) in x.iter().zip(want).enumerate() {
                // psi is the contact's last direction upright
                if i == 1 && st.theta() == 0.0 {
                    continue;
                }
                assert_eq!(
                    got.to_bits(),
                    want.to_bits(),
                    "bed {interface}/{formulation}, step {k}, {}: {got} against {want}",
                    crate::description::ROUND_BODY.variables[STATE[i] as usize].name
                );
            }
            assert_eq!(h.integer("impacts") as u64, st.impacts, "step {k}");
            let m = body.mass();
            let r = bed.reaction(st.e, m * (9.81 + next[2])).unwrap();
            let (s, c) = h.get_reals_vr(&CONTACT);
            assert_eq!(s, fmi2OK);
            assert_eq!(
                c,
                [r.contact_area, r.crushed_area, r.contact.af],
                "step {k}"
            );
            peak = peak.max(st.theta());
            crushed = crushed.max(r.crushed_area);
            let regime = h.integer("regime");
            open += matches!(regime, enums::PARTIAL_CONTACT | enums::PARTIAL_CRUSHING) as u32;
        }
        let theta_c = body.model.interface.theta_c();
        eprintln!(
            "bed {interface}/{formulation}: peak {peak:.4} rad, thetaC {theta_c:.2e}, largest crushed area {crushed:.3e} m2, {} impacts, {open} samples with the heel open",
            st.impacts
        );
        assert!(peak > 0.02 && !st.overturned, "the run must rock: {peak}");
        assert!(open > 10, "the heel must open");
        if interface == enums::ELASTO_PLASTIC {
            assert!(peak > 10.0 * theta_c && crushed > 0.0, "the toe must crush");
        } else {
            assert_eq!(crushed, 0.0);
        }
    }
}

/// FMI 2.0 and 3.0 of one binary on a crushing bed, same inputs: the same
/// bits of every output (the contact's included) at every step.
#[test]
fn fmi2_and_fmi3_give_the_same_bits_on_a_crushing_bed() {
    let h = on_bed(enums::ELASTO_PLASTIC, enums::COSTA);
    let three = Fmi3::with(
        &[(vr::KN, KN), (vr::FM, FM)],
        &[
            (vr::INTERFACE, enums::ELASTO_PLASTIC as i64),
            (vr::FORMULATION, enums::COSTA as i64),
        ],
    );
    let md = &crate::description::ROUND_BODY;
    let der: Vec<u32> = (0..3).map(|k| md.fmi3_input_derivative_vr(k)).collect();
    let reals: Vec<u32> = (vr::THETA..=vr::FRICTION_DEMAND).chain(CONTACT).collect();
    let mut regimes = std::collections::BTreeSet::new();
    for k in 0..STEPS {
        set_inputs(&h, k);
        h.check("fmi2DoStep", h.do_step(k as f64 * DT, DT));
        let (a, da) = step_inputs(k);
        let mut vrs = INPUTS.to_vec();
        vrs.extend(&der);
        let mut x = a.to_vec();
        x.extend(da);
        assert_eq!(three.set(&vrs, &x), 0, "{:?}", three.log);
        let (status, t) = three.step(k as f64 * DT, DT);
        assert_eq!((status, t), (0, k as f64 * DT + DT), "{:?}", three.log);
        let (s, two) = h.get_reals_vr(&reals);
        assert_eq!(s, fmi2OK);
        let bits = |x: &[f64]| x.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&three.reals(&reals)), bits(&two), "step {k}");
        let regime = h.integer("regime");
        assert_eq!(three.int64(vr::REGIME), regime as i64, "step {k}");
        regimes.insert(regime);
    }
    // full contact, the heel open, and crushing with it
    for r in [
        enums::FULL_CONTACT,
        enums::PARTIAL_CONTACT,
        enums::PARTIAL_CRUSHING,
    ] {
        assert!(regimes.contains(&r), "{r} not reached: {regimes:?}");
    }
}

/// Upright at rest on a flexible bed: the whole base closed (pi Ro²),
/// nothing crushed, the resultant under the centre (af = Ro), full
/// contact; where g + av <= 0 the bed carries nothing (outOfRange, 0).
#[test]
fn at_rest_on_a_flexible_bed_the_whole_base_carries() {
    for interface in [enums::ELASTIC, enums::ELASTO_PLASTIC] {
        let h = on_bed(interface, enums::SHIFTING_PIVOT);
        let area = std::f64::consts::PI * 0.25;
        let [a, c, af] = h.reals(&["contactArea", "crushedArea", "af"])[..] else {
            unreachable!()
        };
        assert!((a - area).abs() <= 1e-15 * area, "{a} against {area}");
        assert_eq!(c, 0.0);
        assert!((af - 0.5).abs() <= 1e-15, "af {af}");
        assert_eq!(h.integer("regime"), enums::FULL_CONTACT);
        h.check("av", h.set_real("av", -9.81));
        assert_eq!(h.reals(&["contactArea", "crushedArea", "af"]), [0.0; 3]);
        assert_eq!(h.integer("regime"), enums::OUT_OF_RANGE);
    }
}

type Case<'a> = (&'a dyn Fn(&Host), &'a str);

/// Bad values of the bed's parameters are refused naming the variable.
#[test]
fn bad_bed_parameters_are_refused_naming_them() {
    let cases: [Case; 6] = [
        (
            &|h| {
                h.check("set", h.set_integer("interface", enums::ELASTIC));
                h.check("set", h.set_real("kn", -1e8));
            },
            "kn = -100000000",
        ),
        (
            &|h| {
                h.check("set", h.set_integer("interface", enums::ELASTO_PLASTIC));
                h.check("set", h.set_real("kn", f64::NAN));
            },
            "kn = NaN",
        ),
        (
            // the rest position unstable: kn Is < W hG
            &|h| {
                h.check("set", h.set_integer("interface", enums::ELASTIC));
                h.check("set", h.set_real("kn", 1e5));
            },
            "kn = 100000",
        ),
        (
            &|h| {
                h.check("set", h.set_integer("interface", enums::ELASTO_PLASTIC));
                h.check("set", h.set_real("fm", 0.0));
            },
            "fm = 0",
        ),
        (
            // the section crushes at rest: W > fm A
            &|h| {
                h.check("set", h.set_integer("interface", enums::ELASTO_PLASTIC));
                h.check("set", h.set_real("fm", 1e4));
            },
            "fm = 10000",
        ),
        (
            // a value far from 1 in exponent form, not 301 digits
            &|h| {
                h.check("set", h.set_integer("interface", enums::ELASTIC));
                h.check("set", h.set_real("kn", 1e300));
            },
            "kn = 1e300: ",
        ),
    ];
    for (set, message) in cases {
        let h = Host::named("bad");
        set(&h);
        assert_eq!(h.initialize(), fmi2Error, "{message}");
        assert!(h.logged(message), "{message}: {:?}", h.errors());
    }
    // an enumeration code that is no item: refused when set, naming it
    for (name, code) in [("interface", 0), ("interface", 4), ("formulation", 3)] {
        let h = Host::named("bad code");
        assert_eq!(h.set_integer(name, code), fmi2Error);
        assert!(
            h.errors()
                .iter()
                .any(|m| m.contains(name) && m.contains(&code.to_string())),
            "{name} = {code}: {:?}",
            h.errors()
        );
    }
}
