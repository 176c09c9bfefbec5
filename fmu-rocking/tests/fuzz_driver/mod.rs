//! RockingBlock.fmu for the FMI 2.0 fuzz driver (`fmi2-fuzz-driver`,
//! shared with RoundBody): its C API, its inputs `ag`, `av`, its parameters
//! and what they must make, its outputs' ranges, and the steps the driver
//! skips. Used by the proptest suite (`tests/c_api_fuzz.rs`) and the
//! libFuzzer target (`fuzz/fuzz_targets/c_api.rs`, which includes this file
//! with `#[path]`).
//!
//! Beyond the shared checks ([`fmi2_fuzz_driver`]):
//! `fmi2ExitInitializationMode` succeeds exactly when the parameters the
//! driver set build a valid model (`rocking::Params::build`, fed from the
//! driver's own copy of the values, `maxSteps >= 1`, `mu >= 0`); Real
//! outputs, their derivatives, locals and calculated parameters are finite
//! (`thetaC` without crushing and `frictionDemand` at `Fz <= 0` stand at
//! 1e60), `regime` is 0..=5, `impacts` >= 0, `zeroCrossings` >= 0 and not
//! below `impacts` (every impact is a crossing) when both are read in one
//! call.

#![allow(dead_code)]

use std::ffi::c_int;

use fmi2_export::model_description::{LogCategory, Variable};
use fmi2_fuzz_driver::rigid_body::{rigid_body_params, SHAPES};
use fmu_rocking::description::{enums, vr, LOG_CATEGORIES, VARIABLES};
use rocking::model::LawKind;
use rocking::{Formulation, Params, RestraintKind};

pub use fmi2_fuzz_driver::*;

/// The FMU under test.
pub struct RockingBlock;

/// The driver on RockingBlock.fmu.
pub type Driver = fmi2_fuzz_driver::Driver<RockingBlock>;

/// Instances the driver juggles at once.
pub const SLOTS: usize = 4;

/// Event indicators the FMU declares.
const NZ: usize = fmu_rocking::description::EVENT_INDICATORS as usize;

/// thetaJo / thetaOv below which a step is skipped
/// ([`RockingBlock::skip_step`]).
pub const EXTREME_STIFFNESS: f64 = 1e-8;

/// Finite communication steps longer than this are not taken (counted in
/// [`Stats::steps_skipped`]): the FMU integrates whatever it is asked to, and
/// a body rocking or held by ag below uplift for 1e300 s is 1e300 s of work
/// (there is no work limit per step: reported, not what this driver looks
/// for). Non-finite, zero and negative steps are always passed.
pub const MAX_STEP: f64 = 10.0;

/// Decodes `data` into operations on RockingBlock instances.
pub fn decode(data: &[u8]) -> Vec<Op> {
    fmi2_fuzz_driver::decode::<RockingBlock>(data)
}

/// Decodes `data` and runs it: the fuzz target's and the proptests' entry.
pub fn run_bytes(data: &[u8]) -> Stats {
    fmi2_fuzz_driver::run_bytes::<RockingBlock>(data)
}

impl Model for RockingBlock {
    const API: Fmi2Api = fmi2_fuzz_driver::fmi2_api!(fmu_rocking);
    const GUID: &'static str = fmu_rocking::GUID;
    const VARIABLES: &'static [Variable] = VARIABLES;
    const LOG_CATEGORIES: &'static [LogCategory] = LOG_CATEGORIES;
    const SLOTS: usize = SLOTS;
    const MODEL_EXCHANGE: bool = true;
    const STATES: usize = 2;
    const EVENT_INDICATORS: usize = NZ;
    const ME_LENGTH: usize = 2;
    const INPUTS: &'static [u32] = &[vr::AG, vr::AV];
    type Params = Params;

    /// The physics parameters, mapped independently of the FMU's binding.
    fn params(stored: &Stored) -> Option<Params> {
        use enums::*;
        let r = |k: u32| stored.real[k as usize];
        let i = |k: u32| stored.int[k as usize];
        let own = Params {
            b: r(vr::B),
            l: r(vr::L),
            t: r(vr::T),
            interface: match i(vr::INTERFACE) {
                RIGID => LawKind::Rigid,
                ELASTIC => LawKind::Elastic,
                ELASTO_PLASTIC => LawKind::ElastoPlastic,
                _ => return None,
            },
            kn: r(vr::KN),
            fm: r(vr::FM),
            formulation: match i(vr::FORMULATION) {
                COSTA => Formulation::Costa,
                SHIFTING_PIVOT => Formulation::ShiftingPivot,
                _ => return None,
            },
            theta0: r(vr::THETA),
            omega0: r(vr::OMEGA),
            restraint: match i(vr::RESTRAINT) {
                NONE => RestraintKind::None,
                ONE_SIDED => RestraintKind::OneSided,
                _ => return None,
            },
            side: i(vr::SIDE),
            e_restraint: r(vr::E_RESTRAINT),
            ..Params::default()
        };
        rigid_body_params::<Self>(stored, &SHAPES, own)
    }

    fn valid(stored: &Stored) -> bool {
        // maxSteps >= 1, mu >= 0 and not NaN (docs/model.md §5)
        let mu = stored.real[vr::MU as usize];
        stored.int[vr::MAX_STEPS as usize] >= 1
            && mu >= 0.0
            && Self::params(stored).is_some_and(|p| p.build().is_ok())
    }

    fn set_input(b: &mut Bytes, s: u8) -> Op {
        Op::SetReal(s, vec![vr::AG], vec![b.int() as f64 * 2.5])
    }

    fn set_input_derivative(b: &mut Bytes, s: u8) -> Op {
        let input = if b.chance(1) { vr::AV } else { vr::AG };
        Op::SetInputDerivatives(s, vec![input], vec![1], vec![b.int() as f64 * 10.0])
    }

    fn integer_in_range(r: u32, x: c_int) -> Option<bool> {
        match r {
            vr::REGIME => Some((0..=5).contains(&x)),
            vr::IMPACTS | vr::ZERO_CROSSINGS => Some(x >= 0),
            _ => None,
        }
    }

    fn check_integers(r: &[u32], out: &[c_int]) {
        let of = |v: u32| r.iter().position(|&q| q == v).map(|i| out[i]);
        if let (Some(i), Some(z)) = (of(vr::IMPACTS), of(vr::ZERO_CROSSINGS)) {
            assert!(i <= z, "impacts = {i} > zeroCrossings = {z}");
        }
    }

    /// Skips fmi2DoStep (with [`Driver::tolerate_known`]) for a flexible
    /// interface with thetaJo < 1e-8 thetaOv (kn above about 1e14 Pa/m for
    /// the default block, or a body of next to no weight), where the
    /// integrator resolves the contact's time scale and a step can take
    /// minutes to hours, and for a body whose weight, mass, R0 or IO is
    /// outside 1e-30..1e30, where moments overflow and the step loop may
    /// never end, and after restoring a state from a mutated buffer, whose
    /// engine fields (step size, contact hint, stiff flag) can stall the
    /// integrator (known, reported; not what this driver looks for); and
    /// always a step longer than [`MAX_STEP`].
    fn skip_step(d: &mut Driver, k: u8, h: f64, machine: Option<Machine>, forged: bool) -> bool {
        let skip = h.is_finite() && h > MAX_STEP
            || (d.tolerate_known && forged)
            || (d.tolerate_known && machine == Some(Machine::StepComplete) && extreme(d, k));
        if skip {
            d.stats.steps_skipped += 1;
        }
        skip
    }
}

/// A model out of the integrator's working range (see
/// [`RockingBlock::skip_step`]), read from the FMU itself: a flexible
/// interface far stiffer than the body's weight, or a body whose weight,
/// mass, lever or inertia is beyond 1e-30..1e30 (W = 1.8e308 N on a rigid
/// interface: the moments overflow and the step loop never ends).
fn extreme(d: &mut Driver, k: u8) -> bool {
    let mut law: c_int = 0;
    let Some(fmi2_export::types::fmi2OK) = d.call(k, "fmi2GetInteger", GET, |c| unsafe {
        fmu_rocking::fmi2GetInteger(c, &vr::INTERFACE, 1, &mut law)
    }) else {
        return false;
    };
    let Some(x) = d.get_real(
        k,
        &[
            vr::THETA_JO,
            vr::THETA_OV,
            vr::WEIGHT,
            vr::MASS,
            vr::R0,
            vr::IO,
        ],
    ) else {
        return false;
    };
    let body = x[2..].iter().any(|&v| !(1e-30..=1e30).contains(&v));
    body || (law != enums::RIGID && x[0] < EXTREME_STIFFNESS * x[1])
}
