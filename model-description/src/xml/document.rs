//! The FMI 2.0 `modelDescription.xml` document as serde types, element and
//! attribute order as in the FMI 2.0 XSD; `xml.rs` fills them from a
//! [`ModelDescription`](crate::schema::ModelDescription).

use serde::Serialize;

#[derive(Serialize)]
#[serde(rename = "fmiModelDescription")]
pub(super) struct Root {
    #[serde(rename = "@fmiVersion")]
    pub(super) fmi_version: &'static str,
    #[serde(rename = "@modelName")]
    pub(super) model_name: &'static str,
    #[serde(rename = "@guid")]
    pub(super) guid: String,
    #[serde(rename = "@description")]
    pub(super) description: &'static str,
    #[serde(rename = "@author")]
    pub(super) author: &'static str,
    #[serde(rename = "@version")]
    pub(super) version: &'static str,
    #[serde(rename = "@copyright")]
    pub(super) copyright: &'static str,
    #[serde(rename = "@license")]
    pub(super) license: &'static str,
    #[serde(rename = "@generationTool")]
    pub(super) generation_tool: &'static str,
    #[serde(
        rename = "@generationDateAndTime",
        skip_serializing_if = "Option::is_none"
    )]
    pub(super) generation_date_and_time: Option<String>,
    #[serde(rename = "@variableNamingConvention")]
    pub(super) naming: &'static str,
    #[serde(rename = "@numberOfEventIndicators")]
    pub(super) event_indicators: u32,
    #[serde(rename = "ModelExchange", skip_serializing_if = "Option::is_none")]
    pub(super) model_exchange: Option<XModelExchange>,
    #[serde(rename = "CoSimulation")]
    pub(super) co_simulation: XCoSimulation,
    #[serde(rename = "UnitDefinitions")]
    pub(super) units: XUnits,
    #[serde(rename = "TypeDefinitions")]
    pub(super) types: XTypes,
    #[serde(rename = "LogCategories")]
    pub(super) log_categories: XLogCategories,
    #[serde(rename = "DefaultExperiment")]
    pub(super) default_experiment: XDefaultExperiment,
    #[serde(rename = "ModelVariables")]
    pub(super) variables: XVariables,
    #[serde(rename = "ModelStructure")]
    pub(super) structure: XStructure,
}

#[derive(Serialize)]
pub(super) struct XModelExchange {
    #[serde(rename = "@modelIdentifier")]
    pub(super) model_identifier: &'static str,
    #[serde(rename = "@needsExecutionTool")]
    pub(super) needs_execution_tool: &'static str,
    #[serde(rename = "@completedIntegratorStepNotNeeded")]
    pub(super) completed_step_not_needed: &'static str,
    #[serde(rename = "@canBeInstantiatedOnlyOncePerProcess")]
    pub(super) only_once: &'static str,
    #[serde(
        rename = "@canNotUseMemoryManagementFunctions",
        skip_serializing_if = "Option::is_none"
    )]
    pub(super) no_memory_management: Option<&'static str>,
    #[serde(
        rename = "@canGetAndSetFMUstate",
        skip_serializing_if = "Option::is_none"
    )]
    pub(super) get_set_state: Option<&'static str>,
    #[serde(
        rename = "@canSerializeFMUstate",
        skip_serializing_if = "Option::is_none"
    )]
    pub(super) serialize_state: Option<&'static str>,
    #[serde(
        rename = "@providesDirectionalDerivative",
        skip_serializing_if = "Option::is_none"
    )]
    pub(super) directional_derivative: Option<&'static str>,
}

#[derive(Serialize)]
pub(super) struct XCoSimulation {
    #[serde(rename = "@modelIdentifier")]
    pub(super) model_identifier: &'static str,
    #[serde(rename = "@needsExecutionTool")]
    pub(super) needs_execution_tool: &'static str,
    #[serde(
        rename = "@canHandleVariableCommunicationStepSize",
        skip_serializing_if = "Option::is_none"
    )]
    pub(super) variable_step: Option<&'static str>,
    #[serde(
        rename = "@canInterpolateInputs",
        skip_serializing_if = "Option::is_none"
    )]
    pub(super) interpolate_inputs: Option<&'static str>,
    #[serde(
        rename = "@maxOutputDerivativeOrder",
        skip_serializing_if = "Option::is_none"
    )]
    pub(super) max_output_derivative_order: Option<u32>,
    #[serde(
        rename = "@canRunAsynchronuously",
        skip_serializing_if = "Option::is_none"
    )]
    pub(super) asynchronuously: Option<&'static str>,
    #[serde(rename = "@canBeInstantiatedOnlyOncePerProcess")]
    pub(super) only_once: &'static str,
    #[serde(
        rename = "@canNotUseMemoryManagementFunctions",
        skip_serializing_if = "Option::is_none"
    )]
    pub(super) no_memory_management: Option<&'static str>,
    #[serde(
        rename = "@canGetAndSetFMUstate",
        skip_serializing_if = "Option::is_none"
    )]
    pub(super) get_set_state: Option<&'static str>,
    #[serde(
        rename = "@canSerializeFMUstate",
        skip_serializing_if = "Option::is_none"
    )]
    pub(super) serialize_state: Option<&'static str>,
    #[serde(
        rename = "@providesDirectionalDerivative",
        skip_serializing_if = "Option::is_none"
    )]
    pub(super) directional_derivative: Option<&'static str>,
}

#[derive(Serialize)]
pub(super) struct XUnits {
    #[serde(rename = "Unit")]
    pub(super) units: Vec<XUnit>,
}

#[derive(Serialize)]
pub(super) struct XUnit {
    #[serde(rename = "@name")]
    pub(super) name: &'static str,
    #[serde(rename = "BaseUnit")]
    pub(super) base: XBaseUnit,
    #[serde(rename = "DisplayUnit")]
    pub(super) display: Vec<XDisplayUnit>,
}

#[derive(Serialize)]
pub(super) struct XBaseUnit {
    #[serde(rename = "@kg", skip_serializing_if = "Option::is_none")]
    pub(super) kg: Option<i32>,
    #[serde(rename = "@m", skip_serializing_if = "Option::is_none")]
    pub(super) m: Option<i32>,
    #[serde(rename = "@s", skip_serializing_if = "Option::is_none")]
    pub(super) s: Option<i32>,
    #[serde(rename = "@A", skip_serializing_if = "Option::is_none")]
    pub(super) a: Option<i32>,
    #[serde(rename = "@K", skip_serializing_if = "Option::is_none")]
    pub(super) k: Option<i32>,
    #[serde(rename = "@mol", skip_serializing_if = "Option::is_none")]
    pub(super) mol: Option<i32>,
    #[serde(rename = "@cd", skip_serializing_if = "Option::is_none")]
    pub(super) cd: Option<i32>,
    #[serde(rename = "@rad", skip_serializing_if = "Option::is_none")]
    pub(super) rad: Option<i32>,
    #[serde(rename = "@factor", skip_serializing_if = "Option::is_none")]
    pub(super) factor: Option<String>,
    #[serde(rename = "@offset", skip_serializing_if = "Option::is_none")]
    pub(super) offset: Option<String>,
}

#[derive(Serialize)]
pub(super) struct XDisplayUnit {
    #[serde(rename = "@name")]
    pub(super) name: &'static str,
    #[serde(rename = "@factor")]
    pub(super) factor: String,
    #[serde(rename = "@offset", skip_serializing_if = "Option::is_none")]
    pub(super) offset: Option<String>,
}

#[derive(Serialize)]
pub(super) struct XTypes {
    #[serde(rename = "SimpleType")]
    pub(super) types: Vec<XSimpleType>,
}

#[derive(Serialize)]
pub(super) struct XSimpleType {
    #[serde(rename = "@name")]
    pub(super) name: &'static str,
    #[serde(rename = "@description")]
    pub(super) description: &'static str,
    #[serde(rename = "Enumeration")]
    pub(super) enumeration: XEnumeration,
}

#[derive(Serialize)]
pub(super) struct XEnumeration {
    #[serde(rename = "Item")]
    pub(super) items: Vec<XItem>,
}

#[derive(Serialize)]
pub(super) struct XItem {
    #[serde(rename = "@name")]
    pub(super) name: &'static str,
    #[serde(rename = "@value")]
    pub(super) value: i32,
    #[serde(rename = "@description")]
    pub(super) description: &'static str,
}

#[derive(Serialize)]
pub(super) struct XLogCategories {
    #[serde(rename = "Category")]
    pub(super) categories: Vec<XCategory>,
}

#[derive(Serialize)]
pub(super) struct XCategory {
    #[serde(rename = "@name")]
    pub(super) name: &'static str,
    #[serde(rename = "@description")]
    pub(super) description: &'static str,
}

#[derive(Serialize)]
pub(super) struct XDefaultExperiment {
    #[serde(rename = "@startTime")]
    pub(super) start_time: String,
    #[serde(rename = "@stopTime")]
    pub(super) stop_time: String,
    #[serde(rename = "@tolerance")]
    pub(super) tolerance: String,
    #[serde(rename = "@stepSize")]
    pub(super) step_size: String,
}

#[derive(Serialize)]
pub(super) struct XVariables {
    #[serde(rename = "ScalarVariable")]
    pub(super) variables: Vec<XScalarVariable>,
}

#[derive(Serialize)]
pub(super) struct XScalarVariable {
    #[serde(rename = "@name")]
    pub(super) name: &'static str,
    #[serde(rename = "@valueReference")]
    pub(super) vr: u32,
    #[serde(rename = "@description")]
    pub(super) description: &'static str,
    #[serde(rename = "@causality")]
    pub(super) causality: &'static str,
    #[serde(rename = "@variability")]
    pub(super) variability: &'static str,
    #[serde(rename = "@initial", skip_serializing_if = "Option::is_none")]
    pub(super) initial: Option<&'static str>,
    #[serde(rename = "$value")]
    pub(super) ty: XType,
}

#[derive(Serialize)]
pub(super) enum XType {
    Real(XReal),
    Integer(XStart),
    Boolean(XStart),
    Enumeration(XEnum),
    String(XStart),
}

#[derive(Serialize)]
pub(super) struct XReal {
    #[serde(rename = "@unit", skip_serializing_if = "Option::is_none")]
    pub(super) unit: Option<&'static str>,
    #[serde(rename = "@displayUnit", skip_serializing_if = "Option::is_none")]
    pub(super) display_unit: Option<&'static str>,
    #[serde(rename = "@min", skip_serializing_if = "Option::is_none")]
    pub(super) min: Option<String>,
    #[serde(rename = "@max", skip_serializing_if = "Option::is_none")]
    pub(super) max: Option<String>,
    #[serde(rename = "@start", skip_serializing_if = "Option::is_none")]
    pub(super) start: Option<String>,
    #[serde(rename = "@derivative", skip_serializing_if = "Option::is_none")]
    pub(super) derivative: Option<usize>,
}

#[derive(Serialize)]
pub(super) struct XStart {
    #[serde(rename = "@start", skip_serializing_if = "Option::is_none")]
    pub(super) start: Option<String>,
}

#[derive(Serialize)]
pub(super) struct XEnum {
    #[serde(rename = "@declaredType")]
    pub(super) declared_type: &'static str,
    #[serde(rename = "@start", skip_serializing_if = "Option::is_none")]
    pub(super) start: Option<String>,
}

#[derive(Serialize)]
pub(super) struct XStructure {
    #[serde(rename = "Outputs")]
    pub(super) outputs: XUnknowns,
    #[serde(rename = "Derivatives", skip_serializing_if = "Option::is_none")]
    pub(super) derivatives: Option<XUnknowns>,
    #[serde(rename = "InitialUnknowns")]
    pub(super) initial_unknowns: XUnknowns,
}

#[derive(Serialize)]
pub(super) struct XUnknowns {
    #[serde(rename = "Unknown")]
    pub(super) unknowns: Vec<XUnknown>,
}

#[derive(Serialize)]
pub(super) struct XUnknown {
    #[serde(rename = "@index")]
    pub(super) index: usize,
    #[serde(rename = "@dependencies")]
    pub(super) dependencies: String,
}
