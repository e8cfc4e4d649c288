//! Lowering a LinF AST to the IR.
//!
//! What each construct becomes (see also the module docs of [`crate::ir`]):
//!
//! * a name in `lines` is a symbol drawn as a step ([`TurtleOp::Forward`]
//!   with `draw`), a name in `blanks` a step without drawing; a rule head
//!   that is neither is a non-terminal (no turtle meaning);
//! * `+t` (one sign, angle `t`) is the symbol `+t`, interpreted as the
//!   Frenet rotation `t` ([`TurtleOp::Frenet`]); `-t` is `-t`, the negated
//!   pair; a run `++t` is two symbols `+t +t`; a sign without a name uses the
//!   default rotation and is the symbol `+` or `-`;
//! * `x@` is the symbol `x@` ([`TurtleOp::ScaleLength`]), `{` `}` step
//!   through the colour list, `!` swaps `+` and `-`;
//! * `p?s` is a guarded symbol (see [`crate::ir::Guard`]): rewritten by
//!   `s`'s rule with probability `p` at each step, drawn as `s`;
//! * every rule is a context-free production of weight 1.
//!
//! Names in a string are split by the longest declared name (`fgf` is
//! `f g f`). A block given twice, a rotation, name or rule defined twice:
//! the later one is used, with a warning that says so.

mod declarations;
mod guards;
mod nesting;
mod signs;
mod strings;

use super::ast::{Block, BlockBody, File, Rule};
use super::lexer::BlockKind;
use crate::diagnostics::{codes, Code, Diagnostic, Diagnostics};
use crate::front::names::LongestNames;
use crate::front::repeats::Repeats;
use crate::front::suggest::Suggester;
use crate::ir::{Alternative, Production, Rgb, RotationId, Span, SpanTable, System, Word};
use declarations::{declare_head, declare_names, declare_rotations, lower_colours, redefined};
use guards::check_guards;
use std::collections::HashMap;
use strings::lower_string;

pub use crate::ir::Lowered;
pub use declarations::eval;

/// What a declared name is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Role {
    Line,
    Blank,
    Angle(RotationId),
    /// A rule head that is neither a line nor a blank.
    NonTerminal,
}

impl Role {
    fn describe(self) -> &'static str {
        match self {
            Role::Line => "a line",
            Role::Blank => "a blank",
            Role::Angle(_) => "an angle",
            Role::NonTerminal => "a rule head",
        }
    }
}

impl Cx<'_> {
    /// Reports what `build` makes, a diagnostic of `code` found in the
    /// string being lowered, unless the string has reported enough of that
    /// code already: a mistake repeated a million times in one string is
    /// reported a few times, then counted ([`Repeats`]).
    fn report(&mut self, code: Code, build: impl FnOnce(&mut Self) -> Diagnostic) {
        if self.repeats.admit(self.diags, code) {
            let d = build(self);
            self.repeats.push(self.diags, d);
        }
    }

    /// The declared angle names (`angles`), or all the other names.
    fn names(&self, angles: bool) -> Vec<&str> {
        self.roles
            .iter()
            .filter(|(_, (r, _))| matches!(r, Role::Angle(_)) == angles)
            .map(|(n, _)| n.as_str())
            .collect()
    }
}

struct Cx<'a> {
    diags: &'a mut Diagnostics,
    sys: System,
    spans: SpanTable,
    roles: HashMap<String, (Role, Span)>,
    /// Length of the longest declared name.
    longest: usize,
    default_rotation: Option<RotationId>,
    /// Heads with a rule.
    has_rule: HashMap<String, Span>,
    /// What the string being lowered reported.
    repeats: Repeats,
    /// What suggestions for unknown names may still cost.
    suggester: Suggester,
    /// The declared angles, sorted (for help lines, once they are all
    /// declared).
    angle_names: Vec<String>,
    /// The declared names, for splitting runs of them (once they are all
    /// declared).
    name_index: Option<LongestNames>,
}

/// Lowers `file`, reporting problems to `diags`. The system is usable only
/// when no error was reported.
pub fn lower(file: &File, diags: &mut Diagnostics) -> Lowered {
    let mut sys = System::new();
    sys.settings.delta = 0.0;
    let mut cx = Cx {
        diags,
        sys,
        spans: SpanTable::default(),
        roles: HashMap::new(),
        longest: 0,
        default_rotation: None,
        has_rule: HashMap::new(),
        repeats: Repeats::default(),
        suggester: Suggester::default(),
        angle_names: Vec::new(),
        name_index: None,
    };
    directives(file, &mut cx);
    let blocks = winning_blocks(file, cx.diags);
    let get = |k: BlockKind| blocks.iter().find(|b| b.kind == k).map(|b| &b.body);

    if let Some(BlockBody::Names(names)) = get(BlockKind::Lines) {
        declare_names(&mut cx, names, Role::Line);
    }
    if let Some(BlockBody::Names(names)) = get(BlockKind::Blanks) {
        declare_names(&mut cx, names, Role::Blank);
    }
    if let Some(BlockBody::Angles(angles)) = get(BlockKind::Angles) {
        declare_rotations(&mut cx, angles);
    }
    let rules: Vec<&Rule> = match get(BlockKind::Rules) {
        Some(BlockBody::Rules(rules)) => winning_rules(&mut cx, rules),
        _ => Vec::new(),
    };
    for r in &rules {
        declare_head(&mut cx, &r.head);
    }
    match get(BlockKind::Colors) {
        Some(BlockBody::Colors(colours)) => lower_colours(&mut cx, colours),
        _ => cx.sys.colours = vec![Rgb(0, 0, 0)],
    }
    cx.angle_names = cx.names(true).into_iter().map(String::from).collect();
    cx.angle_names.sort();
    cx.name_index = Some(LongestNames::new(cx.roles.keys().map(String::as_str)));

    match blocks.iter().find(|b| b.kind == BlockKind::Axiom) {
        Some(Block {
            body: BlockBody::Axiom(items),
            ..
        }) => {
            let (word, spans) = lower_string(&mut cx, items);
            cx.sys.axiom = Word::from(word);
            cx.spans.axiom = spans;
        }
        _ => cx.diags.push(
            Diagnostic::global(codes::LINF_NO_AXIOM, "no `axiom` block: the axiom is empty")
                .with_help("add `axiom` followed by the starting string, e.g. `axiom f`"),
        ),
    }
    for r in rules {
        let head = cx.sys.intern(&r.head.text);
        let (successor, spans) = lower_string(&mut cx, &r.body);
        cx.spans.symbols.entry(head).or_insert(r.head.span.clone());
        cx.sys.productions.push(Production::new(
            Vec::new(),
            vec![head],
            Vec::new(),
            vec![Alternative::new(1.0, Word::from(successor))],
        ));
        cx.spans.productions.push(r.span.clone());
        cx.spans.successors.push(vec![spans]);
    }
    check_guards(&mut cx);
    Lowered {
        system: cx.sys,
        spans: cx.spans,
    }
}

/// `#: steps N` and `#: view AZ,EL`.
fn directives(file: &File, cx: &mut Cx<'_>) {
    for d in &file.directives {
        let text = d.text.trim();
        let (key, value) = text.split_once(char::is_whitespace).unwrap_or((text, ""));
        let value = value.trim();
        let ok = match key {
            "steps" => value
                .parse::<u64>()
                .map(|n| cx.sys.settings.steps = Some(n))
                .is_ok(),
            "view" => {
                let parts: Vec<Option<f64>> = value
                    .split(',')
                    .map(|p| p.trim().parse::<f64>().ok().filter(|v| v.is_finite()))
                    .collect();
                match parts[..] {
                    [Some(az), Some(el)] => {
                        cx.sys.settings.view = Some((az.to_radians(), el.to_radians()));
                        true
                    }
                    _ => false,
                }
            }
            _ => false,
        };
        if !ok {
            cx.diags.push(
                Diagnostic::at(
                    codes::LINF_DIRECTIVE,
                    d.span.clone(),
                    format!("directive `{text}` not understood; it is ignored"),
                )
                .with_label("a `#:` comment is a graftal directive")
                .with_help("graftal reads `#: steps N` and `#: view AZIMUTH,ELEVATION`; write `# …` for a plain comment"),
            );
        }
    }
}

/// The block of each kind that is used: the last one, with a warning for
/// each earlier one.
fn winning_blocks<'f>(file: &'f File, diags: &mut Diagnostics) -> Vec<&'f Block> {
    let mut out: Vec<&Block> = Vec::new();
    for kind in BlockKind::ALL {
        let of_kind: Vec<&Block> = file.blocks.iter().filter(|b| b.kind == kind).collect();
        let Some(last) = of_kind.last() else {
            continue;
        };
        for earlier in &of_kind[..of_kind.len() - 1] {
            diags.push(
                Diagnostic::at(
                    codes::LINF_DUPLICATE_BLOCK,
                    earlier.keyword.clone(),
                    format!(
                        "`{}` block given twice; the later one is used",
                        kind.keyword()
                    ),
                )
                .with_label("this block is ignored")
                .with_secondary(last.keyword.clone(), "this one is used")
                .with_help(format!(
                    "merge the two `{}` blocks into one",
                    kind.keyword()
                )),
            );
        }
        out.push(last);
    }
    out
}

/// The rules used: for a head given twice, the later rule.
fn winning_rules<'r>(cx: &mut Cx<'_>, rules: &'r [Rule]) -> Vec<&'r Rule> {
    let mut last: HashMap<&str, usize> = HashMap::new();
    for (i, r) in rules.iter().enumerate() {
        if let Some(before) = last.insert(&r.head.text, i) {
            redefined(
                cx,
                &format!("the rule for `{}`", r.head.text),
                rules[i].head.span.clone(),
                rules[before].head.span.clone(),
            );
        }
    }
    rules
        .iter()
        .enumerate()
        .filter(|(i, r)| last.get(r.head.text.as_str()) == Some(i))
        .map(|(_, r)| r)
        .collect()
}
