//! Lowering a `.gft` syntax tree to the IR (docs/gft.md): declarations
//! first (the turtle set, `NAME = OPERATION`, `symbol`, `silent`,
//! rotations), so that words split by the longest declared name; then
//! settings, the program, the axiom and the productions; a `graph` block
//! is lowered on its own (`graph`).

mod declarations;
mod environment;
mod graph;
mod items;
mod keywords;
mod program;
mod structure;
mod words;

use super::ast::{Arg, File, Item};
use crate::common::vocabulary::TurtleSet;
use crate::diagnostics::{codes, Code, Diagnostic, Diagnostics};
use crate::front::suggest::Suggester;
use crate::ir::{Lowered, Span, SpanTable, System};
use std::collections::HashMap;

struct Cx<'d> {
    sys: System,
    spans: SpanTable,
    diags: &'d mut Diagnostics,
    set: TurtleSet,
    /// Names longer than one character that words may contain.
    names: WordNames,
    settings: HashMap<String, Span>,
    globals: HashMap<String, u16>,
    arrays: HashMap<String, (u16, usize)>,
    /// The file's budget for "did you mean …?".
    suggester: Suggester,
    /// The folder texture images are read from (the `.gft` file's); none
    /// for a text read without a file.
    folder: Option<&'d std::path::Path>,
}

/// The names words may contain, found by length: a file that declares
/// ten thousand names splits its words without trying each name at each
/// character.
#[derive(Default)]
struct WordNames {
    names: std::collections::HashSet<String>,
    /// The lengths (bytes) of `names`, longest first.
    lengths: Vec<usize>,
}

impl WordNames {
    fn add(&mut self, name: &str) {
        if self.names.insert(name.to_string()) && !self.lengths.contains(&name.len()) {
            self.lengths.push(name.len());
            self.lengths.sort_unstable_by(|a, b| b.cmp(a));
        }
    }

    /// The length of the longest name `text` starts with; 0 for none.
    fn longest_prefix(&self, text: &str) -> usize {
        (self.lengths.iter().copied())
            .find(|&n| text.get(..n).is_some_and(|p| self.names.contains(p)))
            .unwrap_or(0)
    }
}

/// Lowers a parsed file; the system is usable only when `diags` got no error.
pub fn lower(file: &File, diags: &mut Diagnostics) -> Lowered {
    lower_in(file, None, diags)
}

/// [`lower`] for a file of the folder `folder`, which its `texture` lines
/// name image files in (docs/gft.md §9).
pub fn lower_in(file: &File, folder: Option<&std::path::Path>, diags: &mut Diagnostics) -> Lowered {
    let mut cx = Cx {
        folder,
        sys: System::new(),
        spans: SpanTable::default(),
        diags,
        set: TurtleSet::Pfg,
        names: WordNames::default(),
        settings: HashMap::new(),
        globals: HashMap::new(),
        arrays: HashMap::new(),
        suggester: Suggester::default(),
    };
    let keyword = |name: &'static str| {
        file.items.iter().filter_map(move |i| match i {
            Item::Keyword(k) if k.name == name => Some(k),
            _ => None,
        })
    };
    if let Some(k) = keyword("turtle").next() {
        cx.turtle(k);
    }
    // Without a `turtle` line the set is pfg's (docs/gft.md §3).
    cx.give_set();
    for k in keyword("rotation") {
        cx.rotation(k);
    }
    // Surfaces before the operations that name them.
    for k in keyword("surface") {
        cx.surface(k);
    }
    for item in &file.items {
        match item {
            Item::Define {
                name,
                span,
                op,
                op_span,
            } => cx.define(name, span, op, op_span),
            Item::Keyword(k) if k.name == "silent" => cx.silent(k),
            Item::Keyword(k) if k.name == "array" => cx.array(k),
            Item::Keyword(k) if k.name == "globals" => {
                // `globals a, b`: a comma joins the name before it in a group.
                let groups = groups(&k.args);
                let names = groups.iter().flat_map(|g| g.0.split(','));
                for name in names.filter(|n| !n.is_empty()) {
                    cx.global(name);
                }
            }
            Item::Keyword(k) if k.name == "symbol" => {
                for (name, span) in groups(&k.args) {
                    cx.declare(&name, &span);
                }
            }
            _ => {}
        }
    }
    for item in &file.items {
        match item {
            Item::Keyword(k) => cx.keyword(k),
            Item::Production(p) => {
                if let Some(p) = cx.production(p) {
                    cx.sys.productions.push(p);
                }
            }
            Item::Define { .. } => {}
        }
    }
    cx.structure(file);
    // A structure's seed gives the axiom; a graph has its own.
    let graph = keyword("graph").next().is_some();
    if keyword("axiom").next().is_none() && cx.sys.structure.is_none() && !graph {
        cx.diags.push(
            Diagnostic::global(codes::GFT_NO_AXIOM, "no axiom")
                .with_help("add a line `axiom WORD`, e.g. `axiom F`"),
        );
    }
    Lowered {
        system: cx.sys,
        spans: cx.spans,
    }
}

/// Arguments written without space between them, joined (`scale-length`,
/// `+t`, `2.5*delta`), with their spans.
fn groups(args: &[Arg]) -> Vec<(String, Span)> {
    let mut out: Vec<(String, Span)> = Vec::new();
    for a in args {
        let s = a.span();
        match out.last_mut() {
            Some((text, span)) if span.end == s.start => {
                text.push_str(a.text());
                span.end = s.end;
            }
            _ => out.push((a.text().to_string(), s.clone())),
        }
    }
    out
}

fn err(code: Code, span: &Span, msg: impl Into<String>, label: &str, help: &str) -> Diagnostic {
    Diagnostic::at(code, span.clone(), msg)
        .with_label(label.to_string())
        .with_help(help.to_string())
}

/// The names a production binds: its formals, then the names its
/// statements assign.
struct Locals(Vec<String>);
