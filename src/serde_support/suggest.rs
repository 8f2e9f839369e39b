//! "Did you mean": the error for a `type` that names no message, with the
//! closest names, as command-line parsers suggest a misspelt option.

use alloc::format;
use alloc::string::String;
use alloc::vec::Vec;

/// Lists of at most this many names are spelt out in the error.
const SHORT_LIST: usize = 12;
/// At most this many suggestions.
const MAX_SUGGESTIONS: usize = 3;
/// Longer words get no edit-distance suggestion (and need no stack beyond
/// this).
const MAX_WORD: usize = 48;

/// The error for the unknown type `typed` among `names`: ``unknown type
/// `brake` (did you mean `m1_brake`, `m2_brake` or `base_brake`?)``, and, for
/// a short list, every valid name.
pub(crate) fn unknown_type(typed: &str, names: &[&str]) -> String {
    let mut message = format!("unknown type `{typed}`");
    let close = closest(typed, names);
    if !close.is_empty() {
        message.push_str(" (did you mean ");
        push_list(&mut message, &close, " or ");
        message.push_str("?)");
    }
    if names.len() <= SHORT_LIST {
        message.push_str("; the types are ");
        push_list(&mut message, names, " and ");
    }
    message
}

/// Whether `typed` is close enough to `name` to suggest it (the rule of
/// [`unknown_type`]'s suggestions): a misspelt field name.
pub(crate) fn may_mean(typed: &str, name: &str) -> bool {
    !closest(typed, &[name]).is_empty()
}

/// `names` as `` `a`, `b` or `c` `` (`last` is `" or "` there).
fn push_list(out: &mut String, names: &[&str], last: &str) {
    for (i, name) in names.iter().enumerate() {
        if i > 0 {
            out.push_str(if i + 1 == names.len() { last } else { ", " });
        }
        out.push('`');
        out.push_str(name);
        out.push('`');
    }
}

/// The names `typed` most likely meant: those of which it is a whole
/// `_`-separated part (`brake` in `m1_brake`) or that are one of its
/// (`pong` in `pong_report`), else those nearest by edit
/// distance, if near enough (a third of the word's length, at least 2).
fn closest<'n>(typed: &str, names: &[&'n str]) -> Vec<&'n str> {
    let typed_lower = typed.to_ascii_lowercase();
    let typed = typed_lower.as_str();
    let parts: Vec<&str> = names
        .iter()
        .copied()
        .filter(|name| *name != typed && (is_part(typed, name) || is_part(name, typed)))
        .take(MAX_SUGGESTIONS)
        .collect();
    if !parts.is_empty() || typed.len() > MAX_WORD {
        return parts;
    }
    let limit = (typed.len() / 3).max(2);
    let distances: Vec<(usize, &str)> = names
        .iter()
        .filter_map(|name| edit_distance(typed, name).map(|d| (d, *name)))
        .filter(|&(d, _)| d <= limit)
        .collect();
    let Some(best) = distances.iter().map(|&(d, _)| d).min() else {
        return Vec::new();
    };
    distances
        .into_iter()
        .filter(|&(d, _)| d == best)
        .map(|(_, name)| name)
        .take(MAX_SUGGESTIONS)
        .collect()
}

/// Whether `part` is one or more whole `_`-separated words of `name`.
fn is_part(part: &str, name: &str) -> bool {
    !part.is_empty()
        && name.match_indices(part).any(|(at, _)| {
            let end = at + part.len();
            (at == 0 || name.as_bytes()[at - 1] == b'_')
                && (end == name.len() || name.as_bytes()[end] == b'_')
        })
}

/// Levenshtein distance over bytes; `None` when either word is longer than
/// [`MAX_WORD`].
fn edit_distance(a: &str, b: &str) -> Option<usize> {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    if a.len() > MAX_WORD || b.len() > MAX_WORD {
        return None;
    }
    let mut row = [0usize; MAX_WORD + 1];
    for (j, cell) in row.iter_mut().enumerate().take(b.len() + 1) {
        *cell = j;
    }
    for (i, &ca) in a.iter().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let above = row[j + 1];
            row[j + 1] = (above + 1)
                .min(row[j] + 1)
                .min(diagonal + usize::from(ca != cb));
            diagonal = above;
        }
    }
    Some(row[b.len()])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances() {
        assert_eq!(edit_distance("kitten", "sitting"), Some(3));
        assert_eq!(edit_distance("", "abc"), Some(3));
        assert_eq!(edit_distance("get_blocs", "get_blocks"), Some(1));
        assert_eq!(edit_distance(&"x".repeat(49), "x"), None);
    }

    #[test]
    fn whole_parts() {
        assert!(is_part("brake", "m1_brake"));
        assert!(is_part("m1_brake", "m1_brake"));
        assert!(is_part("set", "set_led"));
        assert!(!is_part("rake", "m1_brake"));
        assert!(!is_part("", "ping"));
    }

    #[test]
    fn suggestions() {
        let names = ["ping", "m1_brake", "m2_brake", "base_brake", "telemetry"];
        assert_eq!(
            closest("brake", &names),
            ["m1_brake", "m2_brake", "base_brake"]
        );
        assert_eq!(
            closest("BRAKE", &names),
            ["m1_brake", "m2_brake", "base_brake"]
        );
        assert_eq!(closest("pnig", &names), ["ping"]);
        assert_eq!(closest("ping_request", &names), ["ping"]);
        assert_eq!(closest("telemtry", &names), ["telemetry"]);
        assert!(closest("zzzzzz", &names).is_empty());
        assert!(closest(&"q".repeat(1000), &names).is_empty());
    }

    #[test]
    fn the_message() {
        let names = ["ping", "m1_brake"];
        assert_eq!(
            unknown_type("brake", &names),
            "unknown type `brake` (did you mean `m1_brake`?); the types are `ping` and `m1_brake`"
        );
        let many = ["a_b"; 13];
        assert_eq!(unknown_type("zzzz", &many), "unknown type `zzzz`");
    }
}
