//! The rules every logger message keeps, checked on what the host's [`Log`]
//! of an instance recorded since the driver last looked, and what an error
//! message must name.

use super::*;

/// A log recording every message (`inspect`) or counting them only.
pub(crate) fn new_log(inspect: bool) -> Box<Log> {
    Log::new(if inspect { Keep::All } else { Keep::Count })
}

/// The first broken rule among the messages logged since the counts were
/// `before` (`recent`: those the log recorded): statuses known, OK messages
/// only with debug logging on, and each recorded message's own rules.
pub(crate) fn problem<M: Model>(
    log: &Log,
    before: [u64; 5],
    recent: &[Message],
    name: &[u8],
    debug: bool,
) -> Option<String> {
    if log.unknown_statuses() > 0 {
        return Some("logger called with a status outside fmi2OK..=fmi2Fatal".into());
    }
    if !debug && log.counts()[fmi2OK as usize] > before[fmi2OK as usize] {
        return Some("an fmi2OK message with debug logging off".into());
    }
    recent.iter().find_map(|m| message_problem::<M>(m, name))
}

/// What is wrong with one message: NULL strings, another instance name
/// (`name` as the FMU must pass it back: lossy UTF-8 of ours), a category
/// not declared or not matching the status, an empty or non-UTF-8 text, a
/// `%` conversion left in the format.
fn message_problem<M: Model>(m: &Message, name: &[u8]) -> Option<String> {
    let [Some(instance), Some(category), Some(format)] = &m.raw else {
        return Some("logger called with a NULL string".into());
    };
    let name = String::from_utf8_lossy(name);
    if instance.as_slice() != name.as_bytes() {
        return Some(format!(
            "instance name {:?}, expected {name:?}",
            String::from_utf8_lossy(instance)
        ));
    }
    let Ok(category) = std::str::from_utf8(category) else {
        return Some("category is not UTF-8".into());
    };
    if !M::LOG_CATEGORIES.iter().any(|c| c.name == category) {
        return Some(format!("undeclared category {category:?}"));
    }
    let expected = match m.status {
        fmi2Warning | fmi2Discard => Some("logStatusWarning"),
        fmi2Error | fmi2Fatal => Some("logStatusError"),
        _ => None,
    };
    if expected.is_some_and(|e| category != e) {
        return Some(format!("status {} in category {category}", m.status));
    }
    let Ok(text) = std::str::from_utf8(format) else {
        return Some("message is not UTF-8".into());
    };
    if text.is_empty() {
        return Some("empty message".into());
    }
    lone_percent(text).then(|| format!("a lone % in the format: {text:?}"))
}

/// Whether a printf format has a conversion left: a run of `%` of odd length.
fn lone_percent(text: &str) -> bool {
    let mut run = 0usize;
    for ch in text.chars().chain(std::iter::once('\n')) {
        if ch == '%' {
            run += 1;
        } else if run % 2 == 1 {
            return true;
        } else {
            run = 0;
        }
    }
    false
}

/// Whether one of the `fmi2Error` messages among `recent` names one of
/// `names` as `name = ` (the FMU's way of naming a variable with its value).
pub fn names_one_of(recent: &[Message], names: &[&str]) -> bool {
    recent
        .iter()
        .filter(|m| m.status == fmi2Error)
        .any(|m| names.iter().any(|n| names_variable(&m.text, n)))
}

/// `text` has `name = ` with `name` a whole word (not the end of a longer
/// name: `Ri = ` is not in `hRi = `).
fn names_variable(text: &str, name: &str) -> bool {
    let pattern = format!("{name} = ");
    text.match_indices(&pattern).any(|(i, _)| {
        !text[..i]
            .chars()
            .next_back()
            .is_some_and(|c| c.is_alphanumeric() || c == '_' || c == '(')
    })
}

/// Whether one of the `fmi2Error` messages among `recent` names one of the
/// variables `vrs` (by name, as a whole word) or its value reference.
pub fn names_a_target(recent: &[Message], vrs: &[u32], variables: &[Variable]) -> bool {
    recent.iter().filter(|m| m.status == fmi2Error).any(|m| {
        vrs.iter().any(|&r| {
            m.text.contains(&format!("value reference {r}"))
                || variables
                    .iter()
                    .find(|v| v.vr == r)
                    .is_some_and(|v| has_word(&m.text, v.name))
        })
    })
}

/// `text` has `word` not inside a longer name.
fn has_word(text: &str, word: &str) -> bool {
    let part = |c: Option<char>| c.is_some_and(|c| c.is_alphanumeric() || c == '_');
    text.match_indices(word).any(|(i, _)| {
        !part(text[..i].chars().next_back()) && !part(text[i + word.len()..].chars().next())
    })
}
