//! `documentation/index.html`: the model's own introduction followed by
//! tables generated from the same [`ModelDescription`] as the XML.

use std::fmt::Write;

use crate::schema::*;
use crate::xml::fmt_real;

/// Escapes text for HTML.
pub fn escape(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => o.push_str("&amp;"),
            '<' => o.push_str("&lt;"),
            '>' => o.push_str("&gt;"),
            '"' => o.push_str("&quot;"),
            '\'' => o.push_str("&#39;"),
            c => o.push(c),
        }
    }
    o
}

fn start(v: &Variable, md: &ModelDescription) -> String {
    match v.ty {
        Type::Real { start, .. } => start.map(fmt_real).unwrap_or_default(),
        Type::Integer { start } => start.map(|s| s.to_string()).unwrap_or_default(),
        Type::Boolean { start } => start.map(|s| s.to_string()).unwrap_or_default(),
        Type::Enumeration {
            declared_type,
            start,
        } => start
            .map(|s| {
                let name = md
                    .enum_type(declared_type)
                    .and_then(|t| t.item(s))
                    .map_or("?", |i| i.name);
                format!("{s} ({name})")
            })
            .unwrap_or_default(),
        Type::String { start } => start.unwrap_or_default().to_string(),
    }
}

fn type_name(v: &Variable) -> String {
    match v.ty {
        Type::Enumeration { declared_type, .. } => format!("Enumeration {declared_type}"),
        t => t.element().to_string(),
    }
}

fn unit_cell(v: &Variable) -> String {
    match v.ty {
        Type::Real {
            unit: Some(u),
            display_unit,
            ..
        } => match display_unit {
            Some(d) => format!("{u} (display {d})"),
            None => u.to_string(),
        },
        _ => String::new(),
    }
}

/// The variable table alone (an HTML `<table>`).
pub fn variable_table(md: &ModelDescription) -> String {
    let mut h = String::new();
    h.push_str("<table>\n<thead><tr><th>name</th><th>value reference</th><th>causality</th><th>variability</th><th>initial</th><th>type</th><th>unit</th><th>start</th><th>description</th></tr></thead>\n<tbody>\n");
    for v in md.variables {
        let _ = writeln!(
            h,
            "<tr id=\"{n}\"><td><code>{n}</code></td><td>{vr}</td><td>{c}</td><td>{va}</td><td>{i}</td><td>{t}</td><td>{u}</td><td>{s}</td><td>{d}</td></tr>",
            n = escape(v.name),
            vr = v.vr,
            c = v.causality.as_str(),
            va = v.variability.as_str(),
            i = v.initial.map_or("", Initial::as_str),
            t = escape(&type_name(v)),
            u = escape(&unit_cell(v)),
            s = escape(&start(v, md)),
            d = escape(v.description),
        );
    }
    h.push_str("</tbody>\n</table>\n");
    h
}

/// The whole page.
pub fn index_html(md: &ModelDescription, guid: &str) -> String {
    let mut h = String::new();
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{name}</title>\n<style>\nbody {{ font-family: sans-serif; max-width: 72em; margin: 2em auto; line-height: 1.4; }}\ntable {{ border-collapse: collapse; margin: 1em 0; }}\nth, td {{ border: 1px solid #bbb; padding: 0.2em 0.5em; text-align: left; vertical-align: top; }}\nth {{ background: #eee; }}\ncode {{ background: #f4f4f4; }}\n</style>\n</head>\n<body>\n<h1>{name}</h1>\n<p>{desc}</p>\n<p>FMI 2.0 co-simulation, model identifier <code>{id}</code>, version {ver}, GUID <code>{guid}</code>.</p>\n",
        name = escape(md.model_name),
        desc = escape(md.description),
        id = escape(md.co_simulation.model_identifier),
        ver = escape(md.version),
        guid = escape(guid),
    );
    h.push_str(md.documentation);
    h.push_str("\n<h2>Variables</h2>\n");
    h.push_str(&variable_table(md));

    h.push_str("<h2>Enumerations</h2>\n");
    for t in md.types {
        let _ = writeln!(
            h,
            "<h3><code>{}</code>: {}</h3>\n<table>\n<thead><tr><th>value</th><th>name</th><th>description</th></tr></thead>\n<tbody>",
            escape(t.name),
            escape(t.description)
        );
        for i in t.items {
            let _ = writeln!(
                h,
                "<tr><td>{}</td><td><code>{}</code></td><td>{}</td></tr>",
                i.value,
                escape(i.name),
                escape(i.description)
            );
        }
        h.push_str("</tbody>\n</table>\n");
    }

    h.push_str("<h2>Units</h2>\n<table>\n<thead><tr><th>unit</th><th>display units (display = factor &times; value)</th></tr></thead>\n<tbody>\n");
    for u in md.units {
        let d: Vec<String> = u
            .display
            .iter()
            .map(|d| format!("{} (factor {})", escape(d.name), fmt_real(d.factor)))
            .collect();
        let _ = writeln!(
            h,
            "<tr><td><code>{}</code></td><td>{}</td></tr>",
            escape(u.name),
            d.join(", ")
        );
    }
    h.push_str("</tbody>\n</table>\n");

    h.push_str("<h2>Log categories</h2>\n<p>Messages with status fmi2Warning, fmi2Discard, fmi2Error or fmi2Fatal always reach the logger; the others only with debug logging on (<code>fmi2SetDebugLogging</code>, no categories meaning all).</p>\n<ul>\n");
    for c in md.log_categories {
        let _ = writeln!(
            h,
            "<li><code>{}</code>: {}</li>",
            escape(c.name),
            escape(c.description)
        );
    }
    h.push_str("</ul>\n");

    let cs = &md.co_simulation;
    let de = &md.default_experiment;
    let _ = write!(
        h,
        "<h2>Capabilities</h2>\n<ul>\n<li>canHandleVariableCommunicationStepSize: {}</li>\n<li>canInterpolateInputs: {}</li>\n<li>maxOutputDerivativeOrder: {}</li>\n<li>canGetAndSetFMUstate: {}</li>\n<li>canSerializeFMUstate: {}</li>\n<li>canBeInstantiatedOnlyOncePerProcess: {}</li>\n<li>canNotUseMemoryManagementFunctions: {}</li>\n<li>needsExecutionTool: {}</li>\n</ul>\n<h2>Default experiment</h2>\n<p>start {} s, stop {} s, relative tolerance {}, step {} s.</p>\n</body>\n</html>\n",
        cs.can_handle_variable_communication_step_size,
        cs.can_interpolate_inputs,
        cs.max_output_derivative_order,
        cs.can_get_and_set_fmu_state,
        cs.can_serialize_fmu_state,
        cs.can_be_instantiated_only_once_per_process,
        cs.can_not_use_memory_management_functions,
        cs.needs_execution_tool,
        fmt_real(de.start_time),
        fmt_real(de.stop_time),
        fmt_real(de.tolerance),
        fmt_real(de.step_size),
    );
    h
}
