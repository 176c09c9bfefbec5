//! What every FMU of this project declares alike: who made it, under which
//! licence, and the co-simulation and model-exchange capabilities of the generic FMI 2.0 layer
//! (`fmi2-export`), which are the layer's, not a model's.

use crate::schema::{CoSimulation, ModelExchange};

pub const AUTHOR: &str = "RockingBlock developers";
pub const COPYRIGHT: &str = "RockingBlock developers";
pub const LICENSE: &str = "MIT OR Apache-2.0";
pub const GENERATION_TOOL: &str =
    concat!("RockingBlock model-description ", env!("CARGO_PKG_VERSION"));

/// The `<CoSimulation>` element of an FMU served by `fmi2-export`: variable
/// steps, inputs interpolated from their derivatives, output derivatives to
/// order 2, FMU states saved and serialized.
pub const fn co_simulation(model_identifier: &'static str) -> CoSimulation {
    CoSimulation {
        model_identifier,
        needs_execution_tool: false,
        can_handle_variable_communication_step_size: true,
        can_interpolate_inputs: true,
        max_output_derivative_order: 2,
        can_run_asynchronuously: false,
        can_be_instantiated_only_once_per_process: false,
        can_not_use_memory_management_functions: true,
        can_get_and_set_fmu_state: true,
        can_serialize_fmu_state: true,
        provides_directional_derivative: false,
        has_event_mode: false,
        might_return_early_from_do_step: false,
    }
}

/// The `<ModelExchange>` element of an FMU served by `fmi2-export` with
/// `event_indicators` event indicators: FMU states saved and serialized;
/// `fmi2CompletedIntegratorStep` is wanted (the model keeps books there).
pub const fn model_exchange(
    model_identifier: &'static str,
    event_indicators: u32,
) -> ModelExchange {
    ModelExchange {
        model_identifier,
        needs_execution_tool: false,
        completed_integrator_step_not_needed: false,
        can_be_instantiated_only_once_per_process: false,
        can_not_use_memory_management_functions: true,
        can_get_and_set_fmu_state: true,
        can_serialize_fmu_state: true,
        provides_directional_derivative: false,
        event_indicators,
    }
}
