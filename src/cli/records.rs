//! The records of `--format json`: every line a command writes, on either
//! stream, is one JSON object whose `type` says what it is (as rustc's
//! `$message_type`), so that a tool reading both streams tells a
//! diagnostic from a command's result or from a file it could not read.
//! The diagnostics' own records (`"type": "diagnostic"`) are written by
//! [`crate::diagnostics::render_json`]; the README lists every type's
//! fields.

use serde::Serialize;
use serde_json::{json, Value};

/// `check`'s listing of the files it read (stdout, after the diagnostics).
pub const FILES: &str = "files";
/// `stats`' figures (stdout).
pub const STATS: &str = "stats";
/// What a mesh `render` wrote holds (stdout).
pub const MESH: &str = "mesh";
/// `translate`'s mapping, and the text when it goes to stdout (stdout).
pub const TRANSLATION: &str = "translation";
/// `list`'s standard library (stdout).
pub const STDLIB: &str = "stdlib";
/// A problem that is not a diagnostic (stderr): a file that cannot be read
/// or written, a picture that cannot be made (exit status 2).
pub const ERROR: &str = "error";

/// `value`, an object, as one line of JSON with its `type` first. The
/// object is written as it serialises, not through a `Value`, so that
/// numbers past `f64` (exact counts, written raw) keep every digit.
pub fn line(kind: &str, value: impl Serialize) -> String {
    let kind_field = format!("\"type\":{}", Value::from(kind));
    // The values written are plain data (no maps keyed by non-strings), so
    // this does not fail; if it ever did, the record still says its type.
    let text = serde_json::to_string(&value)
        .unwrap_or_else(|e| json!({ "message": e.to_string() }).to_string());
    match text.strip_prefix('{') {
        Some("}") => format!("{{{kind_field}}}\n"),
        Some(rest) => format!("{{{kind_field},{rest}\n"),
        None => format!("{{{kind_field},\"value\":{text}}}\n"),
    }
}

/// An [`ERROR`] record: `message`, and `help` (null without).
pub fn error(message: &str, help: Option<&str>) -> String {
    line(ERROR, json!({ "message": message, "help": help }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_record_is_its_object_with_its_type() {
        let v: Value = serde_json::from_str(&line(STATS, json!({ "steps": 2 }))).unwrap();
        assert_eq!(v, json!({ "type": "stats", "steps": 2 }));
        let v: Value = serde_json::from_str(&error("no", None)).unwrap();
        assert_eq!(v, json!({ "type": "error", "message": "no", "help": null }));
        assert_eq!(line(FILES, json!({})), "{\"type\":\"files\"}\n");
        // A number past u64 written raw keeps its digits.
        let big: Box<serde_json::value::RawValue> = serde_json::value::RawValue::from_string(
            "340282366920938463463374607431768211456".into(),
        )
        .unwrap();
        let written = line(STATS, json!({ "steps": 2 }));
        assert_eq!(written, "{\"type\":\"stats\",\"steps\":2}\n");
        #[derive(Serialize)]
        struct Big {
            segments: Box<serde_json::value::RawValue>,
        }
        assert_eq!(
            line(STATS, Big { segments: big }),
            "{\"type\":\"stats\",\"segments\":340282366920938463463374607431768211456}\n"
        );
    }
}
