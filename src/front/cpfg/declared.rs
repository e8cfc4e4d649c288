//! What a cpfg file declares besides its symbols, for the language server:
//! its `#define NAME body` and `#define NAME(args) body` lines (macros and
//! the functions written as macros, with their expansion), and the user
//! function a `func(NAME, x)` or `func(k, x)` calls.

use crate::front::declared::{is_name_char, quoted, word_at};
use crate::front::{Declaration, DeclarationKind};

/// The macros `text` defines, from the lines that define them.
pub fn macros(text: &str) -> Vec<Declaration> {
    let mut out = Vec::new();
    let mut at = 0;
    for line in text.split_inclusive('\n') {
        let start = at;
        at += line.len();
        let trimmed = line.trim_start();
        let Some(rest) = trimmed.strip_prefix('#') else {
            continue;
        };
        let Some(rest) = rest.trim_start().strip_prefix("define") else {
            continue;
        };
        let name_from = line.len() - rest.trim_start().len();
        let name_len = rest.trim_start().find(|c: char| !is_name_char(c));
        let name_len = name_len.unwrap_or(rest.trim_start().len());
        if name_len == 0 || name_from == line.len() - rest.len() {
            continue; // no name, or `#defineX`
        }
        let span = start + name_from..start + name_from + name_len;
        let name = text[span.clone()].to_string();
        let after = &line[name_from + name_len..];
        let (kind, what) = if after.starts_with('(') {
            (DeclarationKind::Function, "function-like macro")
        } else {
            (DeclarationKind::Constant, "macro")
        };
        let definition = quoted(line, &(name_from..line.len()));
        out.push(Declaration {
            about: format!("cpfg {what} `{name}`: expands as `#define {definition}`"),
            name,
            span,
            kind,
        });
    }
    out
}

/// The `NAME` or `k` of the `func(NAME, x)` or `func(k, x)` that `at` is
/// on, outside comments.
pub fn user_function_called_at(text: &str, at: usize) -> Option<&str> {
    let word = word_at(text, at)?;
    let start = text.get(..at)?.rfind(|ch: char| !is_name_char(ch));
    let start = start.map_or(0, |i| i + 1);
    let before = text[..start].trim_end().strip_suffix('(')?.trim_end();
    let called = before.strip_suffix("func")?;
    if called.ends_with(is_name_char) {
        return None; // `myfunc(`
    }
    let comments = super::lexer::comment_spans(text);
    if comments.iter().any(|s| s.start <= start && start < s.end) {
        return None;
    }
    Some(word)
}
