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
//!
//! # Example
//!
//! A gain `y = k u` as an FMU's binary: the model implements [`Slave`], a
//! `modelDescription.xml` table (the `model-description` crate) declares its
//! variables, and [`export_fmi2!`] writes every `fmi2*` C function.
//!
//! ```
//! use fmi2_export::bytes::{ByteReader, ByteWriter, ReadError};
//! use fmi2_export::model_description::{
//!     common, Causality, DefaultExperiment, Initial, ModelDescription, Type, Variability, Variable,
//! };
//! use fmi2_export::{export_fmi2, EventLog, Inputs, Setup, Slave, StepEnd, Values};
//!
//! static GAIN: ModelDescription = ModelDescription {
//!     model_name: "Gain",
//!     description: "y = k u",
//!     author: common::AUTHOR,
//!     version: "0.1.0",
//!     copyright: common::COPYRIGHT,
//!     license: common::LICENSE,
//!     generation_tool: common::GENERATION_TOOL,
//!     co_simulation: common::co_simulation("Gain"),
//!     model_exchange: None,
//!     units: &[],
//!     types: &[],
//!     log_categories: &[],
//!     default_experiment: DefaultExperiment { start_time: 0.0, stop_time: 1.0, tolerance: 1e-6, step_size: 1e-3 },
//!     variables: &[
//!         Variable { name: "u", vr: 0, description: "input", causality: Causality::Input,
//!                    ty: Type::Real { unit: None, display_unit: None, start: Some(0.0), min: None, max: None },
//!                    ..Variable::DEFAULT },
//!         Variable { name: "k", vr: 1, description: "gain", causality: Causality::Parameter, variability: Variability::Fixed,
//!                    initial: Some(Initial::Exact),
//!                    ty: Type::Real { unit: None, display_unit: None, start: Some(2.0), min: None, max: None },
//!                    ..Variable::DEFAULT },
//!         Variable { name: "y", vr: 2, description: "output k u", causality: Causality::Output, depends_on: &["u", "k"],
//!                    ..Variable::DEFAULT },
//!     ],
//!     documentation: "",
//!     arrays3: None,
//! };
//!
//! struct Gain { k: f64 }
//!
//! impl Slave for Gain {
//!     type State = (); // no state: the output follows the input
//!     fn description() -> &'static ModelDescription { &GAIN }
//!     // a real FMU embeds the GUID its build script generated with the XML
//!     fn guid() -> &'static str { "{gain}" }
//!     fn new(values: Values<'_>, _setup: &Setup) -> Result<Self, String> {
//!         Ok(Gain { k: values.real(1) })
//!     }
//!     fn get_real(&mut self, vr: u32, inputs: Inputs<'_>) -> Result<f64, String> {
//!         match vr {
//!             2 => Ok(self.k * inputs.real(0)),
//!             _ => Err(format!("no computed Real with value reference {vr}")),
//!         }
//!     }
//!     fn output_derivative(&mut self, vr: u32, order: i32, inputs: Inputs<'_>) -> Result<f64, String> {
//!         match (vr, order) {
//!             (2, 1) => Ok(self.k * inputs.derivative(0)),
//!             _ => Err(format!("no derivative of order {order} of value reference {vr}")),
//!         }
//!     }
//!     fn do_step(&mut self, _t: f64, _h: f64, _inputs: Inputs<'_>, _log: &mut EventLog)
//!         -> Result<StepEnd, String> {
//!         Ok(StepEnd::Completed)
//!     }
//!     fn state(&self) {}
//!     fn set_state(&mut self, _state: ()) {}
//!     fn write_state(_state: &(), _w: &mut ByteWriter) {}
//!     fn read_state(_r: &mut ByteReader<'_>) -> Result<(), ReadError> { Ok(()) }
//! }
//!
//! export_fmi2!(Gain);
//!
//! // the exported C functions, as a host finds them in the library
//! let version = unsafe { std::ffi::CStr::from_ptr(fmi2GetVersion()) };
//! assert_eq!(version.to_str(), Ok("2.0"));
//! ```

pub mod bytes;
pub mod fail;
pub mod ffi;
pub mod ffi_me;
pub mod fmi3_wording;
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

/// The files `model_description::build::generate` wrote into `OUT_DIR`,
/// as constants of the FMU crate that calls this once at its root: `GUID`
/// (the GUID of the `modelDescription.xml` this binary ships with),
/// `MODEL_DESCRIPTION_XML` and `DOCUMENTATION_HTML` (`documentation/index.html`).
#[macro_export]
macro_rules! generated_files {
    () => {
        /// The GUID of the `modelDescription.xml` this binary ships with
        /// (generated by `build.rs` from the variable table).
        pub const GUID: &str = include_str!(concat!(env!("OUT_DIR"), "/guid.txt"));

        /// The `modelDescription.xml` the archive ships (generated by `build.rs`).
        pub const MODEL_DESCRIPTION_XML: &str =
            include_str!(concat!(env!("OUT_DIR"), "/modelDescription.xml"));

        /// `documentation/index.html` (generated by `build.rs`).
        pub const DOCUMENTATION_HTML: &str = include_str!(concat!(env!("OUT_DIR"), "/index.html"));
    };
}

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
            unsafe { $crate::ffi::get_fmu_state::<$slave>(c, state, "fmi2GetFMUstate") }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetFMUstate(
            c: $crate::types::fmi2Component,
            state: $crate::types::fmi2FMUstate,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::set_fmu_state::<$slave>(c, state, "fmi2SetFMUstate") }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2FreeFMUstate(
            c: $crate::types::fmi2Component,
            state: *mut $crate::types::fmi2FMUstate,
        ) -> $crate::types::fmi2Status {
            unsafe { $crate::ffi::free_fmu_state::<$slave>(c, state, "fmi2FreeFMUstate") }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2SerializedFMUstateSize(
            c: $crate::types::fmi2Component,
            state: $crate::types::fmi2FMUstate,
            size: *mut usize,
        ) -> $crate::types::fmi2Status {
            unsafe {
                $crate::ffi::serialized_fmu_state_size::<$slave>(
                    c,
                    state,
                    size,
                    "fmi2SerializedFMUstateSize",
                )
            }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2SerializeFMUstate(
            c: $crate::types::fmi2Component,
            state: $crate::types::fmi2FMUstate,
            serialized_state: *mut $crate::types::fmi2Byte,
            size: usize,
        ) -> $crate::types::fmi2Status {
            unsafe {
                $crate::ffi::serialize_fmu_state::<$slave>(
                    c,
                    state,
                    serialized_state as *mut u8,
                    size,
                    "fmi2SerializeFMUstate",
                )
            }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
            c: $crate::types::fmi2Component,
            serialized_state: *const $crate::types::fmi2Byte,
            size: usize,
            state: *mut $crate::types::fmi2FMUstate,
        ) -> $crate::types::fmi2Status {
            unsafe {
                $crate::ffi::deserialize_fmu_state::<$slave>(
                    c,
                    serialized_state as *const u8,
                    size,
                    state,
                    "fmi2DeSerializeFMUstate",
                )
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
