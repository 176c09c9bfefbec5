//! RoundBody.fmu for the FMI 2.0 fuzz driver (`fmi2-fuzz-driver`, shared
//! with RockingBlock): its C API, its inputs `agx`, `agy`, `av`, its
//! parameters and what they must make, its outputs' ranges, and the known
//! finding the driver lets pass. Used by the proptest suite
//! (`tests/fmi2_fuzz.rs`) and the libFuzzer target
//! (`fuzz/fuzz_targets/round_body.rs`, which includes this file with
//! `#[path]`).
//!
//! Beyond the shared checks ([`fmi2_fuzz_driver`]), the strict ones
//! ([`Model::STRICT`]): `fmi2ExitInitializationMode` succeeds exactly when
//! the parameters make a valid round body (docs/round-body.md, "Bad
//! input": `rocking::Params::build` of the driver's own copy of the values,
//! a round shape, `IcAxial > 0` for the lumped model, `maxSteps >= 1`,
//! finite `psi0` and initial angular velocities; an instance of Model
//! Exchange only on the rigid bed), the refusal naming a
//! parameter (`name = value`); a step refused with `fmi2Error` names an
//! input or the communication point and leaves the state (theta .. yG) as
//! it was; Real outputs and calculated parameters are finite
//! (`frictionDemand` at most 1e60, which it is where `Fz <= 0`), `theta` in
//! [0, pi/2] equals `asin(sqrt(ex^2 + ey^2))`, `psi` in (-pi, pi], `regime`
//! one of RegimeKind's codes 1 ..= 7, `thetaOv <= alpha` (equal on the rigid
//! bed; a flexible bed's resultant shortens the lever), `impacts` >= 0.

#![allow(dead_code)]

use std::ffi::c_int;

use fmi2_export::model_description::{LogCategory, Variable};
use fmi2_export::test_host::Message;
use fmi2_fuzz_driver::rigid_body::{rigid_body_params, SHAPES};
use fmu_round_body::description::{enums, vr, LOG_CATEGORIES, ROUND_BODY, VARIABLES};
use rocking::model::LawKind;
use rocking::{Formulation, Params};

pub use fmi2_fuzz_driver::*;

/// The FMU under test.
pub struct RoundBody;

/// The driver on RoundBody.fmu.
pub type Driver = fmi2_fuzz_driver::Driver<RoundBody>;

/// The inputs.
pub const INPUTS: [u32; 3] = [vr::AGX, vr::AGY, vr::AV];

/// Instances the driver juggles at once.
pub const SLOTS: usize = 3;

/// What stands for `+inf` at the boundary (docs/round-body.md): the most
/// `frictionDemand` may be.
pub const UNBOUNDED: f64 = 1e60;

/// |agx|, |agy| or |av| (m/s2) from which the known overflow is let pass (the
/// smallest seen is 3.6e31 after a step of 1 s; steps of up to 1e300 s
/// leave larger step sizes in the state).
pub const KNOWN_OVERFLOW: f64 = 1e20;

/// The message of the known overflow.
pub const NON_FINITE_STATE: &str = "the integration produced a non-finite state";

/// The outputs of the state alone (theta .. yG): they do not depend on the
/// inputs, so they read back whatever the inputs are.
pub const STATE_OUTPUTS: [u32; 10] = [
    vr::THETA,
    vr::PSI,
    vr::THETA_OVER_ALPHA,
    vr::EX,
    vr::EY,
    vr::OMEGA_X,
    vr::OMEGA_Y,
    vr::OMEGA_Z,
    vr::XG,
    vr::YG,
];

/// Whether the model description declares Model Exchange (the driver then
/// expects `fmi2ModelExchange` instances to be made).
pub fn model_exchange() -> bool {
    ROUND_BODY.model_exchange.is_some()
}

/// Decodes `data` into operations on RoundBody instances.
pub fn decode(data: &[u8]) -> Vec<Op> {
    fmi2_fuzz_driver::decode::<RoundBody>(data)
}

/// Decodes `data` and runs it: the fuzz target's and the proptests' entry.
pub fn run_bytes(data: &[u8]) -> Stats {
    fmi2_fuzz_driver::run_bytes::<RoundBody>(data)
}

impl Model for RoundBody {
    const API: Fmi2Api = fmi2_fuzz_driver::fmi2_api!(fmu_round_body);
    const GUID: &'static str = fmu_round_body::GUID;
    const VARIABLES: &'static [Variable] = VARIABLES;
    const LOG_CATEGORIES: &'static [LogCategory] = LOG_CATEGORIES;
    const SLOTS: usize = SLOTS;
    const MODEL_EXCHANGE: bool = ROUND_BODY.model_exchange.is_some();
    const STATES: usize = 8;
    const EVENT_INDICATORS: usize = match &ROUND_BODY.model_exchange {
        Some(m) => m.event_indicators as usize,
        None => 0,
    };
    const ME_LENGTH: usize = 7;
    const INPUTS: &'static [u32] = &INPUTS;
    const STATE_OUTPUTS: &'static [u32] = &STATE_OUTPUTS;
    const STEP_REFUSAL_NAMES: &'static [&'static str] =
        &["agx", "agy", "av", "currentCommunicationPoint", "stopTime"];
    const STRICT: bool = true;
    type Params = Params;

    /// The physics parameters, mapped independently of the FMU's binding
    /// (docs/round-body.md: a round base on the rigid bed, `theta0` the
    /// initial tilt); `None` for a code that is no item of its enumeration
    /// or a rectangle.
    fn params(stored: &Stored) -> Option<Params> {
        // the bed: RockingBlock's codes (docs/round-body.md, "Flexible beds")
        let own = Params {
            interface: match stored.int[vr::INTERFACE as usize] {
                1 => LawKind::Rigid,
                2 => LawKind::Elastic,
                3 => LawKind::ElastoPlastic,
                _ => return None,
            },
            kn: stored.real[vr::KN as usize],
            fm: stored.real[vr::FM as usize],
            formulation: match stored.int[vr::FORMULATION as usize] {
                1 => Formulation::Costa,
                2 => Formulation::ShiftingPivot,
                _ => return None,
            },
            theta0: stored.real[vr::THETA0 as usize],
            ..Params::default()
        };
        rigid_body_params::<Self>(stored, &SHAPES[2..], own)
    }

    /// docs/round-body.md, "Bad input".
    fn valid(stored: &Stored) -> bool {
        let r = |k: u32| stored.real[k as usize];
        let lumped = stored.int[vr::MASS_MODEL as usize] == enums::LUMPED;
        let ic_axial = r(vr::IC_AXIAL);
        stored.int[vr::MAX_STEPS as usize] >= 1
            && [vr::PSI0, vr::OMEGA_X0, vr::OMEGA_Y0, vr::OMEGA_Z0]
                .iter()
                .all(|&k| r(k).is_finite())
            && (!lumped || (ic_axial.is_finite() && ic_axial > 0.0))
            && Self::params(stored).is_some_and(|p| p.build().is_ok())
    }

    /// Model Exchange runs on the rigid bed and on a flexible one with
    /// `costa` (docs/round-body.md).
    fn valid_for(stored: &Stored, model_exchange: bool) -> bool {
        Self::valid(stored)
            && !(model_exchange
                && stored.int[vr::INTERFACE as usize] != enums::RIGID
                && stored.int[vr::FORMULATION as usize] == enums::SHIFTING_PIVOT)
    }

    fn set_input(b: &mut Bytes, s: u8) -> Op {
        // an input: around the uplift threshold g tan(alpha) = 3.27
        // m/s2 of the default drum, or awkward (NaN, inf, 1e300, ...)
        let input = INPUTS[b.below(3)];
        let x = if b.chance(6) {
            b.int() as f64 * 2.5
        } else {
            b.awkward()
        };
        Op::SetReal(s, vec![input], vec![x])
    }

    fn set_input_derivative(b: &mut Bytes, s: u8) -> Op {
        let input = INPUTS[b.below(3)];
        let x = if b.chance(6) {
            b.int() as f64 * 10.0
        } else {
            b.awkward()
        };
        Op::SetInputDerivatives(s, vec![input], vec![1], vec![x])
    }

    /// docs/round-body.md's ranges.
    fn real_problem(r: u32, x: f64) -> Option<String> {
        use std::f64::consts::{FRAC_PI_2, PI};
        let ok = match r {
            vr::THETA => (0.0..=FRAC_PI_2).contains(&x),
            vr::PSI => x > -PI && x <= PI,
            vr::EX | vr::EY => x.abs() <= 1.0,
            vr::THETA_OVER_ALPHA => x >= 0.0,
            vr::FRICTION_DEMAND => (0.0..=UNBOUNDED).contains(&x),
            vr::MASS | vr::WEIGHT | vr::R0 | vr::IO => x > 0.0,
            // atan(Ro/hG): pi/2 where hG underflows to 0 (H = 5e-324)
            vr::ALPHA | vr::THETA_OV => x > 0.0 && x <= FRAC_PI_2,
            vr::ETA_HOUSNER => x <= 1.0,
            _ => true,
        };
        let name = VARIABLES.iter().find(|v| v.vr == r).map_or("?", |v| v.name);
        (!ok).then(|| format!("{name} = {x} is outside its range"))
    }

    fn check_reals(r: &[u32], out: &[f64]) {
        let of = |v: u32| r.iter().position(|&q| q == v).map(|i| out[i]);
        if let (Some(theta), Some(ex), Some(ey)) = (of(vr::THETA), of(vr::EX), of(vr::EY)) {
            // theta = asin(sqrt(ex^2 + ey^2)) (docs/round-body.md), to
            // rounding: asin's slope is 1/cos(theta)
            let want = ex.hypot(ey).min(1.0).asin();
            let tol = 1e-12 / theta.cos().max(1e-6);
            assert!(
                (theta - want).abs() <= tol,
                "theta = {theta}, asin(|(ex, ey)|) = {want} (ex = {ex}, ey = {ey})"
            );
        }
        if let (Some(alpha), Some(theta_ov)) = (of(vr::ALPHA), of(vr::THETA_OV)) {
            // alpha on the rigid bed, before it on a flexible one
            assert!(
                theta_ov <= alpha,
                "thetaOv = {theta_ov} beyond alpha = {alpha}"
            );
        }
    }

    fn integer_in_range(r: u32, x: c_int) -> Option<bool> {
        match r {
            vr::REGIME => Some((enums::REST..=enums::OUT_OF_RANGE).contains(&x)),
            vr::IMPACTS => Some(x >= 0),
            _ => None,
        }
    }

    /// The known findings (tests/fmi2_fuzz.rs, `finding_*`), where
    /// fmi2DoStep fails with "the integration produced a non-finite state"
    /// (fmi2Error naming no variable, the state kept): after a step, `agx`
    /// or `agy` of about 1e31 m/s2 and more (inside the 1e100 bound the FMU
    /// accepts; from rest the same input overturns the body), or `av`
    /// reaching 5e96 m/s2 in a step; a body the parameters accept whose
    /// inertia is absurd beside m R0^2 (lumped `Ic` = 1e24 kg m2 with m =
    /// 1e4 kg) started upright with an angular velocity; a time or step of
    /// 1e300 s (the state at t = 2e300). Tolerated when the time or the step
    /// reaches 1e15 s, an input reaches [`KNOWN_OVERFLOW`] over the step (or
    /// the driver does not know the inputs' slopes) or the body is extreme
    /// ([`extreme_body`]).
    fn known_finding(d: &mut Driver, k: u8, t: f64, h: f64) -> bool {
        // the inputs over the step, where the driver knows their slopes
        let inputs = d.get_real(k, &INPUTS);
        let derivatives = d.derivatives(k).map(<[f64]>::to_vec);
        let huge_input = match (inputs, derivatives) {
            (Some(x), Some(d)) => (0..3).any(|i| {
                x[i].abs().max((x[i] + d[i] * h).abs()) >= KNOWN_OVERFLOW || !h.is_finite()
            }),
            _ => true,
        };
        let extreme = extreme_body(d, k);
        huge_input || extreme || t.abs().max(h) >= 1e15
    }

    fn known_refusal(recent: &[Message]) -> bool {
        recent.iter().any(|m| m.text.contains(NON_FINITE_STATE))
    }
}

/// Whether the body is one of the known finding's absurd ones
/// ([`Model::known_finding`]): mass, R0, IO or g outside 1e-30..1e30, an
/// initial angular velocity of 1e15 rad/s or more (g = 5e-324 m/s2 with
/// omegaZ0 = 1e300 rad/s and av = 2 m/s2 gives the non-finite state), or
/// an inertia about the centre of mass (Ic, or the axial one) beyond
/// 1e-12..1e12 times m R0^2.
pub fn extreme_body(d: &mut Driver, k: u8) -> bool {
    let Some(x) = d.get_real(k, &[vr::MASS, vr::R0, vr::IO]) else {
        return true;
    };
    let Some(stored) = d.stored(k).cloned() else {
        return true;
    };
    let [m, r0, io] = [x[0], x[1], x[2]];
    let r = |q: u32| stored.real[q as usize];
    let m_r0 = m * r0 * r0;
    let axial = if stored.int[vr::MASS_MODEL as usize] == enums::LUMPED {
        r(vr::IC_AXIAL)
    } else {
        let ri = if stored.int[vr::SHAPE as usize] == enums::HOLLOW_CIRCLE {
            r(vr::RI)
        } else {
            0.0
        };
        m * (r(vr::RO).powi(2) + ri * ri) / 2.0
    };
    let out = |x: f64, lo: f64, hi: f64| !(lo..=hi).contains(&x);
    let spin = [vr::OMEGA_X0, vr::OMEGA_Y0, vr::OMEGA_Z0]
        .iter()
        .any(|&q| r(q).abs() >= 1e15);
    spin || [m, r0, io, r(vr::G)].iter().any(|&x| out(x, 1e-30, 1e30))
        || out((io - m_r0) / m_r0, 1e-12, 1e12)
        || out(axial / m_r0, 1e-12, 1e12)
}
