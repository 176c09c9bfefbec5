//! The FMI 2.0 model description as plain Rust data (generic: nothing here
//! knows the rocking model). A model is one `static` [`ModelDescription`];
//! the XML, the value references the binary uses and the documentation are
//! all generated from it.

/// `causality` of a scalar variable (FMI 2.0 §2.2.7).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Causality {
    Parameter,
    CalculatedParameter,
    Input,
    Output,
    Local,
    Independent,
}

impl Causality {
    pub fn as_str(self) -> &'static str {
        match self {
            Causality::Parameter => "parameter",
            Causality::CalculatedParameter => "calculatedParameter",
            Causality::Input => "input",
            Causality::Output => "output",
            Causality::Local => "local",
            Causality::Independent => "independent",
        }
    }
}

/// `variability` of a scalar variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Variability {
    Constant,
    Fixed,
    Tunable,
    Discrete,
    Continuous,
}

impl Variability {
    pub fn as_str(self) -> &'static str {
        match self {
            Variability::Constant => "constant",
            Variability::Fixed => "fixed",
            Variability::Tunable => "tunable",
            Variability::Discrete => "discrete",
            Variability::Continuous => "continuous",
        }
    }
}

/// `initial` of a scalar variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Initial {
    Exact,
    Approx,
    Calculated,
}

impl Initial {
    pub fn as_str(self) -> &'static str {
        match self {
            Initial::Exact => "exact",
            Initial::Approx => "approx",
            Initial::Calculated => "calculated",
        }
    }
}

/// The base type of a variable, with its type-specific attributes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Type {
    Real {
        /// Name of a [`Unit`] of the model.
        unit: Option<&'static str>,
        /// Name of one of that unit's [`DisplayUnit`]s.
        display_unit: Option<&'static str>,
        start: Option<f64>,
        min: Option<f64>,
        max: Option<f64>,
    },
    Integer {
        start: Option<i32>,
    },
    Boolean {
        start: Option<bool>,
    },
    /// An enumeration, set and got as an Integer (FMI 2.0).
    Enumeration {
        /// Name of an [`EnumType`] of the model.
        declared_type: &'static str,
        start: Option<i32>,
    },
    String {
        start: Option<&'static str>,
    },
}

/// The FMI 2.0 C type through which a variable is set and got.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BaseType {
    Real,
    Integer,
    Boolean,
    String,
}

impl BaseType {
    pub fn as_str(self) -> &'static str {
        match self {
            BaseType::Real => "Real",
            BaseType::Integer => "Integer",
            BaseType::Boolean => "Boolean",
            BaseType::String => "String",
        }
    }
}

impl Type {
    /// A real without unit, start or bounds.
    pub const REAL: Type = Type::Real {
        unit: None,
        display_unit: None,
        start: None,
        min: None,
        max: None,
    };

    /// The C type through which the variable is accessed (enumerations are Integers).
    pub fn base(&self) -> BaseType {
        match self {
            Type::Real { .. } => BaseType::Real,
            Type::Integer { .. } | Type::Enumeration { .. } => BaseType::Integer,
            Type::Boolean { .. } => BaseType::Boolean,
            Type::String { .. } => BaseType::String,
        }
    }

    /// The element name in the XML.
    pub fn element(&self) -> &'static str {
        match self {
            Type::Real { .. } => "Real",
            Type::Integer { .. } => "Integer",
            Type::Boolean { .. } => "Boolean",
            Type::Enumeration { .. } => "Enumeration",
            Type::String { .. } => "String",
        }
    }

    pub fn has_start(&self) -> bool {
        match self {
            Type::Real { start, .. } => start.is_some(),
            Type::Integer { start } | Type::Enumeration { start, .. } => start.is_some(),
            Type::Boolean { start } => start.is_some(),
            Type::String { start } => start.is_some(),
        }
    }

    pub fn unit(&self) -> Option<&'static str> {
        match self {
            Type::Real { unit, .. } => *unit,
            _ => None,
        }
    }
}

/// One scalar variable.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Variable {
    /// Public name (stable).
    pub name: &'static str,
    /// Value reference (unique across all types in this crate's models).
    pub vr: u32,
    pub description: &'static str,
    pub causality: Causality,
    pub variability: Variability,
    /// `None`: the attribute is absent (inputs, and where the default applies).
    pub initial: Option<Initial>,
    pub ty: Type,
    /// For outputs and calculated parameters: the names of the variables
    /// this one depends on at initialization (inputs, parameters and
    /// variables with `initial = exact`). Its subset of inputs is its
    /// dependency list in `ModelStructure/Outputs`. Empty for the others.
    pub depends_on: &'static [&'static str],
    /// For a state derivative (Model Exchange): the name of the continuous
    /// state it is the derivative of (`derivative` attribute); it is then
    /// listed in `ModelStructure/Derivatives`, with the inputs and states
    /// of `depends_on` as its dependencies.
    pub derivative: Option<&'static str>,
    /// The inputs and continuous states it depends on in continuous-time and
    /// event mode and at communication points (`ModelStructure/Outputs`,
    /// `Derivatives`), where those of `depends_on` are not: an output whose
    /// start value is exact that depends on an input afterwards, a derivative
    /// that depends on a state whose start is calculated. Empty: the inputs
    /// and states of `depends_on`.
    pub run_depends_on: &'static [&'static str],
}

impl Variable {
    /// A template for `..Variable::DEFAULT` in tables.
    pub const DEFAULT: Variable = Variable {
        name: "",
        vr: 0,
        description: "",
        causality: Causality::Local,
        variability: Variability::Continuous,
        initial: None,
        ty: Type::REAL,
        depends_on: &[],
        derivative: None,
        run_depends_on: &[],
    };

    /// The names its `ModelStructure/Outputs` or `Derivatives` entry draws
    /// on (see `run_depends_on`), before keeping inputs (and states).
    pub fn run_dependencies(&self) -> &'static [&'static str] {
        if self.run_depends_on.is_empty() {
            self.depends_on
        } else {
            self.run_depends_on
        }
    }

    /// The effective `initial` (FMI 2.0 Table on p. 50: defaults when absent).
    pub fn effective_initial(&self) -> Option<Initial> {
        if self.initial.is_some() {
            return self.initial;
        }
        use Causality as C;
        use Variability as V;
        match (self.causality, self.variability) {
            (C::Parameter, _) => Some(Initial::Exact),
            (C::CalculatedParameter, _) => Some(Initial::Calculated),
            (C::Output, V::Constant) | (C::Local, V::Constant) => Some(Initial::Exact),
            (C::Output, _) | (C::Local, _) => Some(Initial::Calculated),
            (C::Input, _) | (C::Independent, _) => None,
        }
    }

    /// Whether the variable belongs to `ModelStructure/InitialUnknowns`
    /// (FMI 2.0 §2.2.8): outputs and locals that are calculated, calculated
    /// parameters, and the state derivatives (Model Exchange).
    pub fn is_initial_unknown(&self) -> bool {
        if self.derivative.is_some() {
            return matches!(
                self.effective_initial(),
                Some(Initial::Approx | Initial::Calculated)
            );
        }
        match self.causality {
            Causality::CalculatedParameter => true,
            Causality::Output => matches!(
                self.effective_initial(),
                Some(Initial::Approx | Initial::Calculated)
            ),
            _ => false,
        }
    }
}

/// Exponents of the SI base units and the factor/offset to them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BaseUnit {
    pub kg: i32,
    pub m: i32,
    pub s: i32,
    /// Ampere exponent.
    pub ampere: i32,
    /// Kelvin exponent.
    pub kelvin: i32,
    pub mol: i32,
    pub cd: i32,
    pub rad: i32,
    pub factor: f64,
    pub offset: f64,
}

impl BaseUnit {
    pub const ONE: BaseUnit = BaseUnit {
        kg: 0,
        m: 0,
        s: 0,
        ampere: 0,
        kelvin: 0,
        mol: 0,
        cd: 0,
        rad: 0,
        factor: 1.0,
        offset: 0.0,
    };
}

/// `display = factor * value + offset`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DisplayUnit {
    pub name: &'static str,
    pub factor: f64,
    pub offset: f64,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Unit {
    pub name: &'static str,
    pub base: BaseUnit,
    pub display: &'static [DisplayUnit],
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnumItem {
    pub name: &'static str,
    pub value: i32,
    pub description: &'static str,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnumType {
    pub name: &'static str,
    pub description: &'static str,
    pub items: &'static [EnumItem],
}

impl EnumType {
    pub fn item(&self, value: i32) -> Option<&EnumItem> {
        self.items.iter().find(|i| i.value == value)
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LogCategory {
    pub name: &'static str,
    pub description: &'static str,
}

/// The `<CoSimulation>` element's capability flags.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CoSimulation {
    pub model_identifier: &'static str,
    pub needs_execution_tool: bool,
    pub can_handle_variable_communication_step_size: bool,
    pub can_interpolate_inputs: bool,
    pub max_output_derivative_order: u32,
    pub can_run_asynchronuously: bool,
    pub can_be_instantiated_only_once_per_process: bool,
    pub can_not_use_memory_management_functions: bool,
    pub can_get_and_set_fmu_state: bool,
    pub can_serialize_fmu_state: bool,
    pub provides_directional_derivative: bool,
    /// FMI 3.0 only (`hasEventMode`): the FMU has event mode in co-simulation.
    pub has_event_mode: bool,
    /// FMI 3.0 only (`mightReturnEarlyFromDoStep`): `fmi3DoStep` may stop at
    /// an event before the end of the step when the host allows it.
    pub might_return_early_from_do_step: bool,
}

/// The `<ModelExchange>` element: capabilities of an FMU's Model Exchange
/// interface (FMI 2.0 §3.3).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelExchange {
    pub model_identifier: &'static str,
    pub needs_execution_tool: bool,
    pub completed_integrator_step_not_needed: bool,
    pub can_be_instantiated_only_once_per_process: bool,
    pub can_not_use_memory_management_functions: bool,
    pub can_get_and_set_fmu_state: bool,
    pub can_serialize_fmu_state: bool,
    pub provides_directional_derivative: bool,
    /// `numberOfEventIndicators` of the model description.
    pub event_indicators: u32,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DefaultExperiment {
    pub start_time: f64,
    pub stop_time: f64,
    pub tolerance: f64,
    pub step_size: f64,
}

/// A whole model description.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelDescription {
    pub model_name: &'static str,
    pub description: &'static str,
    pub author: &'static str,
    pub version: &'static str,
    pub copyright: &'static str,
    pub license: &'static str,
    pub generation_tool: &'static str,
    pub co_simulation: CoSimulation,
    /// The Model Exchange interface, if the FMU has one.
    pub model_exchange: Option<ModelExchange>,
    pub units: &'static [Unit],
    pub types: &'static [EnumType],
    pub log_categories: &'static [LogCategory],
    pub default_experiment: DefaultExperiment,
    /// In XML order (the 1-based position is the variable's index).
    pub variables: &'static [Variable],
    /// HTML fragment for `documentation/index.html`, before the generated tables.
    pub documentation: &'static str,
    /// FMI 3.0 only: the table's per-element scalars that are arrays there.
    pub arrays3: Option<crate::fmi3::Arrays3>,
}

impl ModelDescription {
    pub fn variable(&self, name: &str) -> Option<&'static Variable> {
        self.variables.iter().find(|v| v.name == name)
    }

    /// The variable of value reference `vr` accessed through `base`.
    ///
    /// Every `fmi2Get*`/`fmi2Set*` and every input a step reads comes here,
    /// so the usual table, listed by ascending value reference from 0 (the
    /// one `vr` of each variable: [`check`](Self::check)), is looked up
    /// from index `vr` downwards, where the variable is: one or two
    /// comparisons instead of a scan of the table (which cost 3-5 % of a
    /// rigid body's `fmi2DoStep`). Any other table is scanned.
    pub fn by_vr(&self, base: BaseType, vr: u32) -> Option<(usize, &'static Variable)> {
        let vars = self.variables;
        if let Some(last) = vars.len().checked_sub(1) {
            let mut i = (vr as usize).min(last);
            loop {
                let v = &vars[i];
                if v.vr == vr && v.ty.base() == base {
                    return Some((i, v));
                }
                if v.vr <= vr || i == 0 {
                    break;
                }
                i -= 1;
            }
        }
        self.variables
            .iter()
            .enumerate()
            .find(|(_, v)| v.vr == vr && v.ty.base() == base)
    }

    /// 1-based index of a variable in `ModelVariables`.
    pub fn index_of(&self, name: &str) -> Option<usize> {
        self.variables
            .iter()
            .position(|v| v.name == name)
            .map(|i| i + 1)
    }

    pub fn enum_type(&self, name: &str) -> Option<&'static EnumType> {
        self.types.iter().find(|t| t.name == name)
    }

    pub fn unit(&self, name: &str) -> Option<&'static Unit> {
        self.units.iter().find(|u| u.name == name)
    }

    /// Consistency checks the XML schema cannot express; `Err` lists every problem.
    pub fn check(&self) -> Result<(), Vec<String>> {
        let mut p = Vec::new();
        for (i, v) in self.variables.iter().enumerate() {
            if self.variables[..i].iter().any(|w| w.name == v.name) {
                p.push(format!("variable name {} is not unique", v.name));
            }
            if self.variables[..i].iter().any(|w| w.vr == v.vr) {
                p.push(format!(
                    "value reference {} of {} is not unique",
                    v.vr, v.name
                ));
            }
            if v.description.is_empty() {
                p.push(format!("{} has no description", v.name));
            }
            if let Some(u) = v.ty.unit() {
                match self.unit(u) {
                    None => p.push(format!("unit {u} of {} is not defined", v.name)),
                    Some(unit) => {
                        if let Type::Real {
                            display_unit: Some(d),
                            ..
                        } = v.ty
                        {
                            if !unit.display.iter().any(|x| x.name == d) {
                                p.push(format!("display unit {d} of {} is not defined", v.name));
                            }
                        }
                    }
                }
            }
            if let Type::Enumeration {
                declared_type,
                start,
            } = v.ty
            {
                match self.enum_type(declared_type) {
                    None => p.push(format!("type {declared_type} of {} is not defined", v.name)),
                    Some(t) => {
                        if let Some(s) = start {
                            if t.item(s).is_none() {
                                p.push(format!(
                                    "start {s} of {} is no item of {declared_type}",
                                    v.name
                                ));
                            }
                        }
                    }
                }
            }
            let init = v.effective_initial();
            let needs_start = matches!(init, Some(Initial::Exact | Initial::Approx))
                || v.causality == Causality::Input;
            if needs_start != v.ty.has_start() {
                p.push(format!(
                    "{}: a start value is {} with initial {:?}",
                    v.name,
                    if needs_start { "required" } else { "forbidden" },
                    init
                ));
            }
            if !v.depends_on.is_empty() && !v.is_initial_unknown() {
                p.push(format!(
                    "{} lists dependencies but is no initial unknown",
                    v.name
                ));
            }
            if let Some(x) = v.derivative {
                match self.variable(x) {
                    Some(k)
                        if k.variability == Variability::Continuous
                            && k.ty.base() == BaseType::Real => {}
                    _ => p.push(format!(
                        "{} is the derivative of {x}, which is no continuous real",
                        v.name
                    )),
                }
            }
            for d in v.run_depends_on {
                let known = self.variable(d).is_some_and(|k| {
                    k.causality == Causality::Input
                        || self.variables.iter().any(|x| x.derivative == Some(k.name))
                });
                if !known {
                    p.push(format!(
                        "{} depends on {d} in a run, which is no input or continuous state",
                        v.name
                    ));
                }
            }
            for d in v.depends_on {
                match self.variable(d) {
                    None => p.push(format!("{} depends on unknown variable {d}", v.name)),
                    Some(k) => {
                        let known = k.causality == Causality::Input
                            || k.causality == Causality::Independent
                            || k.effective_initial() == Some(Initial::Exact);
                        if !known {
                            p.push(format!(
                                "{} depends on {d}, which is not known at initialization",
                                v.name
                            ));
                        }
                    }
                }
            }
        }
        if p.is_empty() {
            Ok(())
        } else {
            Err(p)
        }
    }
}
