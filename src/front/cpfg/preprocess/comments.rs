//! Comments become spaces before anything else is read, their line
//! breaks kept, so lines and columns stay put.

use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use std::ops::Range;

/// The text with comments replaced by spaces (line breaks kept), byte for
/// byte, and whether each line break lies inside a comment.
pub(super) fn strip_comments(text: &str, diags: &mut Diagnostics) -> (String, Vec<bool>) {
    let b = text.as_bytes();
    let mut out = b.to_vec();
    let mut nl_in_comment = vec![false; b.len()];
    let mut i = 0;
    let blank = |out: &mut Vec<u8>, nl: &mut Vec<bool>, r: Range<usize>| {
        for j in r {
            if b[j] == b'\n' {
                nl[j] = true;
            } else if b[j] != b'\r' {
                out[j] = b' ';
            }
        }
    };
    while i < b.len() {
        match b[i] {
            b'"' => {
                i += 1;
                while i < b.len() && b[i] != b'"' && b[i] != b'\n' {
                    i += if b[i] == b'\\' && i + 1 < b.len() && b[i + 1] != b'\n' {
                        2
                    } else {
                        1
                    };
                }
                i += 1;
            }
            b'/' if b.get(i + 1) == Some(&b'*') => {
                let start = i;
                let end = text[i + 2..].find("*/").map(|k| i + 2 + k + 2);
                match end {
                    Some(e) => {
                        blank(&mut out, &mut nl_in_comment, start..e);
                        i = e;
                    }
                    None => {
                        diags.push(
                            Diagnostic::at(
                                codes::CPFG_UNTERMINATED_COMMENT,
                                start..start + 2,
                                "comment never closed",
                            )
                            .with_label("this comment runs to the end of the file")
                            .with_help("close it with `*/`"),
                        );
                        blank(&mut out, &mut nl_in_comment, start..b.len());
                        // A line break of an unclosed comment still ends lines.
                        nl_in_comment.iter_mut().for_each(|x| *x = false);
                        i = b.len();
                    }
                }
            }
            b'/' if b.get(i + 1) == Some(&b'/') => {
                let start = i;
                if let Some(d) = rolls_read_as_comment(text, start) {
                    diags.push(d);
                }
                while i < b.len() && b[i] != b'\n' {
                    i += 1;
                }
                blank(&mut out, &mut nl_in_comment, start..i);
            }
            _ => i += 1,
        }
    }
    // Only ASCII bytes were replaced by ASCII spaces, and every byte of a
    // multi-byte character inside a comment was replaced: still UTF-8.
    let s = String::from_utf8(out)
        .unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned());
    (s, nl_in_comment)
}

/// A warning when the `//` at `start` ends a module of an axiom or a
/// successor: cpfg's preprocessor reads it as a comment, so `E///T(0)FA`
/// is the axiom `E`, where `/` rolls were meant. A `//` after a space is
/// taken for the comment it usually is.
fn rolls_read_as_comment(text: &str, start: usize) -> Option<Diagnostic> {
    let line_start = text[..start].rfind('\n').map_or(0, |k| k + 1);
    let before = &text[line_start..start];
    let last = before.chars().next_back()?;
    if last.is_whitespace() || last == '>' || !is_word_line(before) {
        return None;
    }
    let slashes = text[start..].bytes().take_while(|&c| c == b'/').count();
    let spaced = vec!["/"; slashes].join(" ");
    Some(
        Diagnostic::at(
            codes::CPFG_SLASHES_COMMENT,
            start..start + slashes,
            "`//` starts a comment here",
        )
        .with_label("the rest of the line is not read")
        .with_note("cpfg runs the C preprocessor over the file, which removes `//` comments")
        .with_fix(
            start..start + slashes,
            spaced.clone(),
            format!("write `{spaced}` for {slashes} rolls"),
        ),
    )
}

/// Whether the text of a line up to a `//` is an axiom or a production
/// whose successor has begun.
fn is_word_line(before: &str) -> bool {
    let head = before.trim_start().to_ascii_lowercase();
    let axiom = head
        .strip_prefix("axiom")
        .is_some_and(|r| r.trim_start().starts_with(':'));
    axiom || before.contains("-->") || before.contains("->")
}

// ---------------------------------------------------------------------------
// Output
