//! Lowering one Fractint entry to the IR, with Fractint's checks.
//!
//! What each command does is in [`crate::ir`]'s module docs ("Fractint
//! entry"); the numbers are Fractint's `getnumber` ([`super::lexer::number`]).

use super::ast::{Body, Entry, LineKind};
use super::lexer::commands;
use super::parser::KEYWORDS;
use crate::common::vocabulary::fractint_op;
use crate::diagnostics::{codes, nearest, Diagnostic, Diagnostics};
use crate::ir::{Alternative, Production, Span, SpanTable, SymbolId, System, Word};

/// Fractint's default order (the `lsystem` type's one parameter, 2 in
/// `fractalp.c`): the steps derived when `-n` is not given.
pub const DEFAULT_ORDER: u64 = 2;

/// The characters Fractint 19 does not allow as rule heads.
pub const RESERVED: &str = "+-/\\@|!c<>[]";

/// The colour Fractint draws with until told otherwise.
pub const DEFAULT_COLOUR: usize = 15;

pub use crate::ir::Lowered;

pub use crate::common::palettes::fractint_palette as palette;

struct Cx<'a> {
    sys: System,
    spans: SpanTable,
    diags: &'a mut Diagnostics,
}

impl Cx<'_> {
    /// The symbols of a body, with their spans; warns on unbalanced
    /// brackets.
    fn word(&mut self, body: &Body) -> (Word, Vec<Span>) {
        let mut word = Vec::new();
        let mut spans = Vec::new();
        let mut depth: i64 = 0;
        let mut unbalanced = false;
        for (cmd, r) in commands(&body.text) {
            let span = body.span.start + r.start..body.span.start + r.end;
            let id = self.sys.intern(cmd);
            self.spans.symbols.entry(id).or_insert_with(|| span.clone());
            match cmd {
                "[" => depth += 1,
                "]" => {
                    depth -= 1;
                    unbalanced |= depth < 0;
                }
                _ => {}
            }
            word.push(id);
            spans.push(span);
        }
        if unbalanced || depth != 0 {
            self.diags.push(
                Diagnostic::at(
                    codes::FR_UNBALANCED,
                    body.span.clone(),
                    "unbalanced brackets in this string",
                )
                .with_label(if depth > 0 {
                    "a `[` has no `]`"
                } else {
                    "a `]` has no `[`"
                })
                .with_help("Fractint draws each string's brackets on their own: balance them"),
            );
        }
        (Word::from(word), spans)
    }
}

/// What an entry's lines say, read in order.
#[derive(Default)]
struct Lines<'e> {
    /// The last `Axiom` line's string.
    axiom: Option<&'e Body>,
    axiom_seen: bool,
    /// The last valid `Angle`.
    angle: Option<u32>,
    angle_seen: bool,
    /// Rules in file order: (head, head span, body).
    rules: Vec<(&'e str, Span, Option<&'e Body>)>,
}

impl Cx<'_> {
    /// Reads the lines of `entry`, reporting what Fractint rejects or
    /// ignores in each.
    fn read_lines<'e>(&mut self, entry: &'e Entry) -> Lines<'e> {
        let mut lines = Lines::default();
        for line in &entry.lines {
            match &line.kind {
                LineKind::Axiom { keyword, body } => {
                    lines.axiom_seen = true;
                    lines.axiom = body.as_ref();
                    if body.is_none() {
                        self.diags.push(
                            Diagnostic::at(
                                codes::FR_NO_AXIOM,
                                keyword.clone(),
                                "`Axiom` without a string",
                            )
                            .with_label("the axiom string is missing")
                            .with_help("write the string after the keyword, e.g. `Axiom F--F--F`"),
                        );
                    }
                }
                LineKind::Angle { keyword, value } => {
                    lines.angle_seen = true;
                    if let Some(n) = self.angle(keyword, value.as_ref()) {
                        lines.angle = Some(n);
                    }
                }
                LineKind::Rule {
                    head,
                    head_span,
                    body,
                } => {
                    self.check_rule_head(head, head_span);
                    lines.rules.push((head, head_span.clone(), body.as_ref()));
                }
                LineKind::Unknown { word, span, rule } => self.unknown_line(word, span, *rule),
            }
            if let Some(x) = &line.extra {
                self.extra_text(x, &line.kind);
            }
        }
        lines
    }

    /// The angle increments per turn of an `Angle` line: 3 to 50.
    fn angle(&mut self, keyword: &Span, value: Option<&Body>) -> Option<u32> {
        let (span, n) = match value {
            Some(v) => (v.span.clone(), atoi(&v.text)),
            None => (keyword.clone(), 0),
        };
        if (3..=50).contains(&n) {
            return Some(n as u32);
        }
        let what = match value {
            Some(v) => format!("illegal angle `{}`", v.text),
            None => "`Angle` without a number".to_string(),
        };
        let mut d = Diagnostic::at(codes::FR_BAD_ANGLE, span, what)
            .with_label("Fractint accepts 3 to 50")
            .with_help("`Angle n` turns by 360/n degrees; n is a whole number from 3 to 50");
        if n > 50 && 360 % n == 0 && (3..=50).contains(&(360 / n)) {
            d = d.with_note(format!(
                "n is not in degrees: for {n} degrees write `Angle {}`",
                360 / n
            ));
        }
        self.diags.push(d);
        None
    }

    /// Warns about a rule for a symbol Fractint 19 reserves.
    fn check_rule_head(&mut self, head: &str, head_span: &Span) {
        if !RESERVED.contains(head) {
            return;
        }
        self.diags.push(
            Diagnostic::at(
                codes::FR_RESERVED_RULE,
                head_span.clone(),
                format!("a rule for the reserved symbol `{head}`"),
            )
            .with_label("Fractint 19 rejects this rule")
            .with_note(format!(
                "read as Fractint 16 read it: the rule rewrites every command starting with `{head}`"
            ))
            .with_help("rename the symbol if you meant a variable of your own"),
        );
    }

    /// A line starting with a word that is no keyword (`rule`: followed by
    /// `=`, a rule head of several characters).
    fn unknown_line(&mut self, word: &str, span: &Span, rule: bool) {
        let d = if rule {
            Diagnostic::at(
                codes::FR_UNKNOWN_KEYWORD,
                span.clone(),
                format!("a rule for `{word}`: rule heads are one character"),
            )
            .with_label("several characters")
            .with_help("a rule rewrites one character, e.g. `x=F+F`")
        } else {
            let d = Diagnostic::at(
                codes::FR_UNKNOWN_KEYWORD,
                span.clone(),
                format!("unknown keyword `{word}`"),
            )
            .with_label("not `Angle`, `Axiom` or a rule");
            match nearest(word, &KEYWORDS).first() {
                Some(k) => d.suggesting(capitalised(k)),
                None => d.with_help("a line is `Angle n`, `Axiom STRING`, `x=STRING` or `}`"),
            }
        };
        self.diags.push(d);
    }

    /// Text after a line's string, which Fractint ignores.
    fn extra_text(&mut self, extra: &Span, kind: &LineKind) {
        let d = Diagnostic::at(
            codes::FR_EXTRA_TEXT,
            extra.clone(),
            "extra text after the command",
        )
        .with_label("Fractint reads one string per line");
        // `x = -FX` reads as the rule `x=` with the extra text `-FX`.
        let eq_body = matches!(kind, LineKind::Rule { body: Some(b), .. } if b.text == "=");
        self.diags.push(if eq_body {
            d.with_help("write the rule without blanks around `=`, e.g. `x=-FX`")
        } else {
            d.with_help(
                "strings cannot contain blanks: remove them, or comment the rest out with `;`",
            )
        });
    }

    /// Reports an entry without an axiom or an angle.
    fn check_complete(&mut self, entry: &Entry, lines: &Lines<'_>) {
        for (seen, code, what, keyword, help) in [
            (
                lines.axiom_seen,
                codes::FR_NO_AXIOM,
                "axiom",
                "Axiom",
                "add a line `Axiom STRING`, the word the derivation starts from",
            ),
            (
                lines.angle_seen,
                codes::FR_BAD_ANGLE,
                "angle",
                "Angle",
                "add a line `Angle n` (n from 3 to 50: turns of 360/n degrees)",
            ),
        ] {
            if !seen {
                self.diags.push(
                    Diagnostic::at(
                        code,
                        entry.name_span.clone(),
                        format!("the entry `{}` has no {what}", entry.name),
                    )
                    .with_label(format!("no `{keyword}` line in this entry"))
                    .with_help(help),
                );
            }
        }
    }

    /// The productions of the rules: bodies in file order, rules for one
    /// character concatenated.
    fn productions(&mut self, rules: &[(&str, Span, Option<&Body>)]) {
        let mut heads: Vec<(&str, Span, Vec<SymbolId>, Vec<Span>)> = Vec::new();
        for (head, span, body) in rules {
            let (w, spans) = match body {
                Some(b) => self.word(b),
                None => (Word::default(), Vec::new()),
            };
            match heads.iter_mut().find(|h| h.0 == *head) {
                Some(h) => {
                    h.2.extend(w.0);
                    h.3.extend(spans);
                    h.1 = h.1.start.min(span.start)..h.1.end.max(span.end);
                }
                None => heads.push((head, span.clone(), w.0, spans)),
            }
        }
        for (head, span, succ, succ_spans) in heads {
            self.add_production(head, &span, succ, succ_spans);
        }
    }

    /// The production of one head. A reserved head (Fractint ≤ 16)
    /// rewrites every command it starts.
    fn add_production(
        &mut self,
        head: &str,
        span: &Span,
        succ: Vec<SymbolId>,
        succ_spans: Vec<Span>,
    ) {
        let preds: Vec<SymbolId> = if RESERVED.contains(head) {
            self.sys
                .symbols
                .iter()
                .filter(|(_, i)| i.name.starts_with(head))
                .map(|(id, _)| id)
                .collect()
        } else {
            vec![self.sys.intern(head)]
        };
        for p in preds {
            self.spans.symbols.entry(p).or_insert_with(|| span.clone());
            self.sys.productions.push(Production::new(
                Vec::new(),
                vec![p],
                Vec::new(),
                vec![Alternative::new(1.0, Word::from(succ.clone()))],
            ));
            self.spans.productions.push(span.clone());
            self.spans.successors.push(vec![succ_spans.clone()]);
        }
    }

    /// Gives every command its turtle meaning (`n` increments per turn).
    fn interpret_commands(&mut self, n: u32) {
        let names: Vec<(SymbolId, String)> = self
            .sys
            .symbols
            .iter()
            .map(|(id, i)| (id, i.name.clone()))
            .collect();
        for (id, name) in names {
            if id == SymbolId::OPEN || id == SymbolId::CLOSE {
                continue;
            }
            if let Some(op) = fractint_op(&name, n) {
                self.sys.set_interpretation(id, op);
            }
        }
    }
}

/// Lowers one entry. The system is usable only when `diags` got no error.
pub fn lower_entry(entry: &Entry, diags: &mut Diagnostics) -> Lowered {
    let mut cx = Cx {
        sys: System::new(),
        spans: SpanTable::default(),
        diags,
    };
    let lines = cx.read_lines(entry);
    cx.check_complete(entry, &lines);
    let n = lines.angle.unwrap_or(4);
    cx.sys.settings.delta = (360.0 / f64::from(n)).to_radians();
    cx.sys.settings.steps = Some(DEFAULT_ORDER);
    cx.sys.settings.colour = DEFAULT_COLOUR;
    cx.sys.colours = palette();
    if let Some(b) = lines.axiom {
        let (w, spans) = cx.word(b);
        cx.sys.axiom = w;
        cx.spans.axiom = spans;
    }
    cx.productions(&lines.rules);
    cx.interpret_commands(n);
    Lowered {
        system: cx.sys,
        spans: cx.spans,
    }
}

fn capitalised(k: &str) -> String {
    let mut c = k.chars();
    c.next()
        .map(|f| f.to_ascii_uppercase().to_string() + c.as_str())
        .unwrap_or_default()
}

/// C's `atoi`: optional sign, digits; anything else ends it; 0 when none.
fn atoi(s: &str) -> i64 {
    let (neg, digits) = match s.strip_prefix('-') {
        Some(r) => (true, r),
        None => (false, s.strip_prefix('+').unwrap_or(s)),
    };
    let mut v: i64 = 0;
    for c in digits.chars().take_while(char::is_ascii_digit) {
        v = v
            .saturating_mul(10)
            .saturating_add(i64::from(c as u8 - b'0'));
    }
    if neg {
        -v
    } else {
        v
    }
}
