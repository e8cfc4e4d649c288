//! What the page is sent, as JSON: diagnostics with their places and
//! fixes, and spans, every position in UTF-16 code units (what a
//! browser's strings and CodeMirror count in) rather than bytes.

use crate::diagnostics::{Diagnostic, Severity};
use crate::ir::Span;
use crate::source::SourceFile;
use serde_json::{json, Value};

/// Byte offsets of a text as UTF-16 offsets, and back.
pub struct Positions {
    /// `utf16[b]`: the UTF-16 offset of byte `b` (and of the text's end);
    /// empty for an ASCII text, where they are the same.
    utf16: Vec<u32>,
}

impl Positions {
    pub fn of(text: &str) -> Positions {
        if text.is_ascii() {
            return Positions { utf16: Vec::new() };
        }
        let mut utf16 = Vec::with_capacity(text.len() + 1);
        let mut at = 0u32;
        for c in text.chars() {
            // Every byte of a character maps to where it starts.
            utf16.extend(std::iter::repeat_n(at, c.len_utf8()));
            at += c.len_utf16() as u32;
        }
        utf16.push(at);
        Positions { utf16 }
    }

    /// The UTF-16 offset of byte `b` (clamped to the text).
    pub fn utf16(&self, b: usize) -> usize {
        match self.utf16.last() {
            None => b,
            Some(&end) => self.utf16.get(b).map_or(end, |&u| u) as usize,
        }
    }

    /// The byte offset of UTF-16 offset `u` (the start of the character
    /// it falls in; clamped to the text).
    pub fn byte(&self, u: usize) -> usize {
        if self.utf16.is_empty() {
            return u;
        }
        // The first byte whose UTF-16 offset reaches `u`.
        self.utf16.partition_point(|&x| (x as usize) < u)
    }

    /// `{from, to}` of a byte span.
    pub fn range(&self, span: &Span) -> Value {
        json!({ "from": self.utf16(span.start), "to": self.utf16(span.end) })
    }
}

/// A diagnostic as the page lists it: code, severity, message, place
/// (`from`, `to`, 1-based `line`; 0, 0 and null for one with no place in
/// the text), help, notes, and its fix as edits.
pub fn diagnostic(d: &Diagnostic, file: &SourceFile, at: &Positions) -> Value {
    // A side file's spans point into another text: shown without a place.
    let span = d.span.clone().filter(|_| d.side.is_none());
    let severity = match d.severity {
        Severity::Error => "error",
        Severity::Warning => "warning",
    };
    let fixes: Vec<Value> = (d.fix.iter())
        .filter(|_| d.side.is_none())
        .map(|f| {
            json!({
                "title": fix_title(&f.replacement),
                "edits": [{
                    "from": at.utf16(f.span.start),
                    "to": at.utf16(f.span.end),
                    "insert": f.replacement,
                }],
            })
        })
        .collect();
    let mut notes = d.notes.clone();
    notes.extend(d.labels.iter().map(|l| l.message.clone()));
    json!({
        "code": d.code.0,
        "severity": severity,
        "message": d.message,
        "label": d.label,
        "from": span.as_ref().map_or(0, |s| at.utf16(s.start)),
        "to": span.as_ref().map_or(0, |s| at.utf16(s.end)),
        "line": span.as_ref().map(|s| file.line_index(s.start) + 1),
        "help": d.help.iter().collect::<Vec<_>>(),
        "notes": notes,
        "fixes": fixes,
    })
}

/// What a fix's button says.
fn fix_title(replacement: &str) -> String {
    if replacement.is_empty() {
        return "remove it".to_string();
    }
    let shown = crate::diagnostics::shortened(replacement, 40);
    format!("write `{shown}`")
}

/// Every diagnostic of `diags` as the page lists them.
pub fn diagnostics<'d>(
    diags: impl IntoIterator<Item = &'d Diagnostic>,
    file: &SourceFile,
    at: &Positions,
) -> Vec<Value> {
    diags.into_iter().map(|d| diagnostic(d, file, at)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offsets_count_utf16_units_both_ways() {
        // `é` is 2 bytes and 1 unit, `𝄞` 4 bytes and 2 units.
        let p = Positions::of("aé𝄞b");
        assert_eq!(
            (0..=8).map(|b| p.utf16(b)).collect::<Vec<_>>(),
            [0, 1, 1, 2, 2, 2, 2, 4, 5]
        );
        assert_eq!((p.byte(2), p.byte(4), p.byte(5)), (3, 7, 8));
        let ascii = Positions::of("F+F");
        assert_eq!((ascii.utf16(2), ascii.byte(2)), (2, 2));
    }

    #[test]
    fn a_diagnostic_keeps_its_place_help_and_fix() {
        let file = SourceFile::new("t.l", "é\nF -=> G\n");
        let at = Positions::of(&file.text);
        let code = crate::diagnostics::codes::UNKNOWN_HEADER;
        let d = Diagnostic::at(code, 5..7, "bad arrow").with_fix(
            5..7,
            "-->".into(),
            "write `-->`".into(),
        );
        let v = diagnostic(&d, &file, &at);
        assert_eq!((v["from"].as_u64(), v["to"].as_u64()), (Some(4), Some(6)));
        assert_eq!(v["line"], 2);
        assert_eq!(v["help"][0], "write `-->`");
        assert_eq!(v["fixes"][0]["edits"][0]["insert"], "-->");
        assert_eq!(v["fixes"][0]["edits"][0]["from"], 4);
    }
}
