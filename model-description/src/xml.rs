//! `modelDescription.xml` (FMI 2.0) from a [`ModelDescription`], through
//! serde and quick-xml. Element and attribute order follow the FMI 2.0 XSD.

mod document;

use document::*;
use serde::Serialize;
use sha2::{Digest, Sha256};

use crate::schema::*;

/// Formats a real as an `xs:double`: shortest round-trip representation,
/// with an exponent for very large or small magnitudes.
pub fn fmt_real(x: f64) -> String {
    if x.is_nan() {
        "NaN".into()
    } else if x.is_infinite() {
        if x > 0.0 { "INF" } else { "-INF" }.into()
    } else if x == 0.0 || (1e-4..1e7).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

fn flag(b: bool) -> Option<&'static str> {
    b.then_some("true")
}

fn tf(b: bool) -> &'static str {
    if b {
        "true"
    } else {
        "false"
    }
}

fn nz(x: i32) -> Option<i32> {
    (x != 0).then_some(x)
}

fn unit(u: &Unit) -> XUnit {
    let b = &u.base;
    XUnit {
        name: u.name,
        base: XBaseUnit {
            kg: nz(b.kg),
            m: nz(b.m),
            s: nz(b.s),
            a: nz(b.ampere),
            k: nz(b.kelvin),
            mol: nz(b.mol),
            cd: nz(b.cd),
            rad: nz(b.rad),
            factor: (b.factor != 1.0).then(|| fmt_real(b.factor)),
            offset: (b.offset != 0.0).then(|| fmt_real(b.offset)),
        },
        display: u
            .display
            .iter()
            .map(|d| XDisplayUnit {
                name: d.name,
                factor: fmt_real(d.factor),
                offset: (d.offset != 0.0).then(|| fmt_real(d.offset)),
            })
            .collect(),
    }
}

fn variable(md: &ModelDescription, v: &Variable) -> XScalarVariable {
    let ty = match v.ty {
        Type::Real {
            unit,
            display_unit,
            start,
            min,
            max,
        } => XType::Real(XReal {
            unit,
            display_unit,
            min: min.map(fmt_real),
            max: max.map(fmt_real),
            start: start.map(fmt_real),
            derivative: v
                .derivative
                .map(|x| md.index_of(x).expect("derivatives are checked")),
        }),
        Type::Integer { start } => XType::Integer(XStart {
            start: start.map(|s| s.to_string()),
        }),
        Type::Boolean { start } => XType::Boolean(XStart {
            start: start.map(|s| s.to_string()),
        }),
        Type::Enumeration {
            declared_type,
            start,
        } => XType::Enumeration(XEnum {
            declared_type,
            start: start.map(|s| s.to_string()),
        }),
        Type::String { start } => XType::String(XStart {
            start: start.map(|s| s.to_string()),
        }),
    };
    XScalarVariable {
        name: v.name,
        vr: v.vr,
        description: v.description,
        causality: v.causality.as_str(),
        variability: v.variability.as_str(),
        initial: v.initial.map(Initial::as_str),
        ty,
    }
}

fn indices<'a>(md: &ModelDescription, names: impl Iterator<Item = &'a str>) -> String {
    let mut ix: Vec<usize> = names
        .map(|n| md.index_of(n).expect("dependency names are checked"))
        .collect();
    ix.sort_unstable();
    ix.dedup();
    ix.iter()
        .map(|i| i.to_string())
        .collect::<Vec<_>>()
        .join(" ")
}

fn structure(md: &ModelDescription) -> XStructure {
    let mut outputs = Vec::new();
    let mut initial = Vec::new();
    let mut derivatives = Vec::new();
    // the knowns of Model Exchange: inputs and continuous states
    let is_known = |d: &&str| {
        md.variable(d).is_some_and(|k| {
            k.causality == Causality::Input
                || md.variables.iter().any(|x| x.derivative == Some(k.name))
        })
    };
    for (i, v) in md.variables.iter().enumerate() {
        if v.derivative.is_some() {
            derivatives.push(XUnknown {
                index: i + 1,
                dependencies: indices(md, v.run_dependencies().iter().copied().filter(is_known)),
            });
        }
        if v.causality == Causality::Output {
            let inputs = v.run_dependencies().iter().copied().filter(|d| {
                md.variable(d)
                    .is_some_and(|k| k.causality == Causality::Input)
            });
            outputs.push(XUnknown {
                index: i + 1,
                dependencies: indices(md, inputs),
            });
        }
        if v.is_initial_unknown() {
            initial.push(XUnknown {
                index: i + 1,
                dependencies: indices(md, v.depends_on.iter().copied()),
            });
        }
    }
    XStructure {
        outputs: XUnknowns { unknowns: outputs },
        derivatives: (!derivatives.is_empty()).then_some(XUnknowns {
            unknowns: derivatives,
        }),
        initial_unknowns: XUnknowns { unknowns: initial },
    }
}

/// The XML with the given `guid` attribute and, if given, the
/// `generationDateAndTime` attribute (`xs:dateTime`).
pub fn render(md: &ModelDescription, guid: &str, generated: Option<&str>) -> String {
    if let Err(problems) = md.check() {
        panic!("inconsistent model description:\n{}", problems.join("\n"));
    }
    let cs = &md.co_simulation;
    let root = Root {
        fmi_version: "2.0",
        model_name: md.model_name,
        guid: guid.to_string(),
        description: md.description,
        author: md.author,
        version: md.version,
        copyright: md.copyright,
        license: md.license,
        generation_tool: md.generation_tool,
        generation_date_and_time: generated.map(str::to_string),
        naming: "flat",
        event_indicators: md.model_exchange.map_or(0, |me| me.event_indicators),
        model_exchange: md.model_exchange.map(|me| XModelExchange {
            model_identifier: me.model_identifier,
            needs_execution_tool: tf(me.needs_execution_tool),
            completed_step_not_needed: tf(me.completed_integrator_step_not_needed),
            only_once: tf(me.can_be_instantiated_only_once_per_process),
            no_memory_management: flag(me.can_not_use_memory_management_functions),
            get_set_state: flag(me.can_get_and_set_fmu_state),
            serialize_state: flag(me.can_serialize_fmu_state),
            directional_derivative: flag(me.provides_directional_derivative),
        }),
        co_simulation: XCoSimulation {
            model_identifier: cs.model_identifier,
            needs_execution_tool: if cs.needs_execution_tool {
                "true"
            } else {
                "false"
            },
            variable_step: flag(cs.can_handle_variable_communication_step_size),
            interpolate_inputs: flag(cs.can_interpolate_inputs),
            max_output_derivative_order: (cs.max_output_derivative_order > 0)
                .then_some(cs.max_output_derivative_order),
            asynchronuously: flag(cs.can_run_asynchronuously),
            only_once: if cs.can_be_instantiated_only_once_per_process {
                "true"
            } else {
                "false"
            },
            no_memory_management: flag(cs.can_not_use_memory_management_functions),
            get_set_state: flag(cs.can_get_and_set_fmu_state),
            serialize_state: flag(cs.can_serialize_fmu_state),
            directional_derivative: flag(cs.provides_directional_derivative),
        },
        units: XUnits {
            units: md.units.iter().map(unit).collect(),
        },
        types: XTypes {
            types: md
                .types
                .iter()
                .map(|t| XSimpleType {
                    name: t.name,
                    description: t.description,
                    enumeration: XEnumeration {
                        items: t
                            .items
                            .iter()
                            .map(|i| XItem {
                                name: i.name,
                                value: i.value,
                                description: i.description,
                            })
                            .collect(),
                    },
                })
                .collect(),
        },
        log_categories: XLogCategories {
            categories: md
                .log_categories
                .iter()
                .map(|c| XCategory {
                    name: c.name,
                    description: c.description,
                })
                .collect(),
        },
        default_experiment: XDefaultExperiment {
            start_time: fmt_real(md.default_experiment.start_time),
            stop_time: fmt_real(md.default_experiment.stop_time),
            tolerance: fmt_real(md.default_experiment.tolerance),
            step_size: fmt_real(md.default_experiment.step_size),
        },
        variables: XVariables {
            variables: md.variables.iter().map(|v| variable(md, v)).collect(),
        },
        structure: structure(md),
    };
    let mut body = String::new();
    let mut ser = quick_xml::se::Serializer::new(&mut body);
    ser.indent(' ', 2);
    root.serialize(ser)
        .expect("the model description serializes");
    format!("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n{body}\n")
}

/// The GUID of a model description: derived from its XML without the GUID
/// and the generation time, so it changes exactly when the description does.
pub fn guid(md: &ModelDescription) -> String {
    guid_of(render(md, "", None).as_bytes())
}

/// A GUID `{xxxxxxxx-xxxx-8xxx-yxxx-xxxxxxxxxxxx}` from the first 16 bytes
/// of the SHA-256 of `content` (RFC 9562 version 8, "custom").
pub fn guid_of(content: &[u8]) -> String {
    let d = Sha256::digest(content);
    let mut b = [0u8; 16];
    b.copy_from_slice(&d[..16]);
    b[6] = (b[6] & 0x0f) | 0x80;
    b[8] = (b[8] & 0x3f) | 0x80;
    let hex: String = b.iter().map(|x| format!("{x:02x}")).collect();
    format!(
        "{{{}-{}-{}-{}-{}}}",
        &hex[0..8],
        &hex[8..12],
        &hex[12..16],
        &hex[16..20],
        &hex[20..32]
    )
}

/// The XML, generated at `generated` (`xs:dateTime`, if known), and its GUID.
pub fn model_description_xml(md: &ModelDescription, generated: Option<&str>) -> (String, String) {
    let g = guid(md);
    (render(md, &g, generated), g)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reals() {
        assert_eq!(fmt_real(5e9), "5e9");
        assert_eq!(fmt_real(0.5), "0.5");
        assert_eq!(fmt_real(1e-6), "1e-6");
        assert_eq!(fmt_real(1800.0), "1800");
        assert_eq!(fmt_real(0.0), "0");
        assert_eq!(fmt_real(-2.5e-9), "-2.5e-9");
    }

    /// SHA-256("abc") is FIPS 180-2's published example
    /// ba7816bf 8f01cfea 414140de 5dae2223 b00361a3 ...: its first 16 bytes
    /// with the version nibble (byte 6: 0xcf -> 0x8f) and the variant bits
    /// (byte 8: 0x41 -> 0x81) of RFC 9562 set.
    #[test]
    fn guid_is_the_version_8_form_of_the_sha256() {
        assert_eq!(guid_of(b"abc"), "{ba7816bf-8f01-8fea-8141-40de5dae2223}");
    }
}
