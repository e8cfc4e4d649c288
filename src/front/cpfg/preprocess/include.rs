//! `#include "file"`: the included text is preprocessed in place, and
//! its diagnostics say where it was included from.

use super::output::Out;
use super::tokens::{strip_ws, Tok};
use super::{Included, Pp, SourceMap, MAX_INCLUDE_DEPTH};
use crate::diagnostics::{codes, Diagnostic, SideFile};
use std::ops::Range;
use std::rc::Rc;
use std::sync::Arc;

impl Pp<'_> {
    pub(super) fn include_directive(
        &mut self,
        rest: Vec<Tok>,
        line_span: Range<usize>,
        out: &mut Out,
    ) {
        let words = strip_ws(rest);
        let (file, file_span, after) = match words.first() {
            Some(t) if t.text.starts_with('"') && t.text.len() >= 2 && t.text.ends_with('"') => {
                (t.text[1..t.text.len() - 1].to_string(), t.origin.clone(), 1)
            }
            Some(t) if &*t.text == "<" => match words.iter().position(|x| &*x.text == ">") {
                Some(k) if k > 1 => {
                    let name: String = words[1..k].iter().map(|x| &*x.text).collect();
                    (name, t.origin.start..words[k].origin.end, k + 1)
                }
                _ => {
                    self.bad_directive(line_span, "`#include` needs a file name".to_string());
                    return;
                }
            },
            _ => {
                self.bad_directive(
                    line_span,
                    "`#include` needs a file name in quotes".to_string(),
                );
                return;
            }
        };
        self.extra_tokens(&words[after..], "include");
        if self.stack.len() >= MAX_INCLUDE_DEPTH || self.stack.contains(&file) {
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_RECURSIVE_INCLUDE,
                    file_span,
                    if self.stack.contains(&file) {
                        format!("`{file}` includes itself")
                    } else {
                        format!("includes nested more than {MAX_INCLUDE_DEPTH} deep")
                    },
                )
                .with_label("not included again")
                .with_note(format!("include chain: {}", self.stack.join(" -> "))),
            );
            return;
        }
        let Some(text) = (self.include)(&file) else {
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_MISSING_INCLUDE,
                    file_span,
                    format!("cannot read included file `{file}`"),
                )
                .with_label("no such file beside the L-system file")
                .with_help("check the name; included files are looked for in the object's folder"),
            );
            return;
        };
        let note = self.included_note(&file, &line_span);
        let side = Arc::new(SideFile {
            name: file.clone(),
            text: text.clone(),
        });
        self.stack.push(file);
        self.texts.push(Rc::from(text.as_str()));
        let saved = std::mem::take(&mut self.diags);
        let mut sub = Out::default();
        self.run(&text, &mut sub, false);
        let inner = std::mem::replace(&mut self.diags, saved);
        self.texts.pop();
        self.stack.pop();
        // Diagnostics inside the included file are shown there, with a
        // note at the `#include` (those of a file it includes already are).
        for d in inner.0 {
            let mut d = match d.side {
                Some(_) => d,
                None => d.in_side_file(side.clone()),
            };
            d.notes.push(note.clone());
            self.diags.push(d);
        }
        // The included text (with its own line breaks) maps to the directive.
        let mut t = sub.text;
        if !t.ends_with('\n') && !t.is_empty() {
            t.push('\n');
        }
        let start = out.text.len();
        if !out.push_seg(&t, line_span, false) {
            out.full = true;
            return;
        }
        out.included.push(Included {
            file: side,
            out: start..out.text.len(),
            map: SourceMap {
                segs: sub.segs,
                src_len: text.len(),
                included: sub.included,
            },
            note,
        });
    }

    /// "`file` is included at line N of …": where the `#include` at `at`
    /// of the file being read stands.
    fn included_note(&self, file: &str, at: &Range<usize>) -> String {
        let including = self.texts.last().map_or("", |t| t);
        let before = including.get(..at.start).unwrap_or(including);
        let line = 1 + before.bytes().filter(|&c| c == b'\n').count();
        match self.stack.last() {
            Some(parent) => format!("`{file}` is included at line {line} of `{parent}`"),
            None => format!("`{file}` is included at line {line} of the L-system file"),
        }
    }
}
