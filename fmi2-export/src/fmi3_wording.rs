//! The words of a message as a 3.0 host reads them. The layer's calls and
//! checks are written once, in FMI 2.0's names (`fmi2SetReal`, `fmi2OK`,
//! the state `stepComplete`, the type `Real`); the logger of a 3.0 instance
//! passes every message through [`fmi3_words`], so that its host reads
//! `fmi3SetFloat64`, `fmi3OK`, `stepMode`, `Float64`: the functions and
//! items of the standard it loaded the FMU with.

use std::borrow::Cow;

/// 2.0 names whose 3.0 counterpart is not the same name with `fmi3`.
const RENAMED: [(&str, &str); 22] = [
    ("fmi2SetReal", "fmi3SetFloat64"),
    ("fmi2GetReal", "fmi3GetFloat64"),
    ("fmi2SetInteger", "fmi3SetInt32"),
    ("fmi2GetInteger", "fmi3GetInt32"),
    // 3.0 sets an input's derivative as the Float64 variable der(input)
    ("fmi2SetRealInputDerivatives", "fmi3SetFloat64"),
    ("fmi2GetRealOutputDerivatives", "fmi3GetOutputDerivatives"),
    ("fmi2GetDerivatives", "fmi3GetContinuousStateDerivatives"),
    ("fmi2NewDiscreteStates", "fmi3UpdateDiscreteStates"),
    // 3.0 passes the tolerance and the start and stop times there
    ("fmi2SetupExperiment", "fmi3EnterInitializationMode"),
    ("fmi2GetFMUstate", "fmi3GetFMUState"),
    ("fmi2SetFMUstate", "fmi3SetFMUState"),
    ("fmi2FreeFMUstate", "fmi3FreeFMUState"),
    ("fmi2SerializedFMUstateSize", "fmi3SerializedFMUStateSize"),
    ("fmi2SerializeFMUstate", "fmi3SerializeFMUState"),
    ("fmi2DeSerializeFMUstate", "fmi3DeserializeFMUState"),
    ("fmi2Component", "fmi3Instance"),
    // what fmi2GetBooleanStatus and fmi2GetRealStatus report, fmi3DoStep's
    // output arguments in 3.0
    ("fmi2Terminated", "terminateSimulation"),
    ("fmi2LastSuccessfulTime", "lastSuccessfulTime"),
    ("fmi2Real", "fmi3Float64"),
    ("fmi2Integer", "fmi3Int32"),
    // the base types and the state machine's states, as words
    ("Real", "Float64"),
    ("Integer", "Int32"),
];

/// States of the 2.0 machine under their 3.0 names (FMI 3.0, the
/// co-simulation state machine).
const STATES: [(&str, &str); 1] = [("stepComplete", "stepMode")];

/// One word (a run of ASCII letters and digits) as a 3.0 host reads it.
fn word(w: &str) -> Cow<'_, str> {
    if let Some(&(_, to)) = RENAMED.iter().chain(&STATES).find(|(from, _)| *from == w) {
        return Cow::Borrowed(to);
    }
    match w.strip_prefix("fmi2") {
        Some(rest) => Cow::Owned(format!("fmi3{rest}")),
        None => Cow::Borrowed(w),
    }
}

/// `message` with every 2.0 function, type, status and state named as FMI
/// 3.0 names it.
pub fn fmi3_words(message: &str) -> String {
    let mut out = String::with_capacity(message.len() + 16);
    let mut rest = message;
    while !rest.is_empty() {
        let alnum = |c: char| c.is_ascii_alphanumeric();
        let end = rest
            .find(|c: char| alnum(c) != rest.starts_with(alnum))
            .unwrap_or(rest.len());
        let (run, tail) = rest.split_at(end);
        if run.starts_with(alnum) {
            out.push_str(&word(run));
        } else {
            out.push_str(run);
        }
        rest = tail;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn functions_types_and_states_take_their_3_0_names() {
        assert_eq!(
            fmi3_words("fmi2SetReal: B = 0.6"),
            "fmi3SetFloat64: B = 0.6"
        );
        assert_eq!(
            fmi3_words(
                "fmi2DoStep: not allowed in state stepComplete (only in initializationMode)"
            ),
            "fmi3DoStep: not allowed in state stepMode (only in initializationMode)"
        );
        assert_eq!(
            fmi3_words("unknown Real value reference 7; fmi2Error, fmi2GetFMUstate"),
            "unknown Float64 value reference 7; fmi3Error, fmi3GetFMUState"
        );
        assert_eq!(
            fmi3_words("the simulation ends at t = 0.5 (fmi2Terminated is true)"),
            "the simulation ends at t = 0.5 (terminateSimulation is true)"
        );
        // only whole words: a longer name or one within a word stays
        assert_eq!(
            fmi3_words("RealOutput myfmi2SetReal 3.5e-2"),
            "RealOutput myfmi2SetReal 3.5e-2"
        );
        assert_eq!(fmi3_words(""), "");
        assert_eq!(fmi3_words("100 %, é: Real."), "100 %, é: Float64.");
    }

    /// Every FMI 2.0 name in the layer's and the models' sources that a
    /// message could carry becomes a name the 3.0 layer exports, or a 3.0
    /// type, status or item: a function renamed in 3.0 and missing from
    /// [`RENAMED`] fails here.
    #[test]
    fn every_2_0_function_in_the_sources_maps_to_an_exported_3_0_one() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let read_dir = |d: &str| -> String {
            let mut text = String::new();
            for e in std::fs::read_dir(root.join(d)).unwrap() {
                let p = e.unwrap().path();
                if p.extension().is_some_and(|x| x == "rs") {
                    text.push_str(&std::fs::read_to_string(p).unwrap());
                }
            }
            text
        };
        let sources = ["fmi2-export/src", "fmu-rocking/src", "fmu-shear-frame/src"]
            .map(read_dir)
            .concat();
        let exported = read_dir("fmi3-export/src");
        let exported: std::collections::HashSet<&str> = exported
            .split(|c: char| !c.is_ascii_alphanumeric())
            .collect();
        // functions of 2.0 that 3.0 dropped: never reached by a 3.0 call
        let dropped = [
            "fmi2CancelStep",
            "fmi2GetStatus",
            "fmi2GetRealStatus",
            "fmi2GetIntegerStatus",
            "fmi2GetBooleanStatus",
            "fmi2GetStringStatus",
            "fmi2GetTypesPlatform",
            "fmi2GetDirectionalDerivative",
            "fmi2Instantiate",
            // the status kinds of fmi2GetStatus
            "fmi2Terminated",
            "fmi2DoStepStatus",
        ];
        let mut names: Vec<&str> = sources
            .split(|c: char| !c.is_ascii_alphanumeric())
            .filter(|w| {
                w.starts_with("fmi2") && w[4..].starts_with(|c: char| c.is_ascii_uppercase())
            })
            .collect();
        names.sort_unstable();
        names.dedup();
        let functions = names.iter().filter(|n| {
            // a function is a verb: Get..., Set..., Enter..., Do..., ...
            let verbs = [
                "Get",
                "Set",
                "Enter",
                "Exit",
                "Do",
                "Free",
                "Reset",
                "Terminate",
                "New",
                "Completed",
                "Serialize",
                "DeSerialize",
                "Serialized",
                "Instantiate",
                "Cancel",
            ];
            let verb = |v: &&str| n[4..].starts_with(*v) && n.len() > 4 + v.len();
            verbs.iter().any(verb) && !dropped.contains(n)
        });
        let mut checked = 0;
        for n in functions {
            let to = fmi3_words(n);
            assert!(
                exported.contains(to.as_str()),
                "{n} -> {to}: fmi3-export exports no {to}"
            );
            checked += 1;
        }
        assert!(checked >= 30, "{checked} functions checked");
    }
}
