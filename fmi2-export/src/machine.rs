//! The FMI 2.0 state machines, co-simulation and Model Exchange, and, as in
//! the Reference FMUs' `fmi2Functions.c`, one mask per function: the states
//! in which it may be called (FMI 2.0, sections 4.2.4 and 3.2.3, state
//! tables).

#![allow(non_upper_case_globals)] // the masks keep the C functions' names

/// States of the FMI 2.0 state machines: co-simulation (no asynchronous
/// steps: `stepInProgress` and `stepCanceled` never occur) and Model
/// Exchange (`eventMode`, `continuousTimeMode`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Machine {
    Instantiated,
    InitializationMode,
    StepComplete,
    StepFailed,
    Terminated,
    Error,
    Fatal,
    EventMode,
    ContinuousTimeMode,
    /// FMI 3.0: structural parameters are set here (from and back to
    /// `Instantiated`); no 2.0 function is allowed.
    ConfigurationMode,
}

impl Machine {
    const ALL: [Machine; 10] = [
        Machine::Instantiated,
        Machine::InitializationMode,
        Machine::StepComplete,
        Machine::StepFailed,
        Machine::Terminated,
        Machine::Error,
        Machine::Fatal,
        Machine::EventMode,
        Machine::ContinuousTimeMode,
        Machine::ConfigurationMode,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Machine::Instantiated => "instantiated",
            Machine::InitializationMode => "initializationMode",
            Machine::StepComplete => "stepComplete",
            Machine::StepFailed => "stepFailed",
            Machine::Terminated => "terminated",
            Machine::Error => "error",
            Machine::Fatal => "fatal",
            Machine::EventMode => "eventMode",
            Machine::ContinuousTimeMode => "continuousTimeMode",
            Machine::ConfigurationMode => "configurationMode",
        }
    }

    /// The state's number in a serialized FMU state.
    pub(crate) fn code(self) -> u8 {
        Machine::ALL.iter().position(|m| *m == self).unwrap() as u8
    }

    pub(crate) fn from_code(c: u8) -> Option<Machine> {
        Machine::ALL.get(c as usize).copied()
    }
}

/// A set of states: where one function may be called.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mask(u16);

impl Mask {
    pub const fn of(states: &[Machine]) -> Mask {
        let mut bits = 0;
        let mut i = 0;
        while i < states.len() {
            bits |= 1 << states[i] as u16;
            i += 1;
        }
        Mask(bits)
    }

    pub fn contains(self, m: Machine) -> bool {
        self.0 & (1 << m as u16) != 0
    }

    /// The states of the mask, in the order of the state table.
    pub fn states(self) -> impl Iterator<Item = Machine> {
        Machine::ALL.into_iter().filter(move |m| self.contains(*m))
    }
}

/// The mask of each function (the functions not listed are allowed in every
/// state but fatal, or, like `fmi2CancelStep`, check nothing).
pub mod mask {
    use super::Machine as M;
    use super::Mask;

    const ANY_BUT_FATAL: Mask = Mask::of(&[
        M::Instantiated,
        M::InitializationMode,
        M::StepComplete,
        M::StepFailed,
        M::Terminated,
        M::Error,
        M::EventMode,
        M::ContinuousTimeMode,
    ]);
    const GET: Mask = Mask::of(&[
        M::InitializationMode,
        M::StepComplete,
        M::StepFailed,
        M::Terminated,
        M::Error,
        M::EventMode,
        M::ContinuousTimeMode,
    ]);
    /// Which variables may be set in each state: `values::settable`.
    const SET: Mask = Mask::of(&[
        M::Instantiated,
        M::InitializationMode,
        M::StepComplete,
        M::EventMode,
        M::ContinuousTimeMode,
    ]);
    /// Model Exchange: evaluations of the model at the current state.
    const EVALUATE: Mask = Mask::of(&[
        M::InitializationMode,
        M::EventMode,
        M::ContinuousTimeMode,
        M::Terminated,
        M::Error,
    ]);
    const STATUS: Mask = Mask::of(&[M::StepComplete, M::StepFailed, M::Terminated]);

    pub const fmi2SetupExperiment: Mask = Mask::of(&[M::Instantiated]);
    pub const fmi2EnterInitializationMode: Mask = Mask::of(&[M::Instantiated]);
    pub const fmi2ExitInitializationMode: Mask = Mask::of(&[M::InitializationMode]);
    pub const fmi2Terminate: Mask = Mask::of(&[
        M::StepComplete,
        M::StepFailed,
        M::EventMode,
        M::ContinuousTimeMode,
    ]);
    pub const fmi2Reset: Mask = Mask(ANY_BUT_FATAL.0 | Mask::of(&[M::ConfigurationMode]).0);

    pub const fmi2GetReal: Mask = GET;
    pub const fmi2GetInteger: Mask = GET;
    pub const fmi2GetBoolean: Mask = GET;
    pub const fmi2GetString: Mask = GET;
    pub const fmi2SetReal: Mask = SET;
    pub const fmi2SetInteger: Mask = SET;
    pub const fmi2SetBoolean: Mask = SET;
    pub const fmi2SetString: Mask = SET;
    pub const fmi2SetRealInputDerivatives: Mask = SET;
    pub const fmi2GetRealOutputDerivatives: Mask =
        Mask::of(&[M::StepComplete, M::StepFailed, M::Terminated, M::Error]);

    pub const fmi2DoStep: Mask = Mask::of(&[M::StepComplete]);
    pub const fmi2GetStatus: Mask = STATUS;
    pub const fmi2GetRealStatus: Mask = STATUS;
    pub const fmi2GetIntegerStatus: Mask = STATUS;
    pub const fmi2GetBooleanStatus: Mask = STATUS;
    pub const fmi2GetStringStatus: Mask = STATUS;

    pub const fmi2SetTime: Mask = Mask::of(&[M::EventMode, M::ContinuousTimeMode]);
    pub const fmi2SetContinuousStates: Mask = Mask::of(&[M::ContinuousTimeMode]);
    pub const fmi2GetContinuousStates: Mask = EVALUATE;
    pub const fmi2GetDerivatives: Mask = EVALUATE;
    pub const fmi2GetEventIndicators: Mask = EVALUATE;
    pub const fmi2GetNominalsOfContinuousStates: Mask = Mask::of(&[
        M::Instantiated,
        M::InitializationMode,
        M::EventMode,
        M::ContinuousTimeMode,
        M::Terminated,
        M::Error,
    ]);
    pub const fmi2EnterEventMode: Mask = Mask::of(&[M::EventMode, M::ContinuousTimeMode]);
    pub const fmi2NewDiscreteStates: Mask = Mask::of(&[M::EventMode]);
    pub const fmi2EnterContinuousTimeMode: Mask = Mask::of(&[M::EventMode]);
    pub const fmi2CompletedIntegratorStep: Mask = Mask::of(&[M::ContinuousTimeMode]);

    pub const fmi2GetFMUstate: Mask = ANY_BUT_FATAL;
    pub const fmi2SetFMUstate: Mask = ANY_BUT_FATAL;
    pub const fmi2FreeFMUstate: Mask = ANY_BUT_FATAL;
    pub const fmi2SerializedFMUstateSize: Mask = ANY_BUT_FATAL;
    pub const fmi2SerializeFMUstate: Mask = ANY_BUT_FATAL;
    pub const fmi2DeSerializeFMUstate: Mask = ANY_BUT_FATAL;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_mask_holds_exactly_its_states_in_table_order() {
        let m = Mask::of(&[Machine::Terminated, Machine::Instantiated]);
        let states: Vec<Machine> = m.states().collect();
        assert_eq!(states, [Machine::Instantiated, Machine::Terminated]);
        for s in Machine::ALL {
            assert_eq!(m.contains(s), states.contains(&s), "{s:?}");
        }
    }
}
