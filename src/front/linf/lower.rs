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

use super::ast::{
    BinOp, Block, BlockBody, ColourDecl, Component, Expr, ExprKind, File, Item, Name, RotationDecl,
    Rule,
};
use super::lexer::BlockKind;
use crate::common::vocabulary::{self, TurtleSet};
use crate::diagnostics::{codes, nearest, Code, Diagnostic, Diagnostics};
use crate::front::name_list;
use crate::front::names::LongestNames;
use crate::front::repeats::Repeats;
use crate::front::suggest::Suggester;
use crate::ir::{
    Alternative, Angle, Production, Rgb, Rotation, RotationId, Span, SpanTable, SymbolId, System,
    TurtleOp, Word,
};
use crate::number::radians;
use std::borrow::Cow;
use std::collections::HashMap;

pub use crate::ir::Lowered;

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

fn redefined(cx: &mut Cx<'_>, what: &str, now: Span, before: Span) {
    cx.diags.push(
        Diagnostic::at(
            codes::LINF_REDEFINED,
            now,
            format!("{what} defined twice; this later definition is used"),
        )
        .with_label("used")
        .with_secondary(before, "ignored")
        .with_help("remove one of the two definitions"),
    );
}

fn conflict(cx: &mut Cx<'_>, name: &Name, role: Role, before: Role, before_span: Span) {
    cx.diags.push(
        Diagnostic::at(
            codes::LINF_NAME_CONFLICT,
            name.span.clone(),
            format!(
                "`{}` is declared as {} and as {}",
                name.text,
                before.describe(),
                role.describe()
            ),
        )
        .with_label(format!("declared as {} here", role.describe()))
        .with_secondary(
            before_span,
            format!("declared as {} here", before.describe()),
        )
        .with_help("a name has one meaning; rename one of them"),
    );
}

fn set_role(cx: &mut Cx<'_>, name: &Name, role: Role) {
    cx.longest = cx.longest.max(name.text.len());
    cx.roles
        .insert(name.text.clone(), (role, name.span.clone()));
}

fn declare_names(cx: &mut Cx<'_>, names: &[Name], role: Role) {
    for n in names {
        match cx.roles.get(&n.text).cloned() {
            Some((before, span)) if before == role => {
                redefined(cx, &format!("`{}`", n.text), n.span.clone(), span)
            }
            Some((before, span)) => {
                conflict(cx, n, role, before, span);
                continue;
            }
            None => {}
        }
        set_role(cx, n, role);
        let id = cx.sys.intern(&n.text);
        cx.spans.symbols.entry(id).or_insert(n.span.clone());
        cx.sys.set_interpretation(
            id,
            TurtleOp::Forward {
                draw: role == Role::Line,
            },
        );
    }
}

fn declare_rotations(cx: &mut Cx<'_>, decls: &[RotationDecl]) {
    let mut default_span: Option<Span> = None;
    for d in decls {
        // A rotation in error is still declared (as no rotation at all), so
        // that its uses are not reported again; the file has an error and is
        // not drawn anyway.
        let (torsion, curvature) =
            rotation_pair(cx, d).unwrap_or((Angle::Radians(0.0), Angle::Radians(0.0)));
        let name = d.name.as_ref().map_or(String::new(), |n| n.text.clone());
        let rotation = Rotation {
            name: name.clone(),
            torsion,
            curvature,
        };
        match &d.name {
            None => {
                if let Some(before) = default_span.replace(d.span.clone()) {
                    redefined(cx, "the default rotation", d.span.clone(), before);
                }
                let id = RotationId(cx.sys.rotations.len() as u32);
                cx.sys.rotations.push(rotation);
                cx.default_rotation = Some(id);
            }
            Some(n) => {
                match cx.roles.get(&n.text).cloned() {
                    Some((Role::Angle(id), span)) => {
                        redefined(
                            cx,
                            &format!("the rotation `{}`", n.text),
                            n.span.clone(),
                            span,
                        );
                        cx.sys.rotations[id.0 as usize] = rotation;
                        set_role(cx, n, Role::Angle(id));
                        continue;
                    }
                    Some((before, span)) => {
                        let id = RotationId(0);
                        conflict(cx, n, Role::Angle(id), before, span);
                        continue;
                    }
                    None => {}
                }
                let id = RotationId(cx.sys.rotations.len() as u32);
                cx.sys.rotations.push(rotation);
                set_role(cx, n, Role::Angle(id));
            }
        }
    }
}

/// The (torsion, curvature) of a declaration, or `None` after reporting why
/// it has none.
fn rotation_pair(cx: &mut Cx<'_>, d: &RotationDecl) -> Option<(Angle, Angle)> {
    if d.recovered {
        return None;
    }
    if d.components.len() != 2 {
        let n = d.components.len();
        let help = match n {
            1 => "a rotation is a pair (torsion, curvature); for a turn in the plane write `(0, angle)`",
            _ => "a rotation is a pair (torsion, curvature), e.g. `(0, pi/3)`",
        };
        cx.diags.push(
            Diagnostic::at(
                codes::LINF_NOT_A_PAIR,
                d.span.clone(),
                format!("a rotation needs two components, torsion and curvature; this one has {n}"),
            )
            .with_label(format!("{n} component{}", if n == 1 { "" } else { "s" }))
            .with_help(help),
        );
        return None;
    }
    let t = angle(cx, &d.components[0]);
    let c = angle(cx, &d.components[1]);
    Some((t?, c?))
}

fn angle(cx: &mut Cx<'_>, c: &Component) -> Option<Angle> {
    match c {
        Component::Value(e) => value(cx, e).map(Angle::Radians),
        Component::Interval { lo, hi, span } => {
            let (l, h) = (value(cx, lo), value(cx, hi));
            let (l, h) = (l?, h?);
            if l > h {
                let (l, h) = (radians(l), radians(h));
                cx.diags.push(
                    Diagnostic::at(
                        codes::LINF_EMPTY_INTERVAL,
                        span.clone(),
                        format!("interval from {l} down to {h}: its low end exceeds its high end"),
                    )
                    .with_label("empty interval")
                    .with_secondary(lo.span.clone(), format!("low end {l}"))
                    .with_secondary(hi.span.clone(), format!("high end {h}"))
                    .with_help("write the low end first: `[lo hi]`"),
                );
                return None;
            }
            Some(Angle::Uniform { lo: l, hi: h })
        }
    }
}

/// The value of `e`, or `None` after reporting why it has none.
fn value(cx: &mut Cx<'_>, e: &Expr) -> Option<f64> {
    match eval(e) {
        Ok(v) => Some(v),
        Err(d) => {
            cx.diags.push(d);
            None
        }
    }
}

/// Evaluates an expression over numbers and `pi` (by recursion, as deep as
/// the tree, which the parser keeps within [`crate::ir::MAX_NESTING`]).
pub fn eval(e: &Expr) -> Result<f64, Diagnostic> {
    let bad = |msg: String| Diagnostic::at(codes::LINF_BAD_EXPRESSION, e.span.clone(), msg);
    let v = match &e.kind {
        ExprKind::Number(v) => *v,
        ExprKind::Name(n) if n == "pi" => std::f64::consts::PI,
        ExprKind::Name(n) => {
            let d = bad(format!("unknown name `{n}` in an expression")).with_label("not a number");
            return Err(if nearest(n, &["pi"]).is_empty() {
                d.with_help("expressions are made of numbers, `pi`, `+ - * /` and parentheses")
            } else {
                d.with_help("did you mean `pi`?")
            });
        }
        ExprKind::Neg(x) => -eval(x)?,
        ExprKind::Binary(op, a, b) => {
            let (a, b) = (eval(a)?, eval(b)?);
            match op {
                BinOp::Add => a + b,
                BinOp::Sub => a - b,
                BinOp::Mul => a * b,
                BinOp::Div if b == 0.0 => {
                    return Err(bad("division by zero".to_string())
                        .with_label("the divisor is 0")
                        .with_help("a rotation component must be a finite number"))
                }
                BinOp::Div => a / b,
            }
        }
    };
    if v.is_finite() {
        Ok(v)
    } else {
        Err(bad("this expression has no finite value".to_string())
            .with_label("too large")
            .with_help("angles are in radians; use numbers of a sensible size"))
    }
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

fn declare_head(cx: &mut Cx<'_>, head: &Name) {
    cx.has_rule.insert(head.text.clone(), head.span.clone());
    match cx.roles.get(&head.text).cloned() {
        Some((Role::Angle(_), span)) => cx.diags.push(
            Diagnostic::at(
                codes::LINF_NAME_CONFLICT,
                head.span.clone(),
                format!("a rule for `{}`, which is an angle", head.text),
            )
            .with_label("angles cannot be rewritten")
            .with_secondary(span, "declared as an angle here")
            .with_help("rename the angle or the rule head"),
        ),
        Some(_) => {}
        None => {
            set_role(cx, head, Role::NonTerminal);
            let id = cx.sys.intern(&head.text);
            cx.spans.symbols.entry(id).or_insert(head.span.clone());
        }
    }
}

fn lower_colours(cx: &mut Cx<'_>, decls: &[ColourDecl]) {
    for (i, d) in decls.iter().enumerate() {
        if let Some((label, span)) = &d.label {
            if *label != i as f64 {
                cx.diags.push(
                    Diagnostic::at(
                        codes::LINF_COLOUR_LABEL,
                        span.clone(),
                        format!("colour labelled {label} is number {i} in the list"),
                    )
                    .with_label(format!("this is colour {i}"))
                    .with_help("colours are used in the order they are listed; labels are only for reading"),
                );
            }
        }
        if d.components.len() != 3 {
            cx.diags.push(
                Diagnostic::at(
                    codes::LINF_COLOUR_ARITY,
                    d.span.clone(),
                    format!(
                        "a colour has three components (red, green, blue); this one has {}",
                        d.components.len()
                    ),
                )
                .with_label("not an (r, g, b) triple")
                .with_help("write each colour as `(r, g, b)` with components from 0 to 255"),
            );
            continue;
        }
        let mut rgb = [0u8; 3];
        let mut ok = true;
        for (k, e) in d.components.iter().enumerate() {
            let Some(v) = value(cx, e) else {
                ok = false;
                continue;
            };
            if !(0.0..=255.0).contains(&v) || v.fract() != 0.0 {
                ok = false;
                cx.diags.push(
                    Diagnostic::at(
                        codes::LINF_COLOUR_RANGE,
                        e.span.clone(),
                        format!("colour component {v} is not a whole number from 0 to 255"),
                    )
                    .with_label("out of range")
                    .with_help("components are 0..255, e.g. `(120, 120, 120)`"),
                );
            } else {
                rgb[k] = v as u8;
            }
        }
        if ok {
            cx.sys.colours.push(Rgb(rgb[0], rgb[1], rgb[2]));
        }
    }
    if cx.sys.colours.is_empty() {
        cx.sys.colours.push(Rgb(0, 0, 0));
    }
}

/// Splits a run of name characters into declared names, longest first.
/// Undeclared stretches come back as `Err` pieces.
fn split<'n>(cx: &Cx<'_>, text: &'n str, start: usize) -> Vec<(Result<Role, ()>, &'n str, Span)> {
    let built;
    let index = match &cx.name_index {
        Some(index) => index,
        None => {
            built = LongestNames::new(cx.roles.keys().map(String::as_str));
            &built
        }
    };
    let longest = index.longest_at(text);
    let mut out: Vec<(Result<Role, ()>, &str, Span)> = Vec::new();
    let mut p = 0;
    while p < text.len() {
        let len = longest[p];
        let found = (len > 0)
            .then(|| cx.roles.get(&text[p..p + len]).map(|(r, _)| (*r, len)))
            .flatten();
        match found {
            Some((role, len)) => {
                out.push((Ok(role), &text[p..p + len], start + p..start + p + len));
                p += len;
            }
            None => {
                // Names are ASCII; extend an unknown stretch by one byte.
                match out.last_mut() {
                    Some((Err(()), _, span)) if span.end == start + p => {
                        span.end += 1;
                        let s = span.start - start;
                        out.last_mut().expect("just matched").1 = &text[s..p + 1];
                    }
                    _ => out.push((Err(()), &text[p..p + 1], start + p..start + p + 1)),
                }
                p += 1;
            }
        }
    }
    out
}

struct StringOut {
    word: Vec<SymbolId>,
    spans: Vec<Span>,
}

impl StringOut {
    fn push(&mut self, id: SymbolId, span: Span) {
        self.word.push(id);
        self.spans.push(span);
    }
}

fn undeclared(cx: &mut Cx<'_>, text: &str, span: Span, whole: &str) {
    cx.report(codes::LINF_UNDECLARED, |cx| {
        undeclared_name(cx, text, span, whole)
    });
}

fn undeclared_name(cx: &mut Cx<'_>, text: &str, span: Span, whole: &str) -> Diagnostic {
    // Angles are not suggested: alone in a string they would be wrong too.
    let affordable = cx
        .suggester
        .afford(text.len() + whole.len(), cx.roles.len(), cx.longest);
    let names = if affordable {
        cx.names(false)
    } else {
        Vec::new()
    };
    let mut near = nearest(text, &names);
    if near.is_empty() && whole != text {
        near = nearest(whole, &names);
    }
    near.sort();
    // With one-letter names everything is one edit away: no guess then.
    if near.len() > 3 {
        near.clear();
    }
    let d = Diagnostic::at(
        codes::LINF_UNDECLARED,
        span,
        format!("`{text}` is not declared"),
    )
    .with_label("not a line, blank, angle or rule head");
    match near.as_slice() {
        [] => d.with_help(format!(
            "declare it: `lines {text}` to draw it, `blanks {text}` to move without drawing, or give it a rule `{text} = …`"
        )),
        [one] => d.suggesting(one),
        many => d.with_help(format!(
            "did you mean one of {}?",
            many.iter()
                .map(|n| format!("`{n}`"))
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

/// Appends the pieces of a name (already split) to `out`.
fn push_pieces(
    cx: &mut Cx<'_>,
    out: &mut StringOut,
    pieces: &[(Result<Role, ()>, &str, Span)],
    whole: &str,
) {
    for (role, text, span) in pieces {
        match role {
            Err(()) => undeclared(cx, text, span.clone(), whole),
            Ok(Role::Angle(_)) => cx.report(codes::LINF_BARE_ANGLE, |_| {
                Diagnostic::at(
                    codes::LINF_BARE_ANGLE,
                    span.clone(),
                    format!("the angle `{text}` is used without a sign"),
                )
                .with_label("an angle name must follow `+` or `-`")
                .with_help(format!(
                    "write `+{text}` or `-{text}` (no space) to rotate by it"
                ))
            }),
            Ok(_) => {
                let id = cx.sys.intern(text);
                out.push(id, span.clone());
            }
        }
    }
}

/// Names may end in digits (`f1`), so `f0.5?j` and `f2@` lex as the name
/// `f0` or `f2` and what follows. When the trailing digits of such a name
/// are no declared name, and a number, `?` or `@` follows, they are the
/// number: `f0.5?j` is `f 0.5?j`, `f2@` is `f 2@`.
fn detach_numbers<'i>(cx: &Cx<'_>, items: &'i [Item]) -> Cow<'i, [Item]> {
    // Most strings have no name ending in digits: they are not copied.
    let ends_in_digit =
        |i: &Item| matches!(i, Item::Name(n) if n.text.ends_with(|c: char| c.is_ascii_digit()));
    if !items.iter().any(ends_in_digit) {
        return Cow::Borrowed(items);
    }
    let mut out: Vec<Item> = Vec::with_capacity(items.len());
    let mut i = 0;
    while i < items.len() {
        let (Item::Name(n), Some(next)) = (&items[i], items.get(i + 1)) else {
            out.push(items[i].clone());
            i += 1;
            continue;
        };
        let fraction = match next {
            Item::Number { text, span, .. }
                if text.starts_with('.') && span.start == n.span.end =>
            {
                Some((text.as_str(), span.end))
            }
            Item::Question(s) | Item::At(s) if s.start == n.span.end => None,
            _ => {
                out.push(items[i].clone());
                i += 1;
                continue;
            }
        };
        let digits = n.text.len() - n.text.trim_end_matches(|c: char| c.is_ascii_digit()).len();
        let unknown_tail =
            matches!(split(cx, &n.text, 0).last(), Some((Err(()), t, _)) if t.len() >= digits);
        if digits == 0 || digits == n.text.len() || !unknown_tail {
            out.push(items[i].clone());
            i += 1;
            continue;
        }
        let cut = n.span.end - digits;
        out.push(Item::Name(Name {
            text: n.text[..n.text.len() - digits].to_string(),
            span: n.span.start..cut,
        }));
        let digit_text = &n.text[n.text.len() - digits..];
        let (text, end) = match fraction {
            Some((f, end)) => (format!("{digit_text}{f}"), end),
            None => (digit_text.to_string(), n.span.end),
        };
        out.push(Item::Number {
            value: text.parse().unwrap_or(f64::NAN),
            text,
            span: cut..end,
        });
        i += if fraction.is_some() { 2 } else { 1 };
    }
    Cow::Owned(out)
}

/// Interns `name` with the turtle meaning `op` and appends it.
fn push_op(cx: &mut Cx<'_>, out: &mut StringOut, name: &str, op: TurtleOp, span: Span) {
    let id = cx.sys.intern(name);
    cx.sys.set_interpretation(id, op);
    out.push(id, span);
}

/// The brackets of a string not yet closed, and at each bracket depth the
/// `{` not yet closed by `}`.
struct Nesting {
    open: Vec<Span>,
    colours: Vec<Vec<Span>>,
}

impl Nesting {
    fn new() -> Self {
        Nesting {
            open: Vec::new(),
            colours: vec![Vec::new()],
        }
    }

    fn open(&mut self, span: &Span) {
        self.open.push(span.clone());
        self.colours.push(Vec::new());
    }

    fn close(&mut self, cx: &mut Cx<'_>, span: &Span) {
        if self.open.pop().is_some() {
            self.colours.pop();
            return;
        }
        cx.report(codes::LINF_UNBALANCED, |_| {
            Diagnostic::at(
                codes::LINF_UNBALANCED,
                span.clone(),
                "`]` without a matching `[`",
            )
            .with_label("nothing to close")
            .with_help("remove this `]` or add the `[` that opens the branch")
        });
    }

    fn next_colour(&mut self, span: &Span) {
        self.colours
            .last_mut()
            .expect("never empty")
            .push(span.clone());
    }

    fn previous_colour(&mut self, cx: &mut Cx<'_>, span: &Span) {
        if self
            .colours
            .last_mut()
            .expect("never empty")
            .pop()
            .is_some()
        {
            return;
        }
        cx.report(codes::LINF_COLOUR_BALANCE, |_| {
            Diagnostic::at(
                codes::LINF_COLOUR_BALANCE,
                span.clone(),
                "`}` without a `{` before it in this string",
            )
            .with_label("goes back to a colour chosen outside this string")
            .with_help("`}` returns to the previous colour; pair it with a `{`")
        });
    }

    /// Reports every `[` never closed, and the first `{` never closed
    /// outside a branch (a branch restores the colour).
    fn check_closed(self, cx: &mut Cx<'_>) {
        for span in self.open {
            cx.report(codes::LINF_UNBALANCED, |_| {
                Diagnostic::at(codes::LINF_UNBALANCED, span, "`[` is never closed")
                    .with_label("this branch has no `]`")
                    .with_help("add `]` where the branch ends")
            });
        }
        if let Some(unclosed) = self.colours.first().and_then(|c| c.first()) {
            cx.diags.push(
                Diagnostic::at(
                    codes::LINF_COLOUR_BALANCE,
                    unclosed.clone(),
                    "`{` is never closed by `}` in this string",
                )
                .with_label("the colour stays changed after this string")
                .with_help(
                    "close it with `}`, or put it inside a branch `[…]`, which restores the colour",
                ),
            );
        }
    }
}

fn lower_string(cx: &mut Cx<'_>, items: &[Item]) -> (Vec<SymbolId>, Vec<Span>) {
    let items = &detach_numbers(cx, items)[..];
    let mut out = StringOut {
        word: Vec::new(),
        spans: Vec::new(),
    };
    let mut nesting = Nesting::new();
    let mut i = 0;
    while i < items.len() {
        i = match &items[i] {
            Item::Name(n) => {
                let pieces = split(cx, &n.text, n.span.start);
                push_pieces(cx, &mut out, &pieces, &n.text);
                i + 1
            }
            Item::Sign { .. } => lower_signs(cx, &mut out, items, i),
            Item::Number { value, text, span } => {
                lower_number(cx, &mut out, items, i, (*value, text), span)
            }
            Item::Question(span) => {
                missing_number(cx, span, "?", "`0.5?j` expands `j` with probability 0.5");
                i + 1
            }
            Item::At(span) => {
                missing_number(cx, span, "@", "`0.5@` halves the length");
                i + 1
            }
            Item::Open(span) => {
                nesting.open(span);
                out.push(SymbolId::OPEN, span.clone());
                i + 1
            }
            Item::Close(span) => {
                nesting.close(cx, span);
                out.push(SymbolId::CLOSE, span.clone());
                i + 1
            }
            Item::NextColour(span) => {
                nesting.next_colour(span);
                push_op(cx, &mut out, "{", linf_op("{"), span.clone());
                i + 1
            }
            Item::PreviousColour(span) => {
                nesting.previous_colour(cx, span);
                push_op(cx, &mut out, "}", linf_op("}"), span.clone());
                i + 1
            }
            Item::Swap(span) => {
                push_op(cx, &mut out, "!", linf_op("!"), span.clone());
                i + 1
            }
        };
    }
    nesting.check_closed(cx);
    cx.repeats.end_item(cx.diags, "in this string");
    // The first place each symbol is written (for diagnostics elsewhere,
    // e.g. translation).
    for (id, span) in out.word.iter().zip(&out.spans) {
        cx.spans.symbols.entry(*id).or_insert_with(|| span.clone());
    }
    (out.word, out.spans)
}

/// What LinF's fixed symbol `name` does ([`vocabulary`]'s LinF set).
fn linf_op(name: &str) -> TurtleOp {
    vocabulary::op(TurtleSet::Linf, name).unwrap_or(TurtleOp::Push)
}

/// A number, as written: `x@` scales the length, `p?s` guards `s`; any
/// other number is reported. Returns the index of the next item.
fn lower_number(
    cx: &mut Cx<'_>,
    out: &mut StringOut,
    items: &[Item],
    i: usize,
    (value, text): (f64, &str),
    span: &Span,
) -> usize {
    match items.get(i + 1) {
        Some(Item::At(at)) => {
            let op = TurtleOp::ScaleLength(value);
            push_op(cx, out, &format!("{text}@"), op, span.start..at.end);
            i + 2
        }
        Some(Item::Question(q)) => lower_guard(cx, out, items, i, value, span, q),
        _ => {
            cx.report(codes::LINF_STRAY_NUMBER, |_| {
                Diagnostic::at(
                    codes::LINF_STRAY_NUMBER,
                    span.clone(),
                    format!("the number `{text}` is not followed by `?` or `@`"),
                )
                .with_label("a number in a string must say what it is for")
                .with_help(format!(
                    "`{text}@` multiplies the length; `{text}?s` expands `s` with probability {text}"
                ))
            });
            i + 1
        }
    }
}

/// `?` or `@` (`mark`) with no number before it.
fn missing_number(cx: &mut Cx<'_>, span: &Span, mark: &str, example: &str) {
    cx.report(codes::LINF_MISSING_NUMBER, |_| {
        Diagnostic::at(
            codes::LINF_MISSING_NUMBER,
            span.clone(),
            format!("`{mark}` without a number before it"),
        )
        .with_label("needs a number right before it")
        .with_help(format!("write the number first: {example}"))
    });
}

/// A run of adjacent signs: each sign (`true` for `-`) and the run's
/// span and text.
struct SignRun {
    signs: Vec<(bool, Span)>,
    span: Span,
    text: String,
}

impl SignRun {
    /// The run starting at `items[i]`, and the index of the item after it.
    fn read(items: &[Item], mut i: usize) -> (Self, usize) {
        let mut signs: Vec<(bool, Span)> = Vec::new();
        while let Some(Item::Sign { minus, span }) = items.get(i) {
            if signs.last().is_some_and(|(_, s)| s.end != span.start) {
                break;
            }
            signs.push((*minus, span.clone()));
            i += 1;
        }
        let span = signs[0].1.start..signs[signs.len() - 1].1.end;
        let text = signs
            .iter()
            .map(|(m, _)| if *m { '-' } else { '+' })
            .collect();
        (SignRun { signs, span, text }, i)
    }
}

/// A run of adjacent signs and the angle named right after it; returns the
/// index of the next item.
fn lower_signs(cx: &mut Cx<'_>, out: &mut StringOut, items: &[Item], i: usize) -> usize {
    let (run, mut i) = SignRun::read(items, i);
    // The name right after the run, split.
    let mut rest: Vec<(Result<Role, ()>, &str, Span)> = Vec::new();
    let mut whole = "";
    if let Some(Item::Name(n)) = items.get(i) {
        if n.span.start == run.span.end {
            rest = split(cx, &n.text, n.span.start);
            whole = &n.text;
            i += 1;
        }
    }
    let (rotation, suffix) = match rest.first() {
        Some((Ok(Role::Angle(id)), text, _)) => {
            let r = (Some(*id), text.to_string());
            let _ = rest.remove(0);
            r
        }
        Some((Err(()), text, span)) => {
            unknown_angle(cx, &run, text, span);
            return i;
        }
        _ => (default_rotation(cx, &run), String::new()),
    };
    if let Some(rotation) = rotation {
        push_rotations(cx, out, &run, rotation, &suffix);
    }
    push_pieces(cx, out, &rest, whole);
    i
}

/// An undeclared name `text` right after the signs of `run`.
fn unknown_angle(cx: &mut Cx<'_>, run: &SignRun, text: &str, span: &Span) {
    cx.report(codes::LINF_UNKNOWN_ANGLE, |cx| {
        unknown_angle_diagnostic(cx, run, text, span)
    });
}

fn unknown_angle_diagnostic(cx: &mut Cx<'_>, run: &SignRun, text: &str, span: &Span) -> Diagnostic {
    let run_text = &run.text;
    let affordable = cx.suggester.afford(text.len(), cx.roles.len(), cx.longest);
    let angles: Vec<&str> = match affordable {
        true => cx.angle_names.iter().map(String::as_str).collect(),
        false => Vec::new(),
    };
    // Rotation names only: a line or rule name after the signs would be
    // another reading of the text (the default rotation, then the name),
    // not the rotation the writer misspelt.
    let mut near: Vec<String> = nearest(text, &angles)
        .into_iter()
        .map(|n| format!("{run_text}{n}"))
        .collect();
    near.sort();
    if near.len() > 3 {
        near.clear();
    }
    let d = Diagnostic::at(
        codes::LINF_UNKNOWN_ANGLE,
        span.clone(),
        format!("unknown angle `{text}` after `{run_text}`"),
    )
    .with_label("not a declared angle")
    .with_secondary(run.span.clone(), "rotates by the angle named here");
    match (near.first(), cx.angle_names.is_empty()) {
        (Some(n), _) => d.suggesting(n),
        (None, true) => d.with_help(format!(
            "declare it in the angles block: `angles {text} = (0, pi/2)`"
        )),
        (None, false) => d.with_help(format!(
            "declared angles: {}; or declare `{text} = (…, …)` in the angles block",
            name_list(cx.angle_names.iter().map(String::as_str), false)
        )),
    }
}

/// The default rotation, for signs that name no angle; reported when
/// there is none.
fn default_rotation(cx: &mut Cx<'_>, run: &SignRun) -> Option<RotationId> {
    if cx.default_rotation.is_some() {
        return cx.default_rotation;
    }
    cx.report(codes::LINF_NO_DEFAULT_ROTATION, |cx| {
        let run_text = &run.text;
        let help = match cx.angle_names.first() {
            Some(a) => format!("name the angle right after the signs, e.g. `{run_text}{a}`, or declare a default rotation: `angles (0, pi/2)`"),
            None => "declare a default rotation in the angles block, e.g. `angles (0, pi/2)`".to_string(),
        };
        Diagnostic::at(
            codes::LINF_NO_DEFAULT_ROTATION,
            run.span.clone(),
            format!("`{run_text}` names no angle and no default rotation is declared"),
        )
        .with_label("rotates by what?")
        .with_help(help)
    });
    None
}

/// One symbol per sign of `run`: `+suffix` or `-suffix`, turning by
/// `rotation` (the angle named `suffix`, or the default rotation when it
/// is empty).
fn push_rotations(
    cx: &mut Cx<'_>,
    out: &mut StringOut,
    run: &SignRun,
    rotation: RotationId,
    suffix: &str,
) {
    for (minus, span) in &run.signs {
        let name = format!("{}{suffix}", if *minus { '-' } else { '+' });
        let op = TurtleOp::Frenet {
            rotation,
            negate: *minus,
        };
        // Each symbol spans its sign and the angle's name.
        let end = if suffix.is_empty() {
            span.end
        } else {
            run.span.end + suffix.len()
        };
        push_op(cx, out, &name, op, span.start..end);
    }
}

/// `p?s`: returns the index of the item after `s`.
fn lower_guard(
    cx: &mut Cx<'_>,
    out: &mut StringOut,
    items: &[Item],
    i: usize,
    p: f64,
    number: &Span,
    question: &Span,
) -> usize {
    let valid = p > 0.0 && p < 1.0;
    if !valid {
        cx.report(codes::LINF_PROBABILITY, |_| {
            Diagnostic::at(
                codes::LINF_PROBABILITY,
                number.clone(),
                format!("probability {p} is not between 0 and 1"),
            )
            .with_label("must be greater than 0 and less than 1")
            .with_help("`p?s` expands `s` with probability p, 0 < p < 1; to always expand it, write `s` alone")
        });
    }
    let Some(Item::Name(n)) = items.get(i + 2) else {
        cx.report(codes::LINF_GUARD_TARGET, |_| {
            Diagnostic::at(
                codes::LINF_GUARD_TARGET,
                question.clone(),
                "`?` is not followed by a symbol",
            )
            .with_label("guards nothing")
            .with_help("write the symbol right after `?`: `0.5?j`")
        });
        return i + 2;
    };
    let mut pieces = split(cx, &n.text, n.span.start);
    match pieces.first() {
        Some((Ok(Role::Angle(_)), _, _)) | Some((Err(()), _, _)) => {}
        Some((Ok(_), text, span)) => {
            let base = cx.sys.intern(text);
            if valid {
                let id = cx.sys.symbols.intern_guarded(p, base);
                cx.sys.intern(cx.sys.symbols.name(id).to_string().as_str());
                out.push(id, number.start..span.end);
            }
            let _ = pieces.remove(0);
        }
        None => {}
    }
    push_pieces(cx, out, &pieces, &n.text);
    i + 3
}

/// Warns about guards on symbols that have no rule.
fn check_guards(cx: &mut Cx<'_>) {
    let mut warned = std::collections::HashSet::new();
    let guarded: Vec<(SymbolId, f64, SymbolId)> = cx
        .sys
        .symbols
        .iter()
        .filter_map(|(id, info)| info.guard.map(|g| (id, g.probability, g.base)))
        .collect();
    for (id, p, base) in guarded {
        let name = cx.sys.symbols.name(base).to_string();
        if cx.has_rule.contains_key(&name) || !warned.insert(base) {
            continue;
        }
        let span = cx
            .spans
            .successors
            .iter()
            .flatten()
            .flatten()
            .zip(
                cx.sys
                    .productions
                    .iter()
                    .flat_map(|p| p.alternatives.iter())
                    .flat_map(|a| a.successor.0.iter()),
            )
            .find(|(_, s)| **s == id)
            .map(|(sp, _)| sp.clone())
            .or_else(|| {
                cx.sys
                    .axiom
                    .0
                    .iter()
                    .zip(&cx.spans.axiom)
                    .find(|(s, _)| **s == id)
                    .map(|(_, sp)| sp.clone())
            });
        let d = Diagnostic::global(
            codes::LINF_GUARD_NO_RULE,
            format!("`{p}?{name}` guards `{name}`, which has no rule: the guard changes nothing"),
        )
        .with_help(format!(
            "give `{name}` a rule (`{name} = …`) or drop `{p}?`"
        ));
        cx.diags.push(match span {
            Some(s) => Diagnostic { span: Some(s), ..d },
            None => d,
        });
    }
}
