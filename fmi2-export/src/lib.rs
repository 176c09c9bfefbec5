//! A generic FMI 2.0 export layer, co-simulation and Model Exchange. It
//! knows nothing of any particular model: a model implements [`Slave`] and a
//! cdylib calls [`export_fmi2!`] once to export every FMI 2.0 function (the
//! Model Exchange ones refuse an instance unless the model description has
//! `<ModelExchange>`).
//!
//! - [`types`]: the FMI 2.0 C types, declared once (`std::ffi`);
//! - [`slave`]: the [`Slave`] trait and the views it gets of the stored values;
//! - [`machine`]: the state machine and the states each function allows;
//! - [`instance`]: one instance, its stored values and its life cycle;
//! - [`values`]: `fmi2Get*`/`fmi2Set*` and the input and output derivatives;
//! - [`step`]: `fmi2DoStep` and the status functions;
//! - [`fmu_state`]: FMU states, saved, restored and serialized;
//! - [`fail`]: failed calls and panics of model code;
//! - [`logging`]: the host logger, categories and `fmi2SetDebugLogging`;
//! - [`bytes`]: the checked byte format of serialized FMU states;
//! - [`ffi`]: pointer checks, panic barriers and the C-facing functions;
//! - [`uri`]: the resource location as a path;
//! - `test_host` (feature `test-host`): an in-process host for FMU tests.
//!
//! Instances share nothing (no global mutable state), so any number of them
//! can run in any threads.

pub mod bytes;
pub mod fail;
pub mod ffi;
pub mod ffi_me;
pub mod fmu_state;
pub mod instance;
pub mod logging;
pub mod machine;
pub mod model_exchange;
pub mod slave;
pub mod step;
#[cfg(feature = "test-host")]
pub mod test_host;
pub mod types;
pub mod uri;
pub mod values;

pub use model_description;
pub use slave::{EventLog, Inputs, Setup, Slave, StepEnd, Update, Values};

/// Exports the FMI 2.0 co-simulation functions for the model type `$slave`
/// (which implements [`Slave`]). Call once, at the root of a cdylib.
#[macro_export]
macro_rules! export_fmi2 {
    ($slave:ty) => {
        #[no_mangle]
        pub extern "C" fn fmi2GetTypesPlatform() -> *const ::std::os::raw::c_char {
            $crate::ffi::get_types_platform()
        }

        #[no_mangle]
        pub extern "C" fn fmi2GetVersion() -> *const ::std::os::raw::c_char {
            $crate::ffi::get_version()
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetDebugLogging(
            c: $crate::types::fmi2Component,
            logging_on: $crate::types::fmi2Boolean,
            n_categories: usize,
            categories: *const $crate::types::fmi2String,
        ) -> $crate::types::fmi2Status {
            unsafe {
                $crate::ffi::set_debug_logging::<$slave>(c, logging_on, n_categories, categories)
            }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2Instantiate(
            instance_name: $crate::types::fmi2String,
            fmu_type: $crate::types::fmi2Type,
            fmu_guid: $crate::types::fmi2String,
            fmu_resource_location: $crate::types::fmi2String,
            functions: *const $crate::types::fmi2CallbackFunctions,
            visible: $crate::types::fmi2Boolean,
            logging_on: $crate::types::fmi2Boolean,
        ) -> $crate::types::fmi2Component {
            unsafe {
                $crate::ffi::instantiate::<$slave>(
                    instance_name,
                    fmu_type,
                    fmu_guid,
                    fmu_resource_location,
                    functions,
                    visible,
                    logging_on,
                )
            }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2FreeInstance(c: $crate::types::fmi2Component) {
            unsafe { $crate::ffi::free_instance::<$slave>(c) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetupExperiment(
            c: $crate::types::fmi2Component,
            tolerance_defined: $crate::types::fmi2Boolean,
            tolerance: $crate::types::fmi2Real,
            start_time: $crate::types::fmi2Real,
            stop_time_defined: $crate::types::fmi2Boolean,
            stop_time: $crate::types::fmi2Real,
        ) -> $crate::types::fmi2Status {
            unsafe {
                $crate::ffi::setup_experiment::<$slave>(
                    c,
                    tolerance_defined,
                    tolerance,
                    start_time,
                    stop_time_defined,
                    stop_time,
                )
            }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2EnterInitializationMode(
            c: $crate::types::fmi2Component,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::enter_initialization_mode::<$slave>(c) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2ExitInitializationMode(
            c: $crate::types::fmi2Component,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::exit_initialization_mode::<$slave>(c) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2Terminate(
            c: $crate::types::fmi2Component,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::terminate::<$slave>(c) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2Reset(
            c: $crate::types::fmi2Component,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::reset::<$slave>(c) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetReal(
            c: $crate::types::fmi2Component,
            vr: *const $crate::types::fmi2ValueReference,
            nvr: usize,
            value: *mut $crate::types::fmi2Real,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::get_real::<$slave>(c, vr, nvr, value) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetInteger(
            c: $crate::types::fmi2Component,
            vr: *const $crate::types::fmi2ValueReference,
            nvr: usize,
            value: *mut $crate::types::fmi2Integer,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::get_integer::<$slave>(c, vr, nvr, value) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetBoolean(
            c: $crate::types::fmi2Component,
            vr: *const $crate::types::fmi2ValueReference,
            nvr: usize,
            value: *mut $crate::types::fmi2Boolean,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::get_boolean::<$slave>(c, vr, nvr, value) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetString(
            c: $crate::types::fmi2Component,
            vr: *const $crate::types::fmi2ValueReference,
            nvr: usize,
            value: *mut $crate::types::fmi2String,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::get_string::<$slave>(c, vr, nvr, value) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetReal(
            c: $crate::types::fmi2Component,
            vr: *const $crate::types::fmi2ValueReference,
            nvr: usize,
            value: *const $crate::types::fmi2Real,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::set_real::<$slave>(c, vr, nvr, value) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetInteger(
            c: $crate::types::fmi2Component,
            vr: *const $crate::types::fmi2ValueReference,
            nvr: usize,
            value: *const $crate::types::fmi2Integer,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::set_integer::<$slave>(c, vr, nvr, value) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetBoolean(
            c: $crate::types::fmi2Component,
            vr: *const $crate::types::fmi2ValueReference,
            nvr: usize,
            value: *const $crate::types::fmi2Boolean,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::set_boolean::<$slave>(c, vr, nvr, value) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetString(
            c: $crate::types::fmi2Component,
            vr: *const $crate::types::fmi2ValueReference,
            nvr: usize,
            value: *const $crate::types::fmi2String,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::set_string::<$slave>(c, vr, nvr, value) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetFMUstate(
            c: $crate::types::fmi2Component,
            state: *mut $crate::types::fmi2FMUstate,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::get_fmu_state::<$slave>(c, state) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetFMUstate(
            c: $crate::types::fmi2Component,
            state: $crate::types::fmi2FMUstate,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::set_fmu_state::<$slave>(c, state) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2FreeFMUstate(
            c: $crate::types::fmi2Component,
            state: *mut $crate::types::fmi2FMUstate,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::free_fmu_state::<$slave>(c, state) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2SerializedFMUstateSize(
            c: $crate::types::fmi2Component,
            state: $crate::types::fmi2FMUstate,
            size: *mut usize,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::serialized_fmu_state_size::<$slave>(c, state, size) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2SerializeFMUstate(
            c: $crate::types::fmi2Component,
            state: $crate::types::fmi2FMUstate,
            serialized_state: *mut $crate::types::fmi2Byte,
            size: usize,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::serialize_fmu_state::<$slave>(c, state, serialized_state, size) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
            c: $crate::types::fmi2Component,
            serialized_state: *const $crate::types::fmi2Byte,
            size: usize,
            state: *mut $crate::types::fmi2FMUstate,
        ) -> $crate::types::fmi2Status {
            unsafe {
                $crate::ffi::deserialize_fmu_state::<$slave>(c, serialized_state, size, state)
            }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetDirectionalDerivative(
            c: $crate::types::fmi2Component,
            _v_unknown_ref: *const $crate::types::fmi2ValueReference,
            _n_unknown: usize,
            _v_known_ref: *const $crate::types::fmi2ValueReference,
            _n_known: usize,
            _dv_known: *const $crate::types::fmi2Real,
            _dv_unknown: *mut $crate::types::fmi2Real,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::get_directional_derivative::<$slave>(c) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
            c: $crate::types::fmi2Component,
            vr: *const $crate::types::fmi2ValueReference,
            nvr: usize,
            order: *const $crate::types::fmi2Integer,
            value: *const $crate::types::fmi2Real,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::set_real_input_derivatives::<$slave>(c, vr, nvr, order, value) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(
            c: $crate::types::fmi2Component,
            vr: *const $crate::types::fmi2ValueReference,
            nvr: usize,
            order: *const $crate::types::fmi2Integer,
            value: *mut $crate::types::fmi2Real,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::get_real_output_derivatives::<$slave>(c, vr, nvr, order, value) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2DoStep(
            c: $crate::types::fmi2Component,
            current_communication_point: $crate::types::fmi2Real,
            communication_step_size: $crate::types::fmi2Real,
            no_set_fmu_state_prior_to_current_point: $crate::types::fmi2Boolean,
        ) -> $crate::types::fmi2Status {
            unsafe {
                $crate::ffi::do_step::<$slave>(
                    c,
                    current_communication_point,
                    communication_step_size,
                    no_set_fmu_state_prior_to_current_point,
                )
            }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2CancelStep(
            c: $crate::types::fmi2Component,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::cancel_step::<$slave>(c) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetStatus(
            c: $crate::types::fmi2Component,
            s: $crate::types::fmi2StatusKind,
            value: *mut $crate::types::fmi2Status,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::get_status::<$slave>(c, s, value) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetRealStatus(
            c: $crate::types::fmi2Component,
            s: $crate::types::fmi2StatusKind,
            value: *mut $crate::types::fmi2Real,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::get_real_status::<$slave>(c, s, value) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetIntegerStatus(
            c: $crate::types::fmi2Component,
            s: $crate::types::fmi2StatusKind,
            value: *mut $crate::types::fmi2Integer,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::get_integer_status::<$slave>(c, s, value) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetBooleanStatus(
            c: $crate::types::fmi2Component,
            s: $crate::types::fmi2StatusKind,
            value: *mut $crate::types::fmi2Boolean,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::get_boolean_status::<$slave>(c, s, value) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetStringStatus(
            c: $crate::types::fmi2Component,
            s: $crate::types::fmi2StatusKind,
            value: *mut $crate::types::fmi2String,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::get_string_status::<$slave>(c, s, value) }
        }

        // ----- Model Exchange (FMI 2.0 §3.2) -----

        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetTime(
            c: $crate::types::fmi2Component,
            time: $crate::types::fmi2Real,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi_me::set_time::<$slave>(c, time) }
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetContinuousStates(
            c: $crate::types::fmi2Component,
            x: *const $crate::types::fmi2Real,
            nx: usize,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi_me::set_continuous_states::<$slave>(c, x, nx) }
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetContinuousStates(
            c: $crate::types::fmi2Component,
            x: *mut $crate::types::fmi2Real,
            nx: usize,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi_me::get_continuous_states::<$slave>(c, x, nx) }
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetNominalsOfContinuousStates(
            c: $crate::types::fmi2Component,
            x_nominal: *mut $crate::types::fmi2Real,
            nx: usize,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi_me::get_nominals_of_continuous_states::<$slave>(c, x_nominal, nx) }
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetDerivatives(
            c: $crate::types::fmi2Component,
            derivatives: *mut $crate::types::fmi2Real,
            nx: usize,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi_me::get_derivatives::<$slave>(c, derivatives, nx) }
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetEventIndicators(
            c: $crate::types::fmi2Component,
            event_indicators: *mut $crate::types::fmi2Real,
            ni: usize,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi_me::get_event_indicators::<$slave>(c, event_indicators, ni) }
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2EnterEventMode(
            c: $crate::types::fmi2Component,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi_me::enter_event_mode::<$slave>(c) }
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2NewDiscreteStates(
            c: $crate::types::fmi2Component,
            event_info: *mut $crate::types::fmi2EventInfo,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi_me::new_discrete_states::<$slave>(c, event_info) }
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2EnterContinuousTimeMode(
            c: $crate::types::fmi2Component,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi_me::enter_continuous_time_mode::<$slave>(c) }
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2CompletedIntegratorStep(
            c: $crate::types::fmi2Component,
            no_set_fmu_state_prior_to_current_point: $crate::types::fmi2Boolean,
            enter_event_mode: *mut $crate::types::fmi2Boolean,
            terminate_simulation: *mut $crate::types::fmi2Boolean,
        ) -> $crate::types::fmi2Status {
            unsafe {
                $crate::ffi_me::completed_integrator_step::<$slave>(
                    c,
                    no_set_fmu_state_prior_to_current_point,
                    enter_event_mode,
                    terminate_simulation,
                )
            }
        }
    };
}
