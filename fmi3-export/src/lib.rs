//! A generic FMI 3.0 export layer, co-simulation (with event mode and early
//! return) and Model Exchange, over the instance of `fmi2-export`: a model
//! implements the same [`fmi2_export::Slave`] trait, and one cdylib calls
//! both `fmi2_export::export_fmi2!` and [`export_fmi3!`] to serve both
//! standards from one binary (the function names do not collide).
//!
//! - [`types`]: the FMI 3.0 C types it needs;
//! - [`ffi`]: instantiation, life cycle, values by 3.0 type, FMU states;
//! - [`modes`]: step mode, event mode and Model Exchange's functions.
//!
//! What 3.0 adds to the table (`time`, the event indicators as variables)
//! comes from `model_description::fmi3`; the 3.0 `modelDescription.xml`
//! from `model_description::xml3`. FMI 3.0 has no function for input
//! derivatives: the first derivative of each continuous input is an input
//! `der(x)` of its own (`derivative` attribute), set with `fmi3SetFloat64`
//! into the store `fmi2SetRealInputDerivatives` fills. Arrays sized by a
//! structural parameter map onto the 2.0 scalars ([`arrays`]). Clocks, binaries and the types the
//! table has no variable of answer with an error naming the value
//! reference (or nothing to do, for none).

pub mod arrays;
pub mod ffi;
pub mod modes;
pub mod types;

/// `fmi3<Get|Set><Type>` of a type the table has no variable of.
#[doc(hidden)]
#[macro_export]
macro_rules! __no_such_type {
    ($slave:ty, $($name:ident: $value:ty),* $(,)?) => {$(
        #[no_mangle]
        pub unsafe extern "C" fn $name(
            c: $crate::types::fmi3Instance,
            vr: *const $crate::types::fmi3ValueReference,
            n: usize,
            _values: $value,
            _n_values: usize,
        ) -> $crate::types::fmi3Status {
            unsafe { $crate::ffi::no_such_type::<$slave>(c, stringify!($name), vr, n) }
        }
    )*};
}

/// Functions this layer does not provide, whatever their arguments.
#[doc(hidden)]
#[macro_export]
macro_rules! __not_provided {
    ($slave:ty, $($name:ident($($arg:ty),*)),* $(,)?) => {$(
        #[no_mangle]
        pub unsafe extern "C" fn $name(
            c: $crate::types::fmi3Instance, $(_: $arg),*
        ) -> $crate::types::fmi3Status {
            unsafe { $crate::ffi::not_provided::<$slave>(c, stringify!($name)) }
        }
    )*};
}

/// `fmi3<Get|Set><Type>` of a type the table has, by `ffi`'s function.
#[doc(hidden)]
#[macro_export]
macro_rules! __values {
    ($slave:ty, $($name:ident => $f:ident($value:ty)),* $(,)?) => {$(
        #[no_mangle]
        pub unsafe extern "C" fn $name(
            c: $crate::types::fmi3Instance,
            vr: *const $crate::types::fmi3ValueReference,
            n: usize,
            values: $value,
            n_values: usize,
        ) -> $crate::types::fmi3Status {
            unsafe { $crate::ffi::$f::<$slave>(c, vr, n, values, n_values) }
        }
    )*};
}

/// `fmi3<Function>(instance)` and `fmi3<Function>(instance, x, n)`, by
/// `$module`'s function.
#[doc(hidden)]
#[macro_export]
macro_rules! __simple {
    ($slave:ty, $($name:ident => $module:ident::$f:ident($($arg:ident: $ty:ty),*)),* $(,)?) => {$(
        #[no_mangle]
        pub unsafe extern "C" fn $name(
            c: $crate::types::fmi3Instance, $($arg: $ty),*
        ) -> $crate::types::fmi3Status {
            unsafe { $crate::$module::$f::<$slave>(c, $($arg),*) }
        }
    )*};
}

/// The FMU-state functions: `fmi2-export`'s, which have the same C shapes,
/// called with the 3.0 name.
#[doc(hidden)]
#[macro_export]
macro_rules! __states {
    ($slave:ty, $($name:ident => $f:ident($($arg:ident: $ty:ty),*)),* $(,)?) => {$(
        #[no_mangle]
        pub unsafe extern "C" fn $name(
            c: $crate::types::fmi3Instance, $($arg: $ty),*
        ) -> $crate::types::fmi3Status {
            unsafe { $crate::fmi2_export::ffi::$f::<$slave>(c, $($arg,)* stringify!($name)) }
        }
    )*};
}

/// Exports the FMI 3.0 functions for the model type `$slave` (which
/// implements `fmi2_export::Slave`). Call once, at the root of a cdylib.
#[macro_export]
macro_rules! export_fmi3 {
    ($slave:ty) => {
        #[no_mangle]
        pub extern "C" fn fmi3GetVersion() -> *const ::std::os::raw::c_char {
            $crate::ffi::get_version()
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi3InstantiateModelExchange(
            instance_name: $crate::types::fmi3String,
            token: $crate::types::fmi3String,
            resource_path: $crate::types::fmi3String,
            _visible: bool,
            logging_on: bool,
            env: $crate::types::fmi3InstanceEnvironment,
            log_message: Option<$crate::types::fmi3LogMessageCallback>,
        ) -> $crate::types::fmi3Instance {
            let names = $crate::ffi::Names { instance_name, token, resource_path };
            let kind = $crate::ffi::Kind {
                model_exchange: true,
                event_mode_used: false,
                early_return_allowed: false,
            };
            unsafe { $crate::ffi::instantiate::<$slave>(names, kind, logging_on, env, log_message) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi3InstantiateCoSimulation(
            instance_name: $crate::types::fmi3String,
            token: $crate::types::fmi3String,
            resource_path: $crate::types::fmi3String,
            _visible: bool,
            logging_on: bool,
            event_mode_used: bool,
            early_return_allowed: bool,
            _required_intermediate_variables: *const $crate::types::fmi3ValueReference,
            _n_required_intermediate_variables: usize,
            env: $crate::types::fmi3InstanceEnvironment,
            log_message: Option<$crate::types::fmi3LogMessageCallback>,
            _intermediate_update: $crate::types::fmi3IntermediateUpdateCallback,
        ) -> $crate::types::fmi3Instance {
            let names = $crate::ffi::Names { instance_name, token, resource_path };
            let kind = $crate::ffi::Kind {
                model_exchange: false,
                event_mode_used,
                early_return_allowed,
            };
            unsafe { $crate::ffi::instantiate::<$slave>(names, kind, logging_on, env, log_message) }
        }

        /// No scheduled execution: always NULL.
        #[no_mangle]
        pub extern "C" fn fmi3InstantiateScheduledExecution(
            _instance_name: $crate::types::fmi3String,
            _token: $crate::types::fmi3String,
            _resource_path: $crate::types::fmi3String,
            _visible: bool,
            _logging_on: bool,
            _env: $crate::types::fmi3InstanceEnvironment,
            _log_message: Option<$crate::types::fmi3LogMessageCallback>,
            _clock_update: *const ::std::ffi::c_void,
            _lock_preemption: *const ::std::ffi::c_void,
            _unlock_preemption: *const ::std::ffi::c_void,
        ) -> $crate::types::fmi3Instance {
            ::std::ptr::null_mut()
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi3FreeInstance(c: $crate::types::fmi3Instance) {
            unsafe { $crate::fmi2_export::ffi::free_instance::<$slave>(c) }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi3DoStep(
            c: $crate::types::fmi3Instance,
            t: f64,
            h: f64,
            no_set_fmu_state_prior_to_current_point: bool,
            event_handling_needed: *mut bool,
            terminate_simulation: *mut bool,
            early_return: *mut bool,
            last_successful_time: *mut f64,
        ) -> $crate::types::fmi3Status {
            let results = $crate::modes::StepResults {
                event_handling_needed,
                terminate_simulation,
                early_return,
                last_successful_time,
            };
            unsafe {
                $crate::modes::do_step::<$slave>(c, t, h, no_set_fmu_state_prior_to_current_point, results)
            }
        }

        #[no_mangle]
        pub unsafe extern "C" fn fmi3UpdateDiscreteStates(
            c: $crate::types::fmi3Instance,
            discrete_states_need_update: *mut bool,
            terminate_simulation: *mut bool,
            nominals_changed: *mut bool,
            values_changed: *mut bool,
            next_event_time_defined: *mut bool,
            next_event_time: *mut f64,
        ) -> $crate::types::fmi3Status {
            let r = $crate::modes::UpdateResults {
                discrete_states_need_update,
                terminate_simulation,
                nominals_changed,
                values_changed,
                next_event_time_defined,
                next_event_time,
            };
            unsafe { $crate::modes::update_discrete_states::<$slave>(c, r) }
        }

        $crate::__simple!($slave,
            fmi3SetDebugLogging => ffi::set_debug_logging(on: bool, n: usize, categories: *const $crate::types::fmi3String),
            fmi3EnterInitializationMode => ffi::enter_initialization_mode(
                tolerance_defined: bool, tolerance: f64, start_time: f64, stop_time_defined: bool, stop_time: f64),
            fmi3ExitInitializationMode => ffi::exit_initialization_mode(),
            fmi3Terminate => ffi::terminate(),
            fmi3Reset => ffi::reset(),
            fmi3GetOutputDerivatives => ffi::get_output_derivatives(
                vr: *const $crate::types::fmi3ValueReference, n: usize, orders: *const i32, values: *mut f64, n_values: usize),
            fmi3EnterEventMode => modes::enter_event_mode(),
            fmi3EnterStepMode => modes::enter_step_mode(),
            fmi3EnterContinuousTimeMode => modes::enter_continuous_time_mode(),
            fmi3CompletedIntegratorStep => modes::completed_integrator_step(
                no_set_prior: bool, enter_event_mode: *mut bool, terminate_simulation: *mut bool),
            fmi3SetTime => modes::set_time(time: f64),
            fmi3SetContinuousStates => modes::set_continuous_states(x: *const f64, n: usize),
            fmi3GetContinuousStates => modes::get_continuous_states(x: *mut f64, n: usize),
            fmi3GetNominalsOfContinuousStates => modes::get_nominals_of_continuous_states(x: *mut f64, n: usize),
            fmi3GetContinuousStateDerivatives => modes::get_derivatives(x: *mut f64, n: usize),
            fmi3GetEventIndicators => modes::get_event_indicators(x: *mut f64, n: usize),
            fmi3GetNumberOfContinuousStates => modes::get_number_of_continuous_states(n: *mut usize),
            fmi3GetNumberOfEventIndicators => modes::get_number_of_event_indicators(n: *mut usize),
            fmi3EnterConfigurationMode => arrays::enter_configuration_mode(),
            fmi3ExitConfigurationMode => arrays::exit_configuration_mode(),
        );

        $crate::__states!($slave,
            fmi3GetFMUState => get_fmu_state(state: *mut $crate::types::fmi3FMUState),
            fmi3SetFMUState => set_fmu_state(state: $crate::types::fmi3FMUState),
            fmi3FreeFMUState => free_fmu_state(state: *mut $crate::types::fmi3FMUState),
            fmi3SerializedFMUStateSize => serialized_fmu_state_size(
                state: $crate::types::fmi3FMUState, size: *mut usize),
            fmi3SerializeFMUState => serialize_fmu_state(
                state: $crate::types::fmi3FMUState, bytes: *mut $crate::types::fmi3Byte, size: usize),
            fmi3DeserializeFMUState => deserialize_fmu_state(
                bytes: *const $crate::types::fmi3Byte, size: usize, state: *mut $crate::types::fmi3FMUState),
        );

        $crate::__values!($slave,
            fmi3GetFloat64 => get_float64(*mut f64),
            fmi3SetFloat64 => set_float64(*const f64),
            fmi3GetInt32 => get_int32(*mut i32),
            fmi3SetInt32 => set_int32(*const i32),
            fmi3GetInt64 => get_int64(*mut i64),
            fmi3SetInt64 => set_int64(*const i64),
            fmi3GetBoolean => get_boolean(*mut bool),
            fmi3SetBoolean => set_boolean(*const bool),
            fmi3GetString => get_string(*mut $crate::types::fmi3String),
            fmi3SetString => set_string(*const $crate::types::fmi3String),
            fmi3GetUInt64 => get_uint64(*mut u64),
            fmi3SetUInt64 => set_uint64(*const u64),
        );
        $crate::__no_such_type!($slave,
            fmi3GetFloat32: *mut f32, fmi3SetFloat32: *const f32,
            fmi3GetInt8: *mut i8, fmi3SetInt8: *const i8,
            fmi3GetUInt8: *mut u8, fmi3SetUInt8: *const u8,
            fmi3GetInt16: *mut i16, fmi3SetInt16: *const i16,
            fmi3GetUInt16: *mut u16, fmi3SetUInt16: *const u16,
            fmi3GetUInt32: *mut u32, fmi3SetUInt32: *const u32,
            fmi3GetClock: *mut bool, fmi3SetClock: *const bool,
        );

        $crate::__not_provided!($slave,
            fmi3GetBinary(*const u32, usize, *mut usize, *mut *const u8, usize),
            fmi3SetBinary(*const u32, usize, *const usize, *const *const u8, usize),
            fmi3GetNumberOfVariableDependencies(u32, *mut usize),
            fmi3GetVariableDependencies(u32, *mut usize, *mut u32, *mut usize, *mut i32, usize),
            fmi3GetDirectionalDerivative(*const u32, usize, *const u32, usize, *const f64, usize, *mut f64, usize),
            fmi3GetAdjointDerivative(*const u32, usize, *const u32, usize, *const f64, usize, *mut f64, usize),
            fmi3GetIntervalDecimal(*const u32, usize, *mut f64, *mut i32),
            fmi3GetIntervalFraction(*const u32, usize, *mut u64, *mut u64, *mut i32),
            fmi3GetShiftDecimal(*const u32, usize, *mut f64),
            fmi3GetShiftFraction(*const u32, usize, *mut u64, *mut u64),
            fmi3SetIntervalDecimal(*const u32, usize, *const f64),
            fmi3SetIntervalFraction(*const u32, usize, *const u64, *const u64),
            fmi3SetShiftDecimal(*const u32, usize, *const f64),
            fmi3SetShiftFraction(*const u32, usize, *const u64, *const u64),
            fmi3EvaluateDiscreteStates(),
            fmi3ActivateModelPartition(u32, f64),
        );
    };
}

#[doc(hidden)]
pub use fmi2_export;
