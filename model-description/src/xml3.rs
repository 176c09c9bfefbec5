//! `modelDescription.xml` (FMI 3.0) from the same [`ModelDescription`] as
//! the FMI 2.0 one. Element order follows the FMI 3.0 XSD; variables and
//! dependencies are named by value reference, enumerations are `Int64`
//! when got and set, `time`, the event indicators and the inputs'
//! derivatives are added ([`crate::fmi3`]). The instantiation token is the 2.0 GUID: both files
//! are functions of one table, and one binary serves both.

use std::fmt::Write;

use crate::fmi3::TIME;
use crate::schema::*;
use crate::xml::{fmt_real, guid};

/// An element under construction: attributes, then children or `/>`.
struct El {
    out: String,
    depth: usize,
}

/// `&`, `<`, `>` and `"` escaped for an attribute value.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

impl El {
    fn open(&mut self, name: &str, attrs: &[(&str, Option<String>)], empty: bool) {
        let _ = write!(self.out, "{:1$}<{name}", "", 2 * self.depth);
        for (k, v) in attrs {
            if let Some(v) = v {
                let _ = write!(self.out, " {k}=\"{}\"", escape(v));
            }
        }
        self.out.push_str(if empty { "/>\n" } else { ">\n" });
        if !empty {
            self.depth += 1;
        }
    }

    fn close(&mut self, name: &str) {
        self.depth -= 1;
        let _ = writeln!(self.out, "{:1$}</{name}>", "", 2 * self.depth);
    }
}

fn s(x: &str) -> Option<String> {
    Some(x.to_string())
}

fn b(x: bool) -> Option<String> {
    s(if x { "true" } else { "false" })
}

/// A variable element, with `<Dimension>` sized by the value reference
/// `size` for an array.
fn typed(e: &mut El, tag: &str, attrs: &[(&str, Option<String>)], size: Option<u32>) {
    match size {
        None => e.open(tag, attrs, true),
        Some(vr) => {
            e.open(tag, attrs, false);
            e.open(
                "Dimension",
                &[("valueReference", Some(vr.to_string()))],
                true,
            );
            e.close(tag);
        }
    }
}

/// Name, description and size (the structural parameter's value
/// reference) of a table variable in 3.0; `None` for an array element past
/// the first (the array stands for it).
fn naming(
    md: &ModelDescription,
    v: &Variable,
) -> Option<(&'static str, &'static str, Option<u32>)> {
    if let Some(a) = md.arrays3.filter(|a| a.size == v.name) {
        return Some((v.name, a.size_description, None));
    }
    match md.fmi3_element(v.name) {
        None => Some((v.name, v.description, None)),
        Some((name, description, 1)) => Some((name, description, md.fmi3_size().map(|n| n.vr))),
        Some(_) => None,
    }
}

fn variable(e: &mut El, md: &ModelDescription, v: &Variable) {
    let Some((name, description, size)) = naming(md, v) else {
        return;
    };
    let structural = md.fmi3_type(v) == "UInt64";
    let causality = if structural {
        "structuralParameter"
    } else {
        v.causality.as_str()
    };
    let mut a = vec![
        ("name", s(name)),
        ("valueReference", Some(v.vr.to_string())),
        ("description", s(description)),
        ("causality", s(causality)),
        ("variability", s(v.variability.as_str())),
        ("initial", v.initial.map(|i| i.as_str().to_string())),
    ];
    match v.ty {
        Type::Real {
            unit,
            display_unit,
            start,
            min,
            max,
        } => a.extend([
            ("unit", unit.map(str::to_string)),
            ("displayUnit", display_unit.map(str::to_string)),
            ("min", min.map(fmt_real)),
            ("max", max.map(fmt_real)),
            ("start", start.map(fmt_real)),
            (
                "derivative",
                v.derivative.map(|x| {
                    md.variable(x)
                        .expect("derivatives are checked")
                        .vr
                        .to_string()
                }),
            ),
        ]),
        Type::Integer { start } if structural => a.extend([
            ("min", s("1")),
            ("max", md.arrays3.map(|x| x.len.to_string())),
            ("start", start.map(|x| x.to_string())),
        ]),
        Type::Integer { start } => a.push(("start", start.map(|x| x.to_string()))),
        Type::Boolean { start } => a.push(("start", start.map(|x| x.to_string()))),
        Type::Enumeration {
            declared_type,
            start,
        } => a.extend([
            ("declaredType", s(declared_type)),
            ("start", start.map(|x| x.to_string())),
        ]),
        Type::String { start } => {
            e.open("String", &a, false);
            if let Some(x) = start {
                e.open("Start", &[("value", s(x))], true);
            }
            e.close("String");
            return;
        }
    }
    typed(e, md.fmi3_type(v), &a, size);
}

/// Value references of `names`, sorted, space-separated.
fn vrs<'a>(md: &ModelDescription, names: impl Iterator<Item = &'a str>) -> String {
    let mut r: Vec<u32> = names
        .map(|n| md.fmi3_vr(n).expect("dependency names are checked"))
        .collect();
    r.sort_unstable();
    r.dedup();
    r.iter().map(u32::to_string).collect::<Vec<_>>().join(" ")
}

/// The table variables a 3.0 variable stands for: an array's elements,
/// the scalar itself, none for an element past the first.
fn members<'a>(md: &'a ModelDescription, v: &Variable) -> Vec<&'a Variable> {
    match md.fmi3_element(v.name) {
        None => vec![md.variable(v.name).expect("a table variable")],
        Some((array, _, 1)) => md
            .variables
            .iter()
            .filter(|w| md.fmi3_element(w.name).is_some_and(|x| x.0 == array))
            .collect(),
        Some(_) => vec![],
    }
}

fn structure(e: &mut El, md: &ModelDescription) {
    let is_input = |d: &&str| {
        md.variable(d)
            .is_some_and(|k| k.causality == Causality::Input)
    };
    let is_state = |d: &&str| md.variables.iter().any(|x| x.derivative == Some(*d));
    // an array's dependencies: its elements' together
    let unknown = |e: &mut El, tag: &str, v: &Variable, deps: &dyn Fn(&Variable) -> Vec<&str>| {
        let all = members(md, v);
        if all.is_empty() {
            return;
        }
        let deps = vrs(md, all.into_iter().flat_map(deps));
        e.open(
            tag,
            &[
                ("valueReference", Some(v.vr.to_string())),
                ("dependencies", Some(deps)),
            ],
            true,
        );
    };
    e.open("ModelStructure", &[], false);
    for v in md
        .variables
        .iter()
        .filter(|v| v.causality == Causality::Output)
    {
        unknown(e, "Output", v, &|v| {
            v.run_dependencies()
                .iter()
                .copied()
                .filter(is_input)
                .collect()
        });
    }
    for v in md.variables.iter().filter(|v| v.derivative.is_some()) {
        unknown(e, "ContinuousStateDerivative", v, &|v| {
            v.run_dependencies()
                .iter()
                .copied()
                .filter(|d| is_input(d) || is_state(d))
                .collect()
        });
    }
    for v in md.variables.iter().filter(|v| v.is_initial_unknown()) {
        unknown(e, "InitialUnknown", v, &|v| v.depends_on.to_vec());
    }
    for i in 0..md.event_indicator_count() {
        let vr = md.fmi3_event_indicator_vr(i).to_string();
        e.open("EventIndicator", &[("valueReference", Some(vr))], true);
    }
    e.close("ModelStructure");
}

fn units(e: &mut El, md: &ModelDescription) {
    e.open("UnitDefinitions", &[], false);
    for u in md.units {
        e.open("Unit", &[("name", s(u.name))], false);
        let x = &u.base;
        let nz = |k: i32| (k != 0).then(|| k.to_string());
        e.open(
            "BaseUnit",
            &[
                ("kg", nz(x.kg)),
                ("m", nz(x.m)),
                ("s", nz(x.s)),
                ("A", nz(x.ampere)),
                ("K", nz(x.kelvin)),
                ("mol", nz(x.mol)),
                ("cd", nz(x.cd)),
                ("rad", nz(x.rad)),
                ("factor", (x.factor != 1.0).then(|| fmt_real(x.factor))),
                ("offset", (x.offset != 0.0).then(|| fmt_real(x.offset))),
            ],
            true,
        );
        for d in u.display {
            let attrs = [
                ("name", s(d.name)),
                ("factor", Some(fmt_real(d.factor))),
                ("offset", (d.offset != 0.0).then(|| fmt_real(d.offset))),
            ];
            e.open("DisplayUnit", &attrs, true);
        }
        e.close("Unit");
    }
    e.close("UnitDefinitions");
}

fn types(e: &mut El, md: &ModelDescription) {
    if md.types.is_empty() {
        return;
    }
    e.open("TypeDefinitions", &[], false);
    for t in md.types {
        let attrs = [("name", s(t.name)), ("description", s(t.description))];
        e.open("EnumerationType", &attrs, false);
        for i in t.items {
            let attrs = [
                ("name", s(i.name)),
                ("value", Some(i.value.to_string())),
                ("description", s(i.description)),
            ];
            e.open("Item", &attrs, true);
        }
        e.close("EnumerationType");
    }
    e.close("TypeDefinitions");
}

fn interfaces(e: &mut El, md: &ModelDescription) {
    if let Some(me) = md.model_exchange {
        let attrs = [
            ("modelIdentifier", s(me.model_identifier)),
            ("needsExecutionTool", b(me.needs_execution_tool)),
            (
                "canBeInstantiatedOnlyOncePerProcess",
                b(me.can_be_instantiated_only_once_per_process),
            ),
            ("canGetAndSetFMUState", b(me.can_get_and_set_fmu_state)),
            ("canSerializeFMUState", b(me.can_serialize_fmu_state)),
            (
                "providesDirectionalDerivatives",
                b(me.provides_directional_derivative),
            ),
            (
                "needsCompletedIntegratorStep",
                b(!me.completed_integrator_step_not_needed),
            ),
        ];
        e.open("ModelExchange", &attrs, true);
    }
    let cs = &md.co_simulation;
    let attrs = [
        ("modelIdentifier", s(cs.model_identifier)),
        ("needsExecutionTool", b(cs.needs_execution_tool)),
        (
            "canBeInstantiatedOnlyOncePerProcess",
            b(cs.can_be_instantiated_only_once_per_process),
        ),
        ("canGetAndSetFMUState", b(cs.can_get_and_set_fmu_state)),
        ("canSerializeFMUState", b(cs.can_serialize_fmu_state)),
        (
            "providesDirectionalDerivatives",
            b(cs.provides_directional_derivative),
        ),
        (
            "canHandleVariableCommunicationStepSize",
            b(cs.can_handle_variable_communication_step_size),
        ),
        (
            "maxOutputDerivativeOrder",
            Some(cs.max_output_derivative_order.to_string()),
        ),
        ("hasEventMode", b(cs.has_event_mode)),
        (
            "mightReturnEarlyFromDoStep",
            b(cs.might_return_early_from_do_step),
        ),
    ];
    e.open("CoSimulation", &attrs, true);
}

/// The FMI 3.0 XML with the given instantiation token and, if given, the
/// `generationDateAndTime` attribute (`xs:dateTime`).
pub fn render(md: &ModelDescription, token: &str, generated: Option<&str>) -> String {
    if let Err(problems) = md.check() {
        panic!("inconsistent model description:\n{}", problems.join("\n"));
    }
    let mut e = El {
        out: String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"),
        depth: 0,
    };
    let root = [
        ("fmiVersion", s("3.0")),
        ("modelName", s(md.model_name)),
        ("instantiationToken", s(token)),
        ("description", s(md.description)),
        ("author", s(md.author)),
        ("version", s(md.version)),
        ("copyright", s(md.copyright)),
        ("license", s(md.license)),
        ("generationTool", s(md.generation_tool)),
        ("generationDateAndTime", generated.map(str::to_string)),
        ("variableNamingConvention", s("flat")),
    ];
    e.open("fmiModelDescription", &root, false);
    interfaces(&mut e, md);
    units(&mut e, md);
    types(&mut e, md);
    e.open("LogCategories", &[], false);
    for c in md.log_categories {
        let attrs = [("name", s(c.name)), ("description", s(c.description))];
        e.open("Category", &attrs, true);
    }
    e.close("LogCategories");
    let x = &md.default_experiment;
    let attrs = [
        ("startTime", Some(fmt_real(x.start_time))),
        ("stopTime", Some(fmt_real(x.stop_time))),
        ("tolerance", Some(fmt_real(x.tolerance))),
        ("stepSize", Some(fmt_real(x.step_size))),
    ];
    e.open("DefaultExperiment", &attrs, true);
    e.open("ModelVariables", &[], false);
    let time = [
        ("name", s(TIME)),
        ("valueReference", Some(md.fmi3_time_vr().to_string())),
        ("description", s("Simulation time")),
        ("causality", s("independent")),
        ("variability", s("continuous")),
        ("unit", md.unit("s").map(|_| "s".to_string())),
    ];
    e.open("Float64", &time, true);
    for v in md.variables {
        variable(&mut e, md, v);
    }
    for i in 0..md.event_indicator_count() {
        let attrs = [
            ("name", Some(format!("eventIndicator{}", i + 1))),
            (
                "valueReference",
                Some(md.fmi3_event_indicator_vr(i).to_string()),
            ),
            (
                "description",
                Some(format!("Event indicator {} (Model Exchange)", i + 1)),
            ),
            ("causality", s("local")),
            ("variability", s("continuous")),
        ];
        e.open("Float64", &attrs, true);
    }
    for (k, (_, x)) in md.fmi3_derivative_inputs().enumerate() {
        let Some((name, _, size)) = naming(md, x) else {
            continue;
        };
        let attrs = [
            ("name", Some(format!("der({name})"))),
            (
                "valueReference",
                Some(md.fmi3_input_derivative_vr(k as u32).to_string()),
            ),
            (
                "description",
                Some(format!(
                    "Co-simulation: first time derivative of {0} (its unit per second); over a step from t, {0} + der({0}) (t' - t) is the input (as fmi2SetRealInputDerivatives of order 1); setting {0} resets it to 0 unless it is set in the same call",
                    name
                )),
            ),
            ("causality", s("input")),
            ("variability", s("continuous")),
            ("start", Some(fmt_real(0.0))),
            ("derivative", Some(x.vr.to_string())),
        ];
        typed(&mut e, "Float64", &attrs, size);
    }
    e.close("ModelVariables");
    structure(&mut e, md);
    e.close("fmiModelDescription");
    e.out
}

/// The FMI 3.0 XML, generated at `generated` (if known), with the 2.0 GUID
/// as its instantiation token.
pub fn model_description_xml(md: &ModelDescription, generated: Option<&str>) -> String {
    render(md, &guid(md), generated)
}

#[cfg(test)]
mod tests {
    use super::escape;

    #[test]
    fn attributes_are_escaped() {
        assert_eq!(escape(r#"a<b & "c">"#), "a&lt;b &amp; &quot;c&quot;&gt;");
    }
}
