//! Lowering a Smith file to the IR.
//!
//! Smith's semantics (1984, "Algorithmic plants"): a symbol's left
//! neighbour is the 0 or 1 just left of it, across a branch's `[` and
//! skipping earlier sibling branches; its right neighbour is the next 0 or
//! 1 at the same level, skipping branches; where there is none (the start
//! of the word, a `]`, the end) the neighbour is an invisible 1. The IR's
//! context matching ([`crate::ir`]) moves the same way, except that a
//! missing neighbour matches only an empty context. So each symbol gets
//! nine productions in first-match order: the four with both neighbours,
//! then left only (reached only when there is no right neighbour: read as
//! an invisible 1), right only (no left neighbour), and neither. Nothing
//! had to be added to the IR.
//!
//! For drawing, each `[` of an image is followed by a turn symbol (`+`, or
//! `-` for every other branch of the image when `alternate`), and `/` (a
//! roll about the heading, for 3D) when `roll` is not 0; each `]` and the
//! end of the axiom are preceded by a leaf `@`. These symbols are never
//! rewritten and the context filter skips them, so the derivation is
//! Smith's, and a branch's angle, chosen when the branch is born, stays
//! with it ("nailed") in every later generation.

use super::ast::{Entry, File};
use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use crate::front::suggest::Suggester;
use crate::ir::{
    Alternative, Angle, Axis, ContextFilter, Lowered, Production, Span, SpanTable, SymbolId,
    System, TurtleOp, Word, MAX_NESTING,
};

/// The keys a Smith file may give.
pub const KEYS: [&str; 12] = [
    "rules",
    "axiom",
    "generations",
    "angle",
    "alternate",
    "angles",
    "roll",
    "length",
    "width",
    "leaf",
    "leaf-size",
    "flower-size",
];

/// The symbols added for drawing, which the context filter skips (and
/// `a0`, `a1`, … for the turns of an `angles:` list).
pub const DRAWING_SYMBOLS: [&str; 6] = ["+", "-", "/", "@", "'", "#"];

/// What is drawn at a branch end.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Leaf {
    Disc,
    Flower,
    None,
}

/// Gene's settings, with their defaults.
#[derive(Clone, Debug, PartialEq)]
pub struct Gene {
    pub angle: f64,
    pub alternate: bool,
    /// Gene's "finite set of angles" (degrees): the j-th branch written in
    /// the rule string turns by the j-th (cyclically); replaces `angle`
    /// and `alternate` when given.
    pub angles: Vec<f64>,
    pub roll: f64,
    pub length: f64,
    /// The stem width (pixels).
    pub width: f64,
    pub leaf: Leaf,
    /// The diameters (pixels) of a leaf disc and of a flower.
    pub leaf_size: f64,
    pub flower_size: f64,
}

impl Default for Gene {
    fn default() -> Self {
        Gene {
            angle: 22.5,
            alternate: true,
            angles: Vec::new(),
            roll: 0.0,
            length: 1.0,
            width: 1.0,
            leaf: Leaf::Disc,
            leaf_size: 3.0,
            flower_size: 8.0,
        }
    }
}

/// The most angles an `angles:` list may give.
const MAX_ANGLES: usize = 64;

/// One character of an image or the axiom: `0`, `1`, `[` or `]`.
type Chars = Vec<(char, Span)>;

/// Lowers a parsed file; the system is usable only when `diags` got no
/// error.
pub fn lower(file: &File, diags: &mut Diagnostics) -> Lowered {
    let entries = latest_entries(file, diags);
    let mut gene = Gene::default();
    let mut steps = None;
    let mut suggest = Suggester::default();
    for e in &entries {
        read_setting(e, &mut gene, &mut steps, &mut suggest, diags);
    }
    let find = |k: &str| entries.iter().find(|e| e.key == k);
    let images = match find("rules") {
        Some(e) => read_rules(e, diags),
        // After a line that could not be read, the rules may be on it.
        None if diags.has_errors() => None,
        None => {
            diags.push(
                Diagnostic::global(codes::SMITH_NO_RULES, "no `rules:` line")
                    .with_help("add the eight images, e.g. `rules: 0.1[1].1.1.0.11.1.0`"),
            );
            None
        }
    };
    let axiom = match find("axiom") {
        Some(e) => read_axiom(e, diags),
        None => vec![('1', 0..0)],
    };
    let mut sys = System::new();
    let mut spans = SpanTable::default();
    let syms = Symbols::new(&mut sys, &gene);
    sys.settings.steps = steps;
    sys.settings.delta = gene.angle.to_radians();
    sys.settings.step = gene.length;
    let (word, axiom_spans) = syms.word(&axiom, true, 0);
    sys.axiom = word;
    spans.axiom = axiom_spans;
    if let Some(images) = images {
        // With an `angles:` list, branches are numbered across the images.
        let mut first = [0; 8];
        for t in 1..8 {
            let branches = images[t - 1].0.iter().filter(|c| c.0 == '[').count();
            first[t] = first[t - 1] + branches * usize::from(!gene.angles.is_empty());
        }
        for s in 0..2 {
            for (left, right, triple) in order(s) {
                let (succ, succ_spans) = syms.word(&images[triple].0, false, first[triple]);
                let ctx = |c: Option<usize>| c.map(|b| vec![syms.bit[b]]).unwrap_or_default();
                sys.productions.push(Production::new(
                    ctx(left),
                    vec![syms.bit[s]],
                    ctx(right),
                    vec![Alternative::new(1.0, succ)],
                ));
                spans.productions.push(images[triple].1.clone());
                spans.successors.push(vec![succ_spans]);
            }
        }
    }
    Lowered { system: sys, spans }
}

/// The nine productions of symbol `s` in first-match order: (left
/// context, right context, index of the triple whose image it uses). A
/// missing context is an invisible 1.
fn order(s: usize) -> Vec<(Option<usize>, Option<usize>, usize)> {
    let both = (0..4).map(|k| (Some(k / 2), Some(k % 2)));
    let left = (0..2).map(|l| (Some(l), None));
    let right = (0..2).map(|r| (None, Some(r)));
    both.chain(left)
        .chain(right)
        .chain(std::iter::once((None, None)))
        .map(|(l, r)| (l, r, 4 * l.unwrap_or(1) + 2 * s + r.unwrap_or(1)))
        .collect()
}

/// The entries with each key's last value (a repeated key is warned of).
fn latest_entries<'f>(file: &'f File, diags: &mut Diagnostics) -> Vec<&'f Entry> {
    let mut out: Vec<&Entry> = Vec::new();
    for e in &file.entries {
        if let Some(i) = out.iter().position(|o| o.key == e.key) {
            diags.push(
                Diagnostic::at(
                    codes::SMITH_DUPLICATE_KEY,
                    e.key_span.clone(),
                    format!("`{}` is given twice", e.key),
                )
                .with_secondary(out[i].key_span.clone(), "first given here")
                .with_help("remove one of them; the last one counts"),
            );
            out[i] = e;
        } else {
            out.push(e);
        }
    }
    out
}

fn read_setting(
    e: &Entry,
    gene: &mut Gene,
    steps: &mut Option<u64>,
    suggest: &mut Suggester,
    diags: &mut Diagnostics,
) {
    let bad = |diags: &mut Diagnostics, what: &str| {
        diags.push(
            Diagnostic::at(
                codes::SMITH_BAD_VALUE,
                e.value_span.clone(),
                format!("`{}` must be {what}", e.key),
            )
            .with_label(format!("`{}` is not {what}", e.value))
            .with_help(format!("write `{}: ` and {what}", e.key)),
        )
    };
    let number = |v: &str| v.parse::<f64>().ok().filter(|x| x.is_finite());
    match e.key.as_str() {
        "rules" | "axiom" => {}
        "generations" => match e.value.parse::<u64>() {
            Ok(n) => *steps = Some(n),
            Err(_) => bad(diags, "a whole number"),
        },
        "angle" | "roll" | "length" => match number(&e.value) {
            Some(x) if e.key == "angle" => gene.angle = x,
            Some(x) if e.key == "roll" => gene.roll = x,
            Some(x) => gene.length = x,
            None => bad(diags, "a number"),
        },
        "width" | "leaf-size" | "flower-size" => match number(&e.value).filter(|x| *x > 0.0) {
            Some(x) if e.key == "width" => gene.width = x,
            Some(x) if e.key == "leaf-size" => gene.leaf_size = x,
            Some(x) => gene.flower_size = x,
            None => bad(diags, "a number above 0"),
        },
        "angles" => {
            let list: Option<Vec<f64>> = e
                .value
                .split(|c: char| c == ',' || c.is_whitespace())
                .filter(|v| !v.is_empty())
                .map(number)
                .collect();
            match list.filter(|l| !l.is_empty() && l.len() <= MAX_ANGLES) {
                Some(l) => gene.angles = l,
                None => bad(diags, "a list of 1 to 64 numbers"),
            }
        }
        "alternate" => match e.value.to_ascii_lowercase().as_str() {
            "yes" | "true" | "on" => gene.alternate = true,
            "no" | "false" | "off" => gene.alternate = false,
            _ => bad(diags, "yes or no"),
        },
        "leaf" => match e.value.to_ascii_lowercase().as_str() {
            "disc" => gene.leaf = Leaf::Disc,
            "flower" => gene.leaf = Leaf::Flower,
            "none" => gene.leaf = Leaf::None,
            _ => bad(diags, "disc, flower or none"),
        },
        _ => unknown_key(e, suggest, diags),
    }
}

fn unknown_key(e: &Entry, suggest: &mut Suggester, diags: &mut Diagnostics) {
    let mut d = Diagnostic::at(
        codes::SMITH_UNKNOWN_KEY,
        e.key_span.clone(),
        format!("unknown key `{}`", e.key),
    )
    .with_label("ignored");
    d = match suggest.nearest(&e.key, &KEYS).first() {
        Some(k) => d.suggesting(k),
        None => d.with_help(format!("the keys are {}", KEYS.join(", "))),
    };
    diags.push(d);
}

/// The characters of `text` (at `start` in the file), with spans; each
/// run of characters other than 0 1 [ ] is reported once with `code`.
fn chars(
    text: &str,
    start: usize,
    code: crate::diagnostics::Code,
    diags: &mut Diagnostics,
) -> Chars {
    let mut out = Vec::new();
    let mut bad: Option<Span> = None;
    let flush = |bad: &mut Option<Span>, diags: &mut Diagnostics| {
        if let Some(span) = bad.take() {
            let what = &text[span.start - start..span.end - start];
            diags.push(
                Diagnostic::at(code, span, format!("`{what}` is not 0, 1, [ or ]"))
                    .with_label("not a symbol of Smith's systems")
                    .with_help("Smith's systems are over 0 and 1, with [ ] for branches"),
            );
        }
    };
    for (off, c) in text.char_indices() {
        let span = start + off..start + off + c.len_utf8();
        if matches!(c, '0' | '1' | '[' | ']') {
            flush(&mut bad, diags);
            out.push((c, span));
        } else if !c.is_whitespace() {
            bad = Some(bad.map_or(span.clone(), |b| b.start..span.end));
        } else {
            flush(&mut bad, diags);
        }
    }
    flush(&mut bad, diags);
    out
}

/// Reports the first unbalanced bracket of `chars` with `code`; whether
/// they balance.
fn balanced(chars: &Chars, code: crate::diagnostics::Code, diags: &mut Diagnostics) -> bool {
    let mut open: Vec<&Span> = Vec::new();
    for (c, span) in chars {
        match c {
            '[' if open.len() == MAX_NESTING => {
                diags.push(
                    Diagnostic::at(codes::NESTED_TOO_DEEPLY, span.clone(), "nested too deeply")
                        .with_label(format!("branch {} deep", MAX_NESTING + 1))
                        .with_help(format!("nest branches at most {MAX_NESTING} deep")),
                );
                return false;
            }
            '[' => open.push(span),
            ']' if open.pop().is_none() => {
                diags.push(
                    Diagnostic::at(code, span.clone(), "`]` without a `[` before it")
                        .with_label("closes no branch")
                        .with_help("open the branch with `[` or remove this `]`"),
                );
                return false;
            }
            _ => {}
        }
    }
    if let Some(span) = open.first() {
        diags.push(
            Diagnostic::at(code, (*span).clone(), "`[` is never closed")
                .with_label("this branch has no `]`")
                .with_help("close the branch with `]`"),
        );
        return false;
    }
    true
}

/// The eight images of a rule string with their spans, or `None` after
/// reporting what is wrong.
fn read_rules(e: &Entry, diags: &mut Diagnostics) -> Option<Vec<(Chars, Span)>> {
    let mut images = Vec::new();
    let mut start = e.value_span.start;
    for part in e.value.split('.') {
        images.push((part, start..start + part.len()));
        start += part.len() + 1;
    }
    if images.len() != 8 {
        diags.push(
            Diagnostic::at(
                codes::SMITH_IMAGE_COUNT,
                e.value_span.clone(),
                format!("{} images where Smith writes eight", images.len()),
            )
            .with_label(format!("{} dots", images.len() - 1))
            .with_help("write the images of 000, 001, …, 111 in order, separated by seven dots"),
        );
        return None;
    }
    let mut ok = true;
    let mut out = Vec::new();
    for (text, span) in images {
        let before = diags.len();
        let cs = chars(text, span.start, codes::SMITH_BAD_SYMBOL, diags);
        ok &= diags.len() == before && balanced(&cs, codes::SMITH_UNBALANCED, diags);
        if !cs.iter().any(|(c, _)| matches!(c, '0' | '1')) && diags.len() == before {
            diags.push(
                Diagnostic::at(codes::SMITH_EMPTY_IMAGE, span.clone(), "an empty image")
                    .with_label("erases the symbol")
                    .with_help("write at least one 0 or 1 (the symbol itself leaves it unchanged)"),
            );
            ok = false;
        }
        out.push((cs, span));
    }
    ok.then_some(out)
}

fn read_axiom(e: &Entry, diags: &mut Diagnostics) -> Chars {
    let before = diags.len();
    let cs = chars(&e.value, e.value_span.start, codes::SMITH_BAD_AXIOM, diags);
    if diags.len() == before
        && balanced(&cs, codes::SMITH_BAD_AXIOM, diags)
        && !cs.iter().any(|(c, _)| matches!(c, '0' | '1'))
    {
        diags.push(
            Diagnostic::at(
                codes::SMITH_BAD_AXIOM,
                e.value_span.clone(),
                "the axiom has no 0 or 1",
            )
            .with_label("nothing to rewrite")
            .with_help("give a word over 0 and 1, usually `axiom: 1`"),
        );
    }
    cs
}

/// The IR symbols of a Smith system and how its characters become words.
struct Symbols {
    bit: [SymbolId; 2],
    /// The turns of branches 0, 1, 2, … (cyclically).
    turn: Vec<SymbolId>,
    roll: Option<SymbolId>,
    /// What is drawn at a branch end, in order (colour, size, disc).
    leaf: Vec<SymbolId>,
}

impl Symbols {
    fn new(sys: &mut System, gene: &Gene) -> Self {
        let bit = [sys.intern("0"), sys.intern("1")];
        for b in bit {
            sys.set_interpretation(b, TurtleOp::Forward { draw: true });
        }
        let op = |sys: &mut System, name: &str, op: TurtleOp| {
            let id = sys.intern(name);
            sys.set_interpretation(id, op);
            id
        };
        let turn_by = |angle| TurtleOp::Rotate {
            axis: Axis::Up,
            angle,
        };
        let turn = if gene.angles.is_empty() {
            let both = [("+", 1.0), ("-", -1.0)];
            let sides = if gene.alternate {
                &both[..]
            } else {
                &both[..1]
            };
            sides
                .iter()
                .map(|&(name, sign)| op(sys, name, turn_by(Angle::Delta(sign))))
                .collect()
        } else {
            (gene.angles.iter().enumerate())
                .map(|(k, a)| {
                    op(
                        sys,
                        &format!("a{k}"),
                        turn_by(Angle::Radians(a.to_radians())),
                    )
                })
                .collect::<Vec<_>>()
        };
        let roll = (gene.roll != 0.0).then(|| {
            let angle = Angle::Radians(gene.roll.to_radians());
            op(
                sys,
                "/",
                TurtleOp::Rotate {
                    axis: Axis::Heading,
                    angle,
                },
            )
        });
        sys.settings.width = gene.width;
        // A leaf or flower: the stem width grown to its size (`#`, undone
        // by the `]` that follows), then a disc; a flower in the palette's
        // next colour (the pfg palette, so that a translation to pfg
        // keeps its words).
        let mut leaf = Vec::new();
        let size = match gene.leaf {
            Leaf::Disc => Some(gene.leaf_size),
            Leaf::Flower => {
                leaf.push(op(sys, "'", TurtleOp::NextColour));
                Some(gene.flower_size)
            }
            Leaf::None => None,
        };
        if let Some(size) = size {
            sys.settings.width_step = size - gene.width;
            leaf.push(op(sys, "#", TurtleOp::LineWidth { up: true }));
            leaf.push(op(sys, "@", TurtleOp::Sphere));
        }
        let mut ignored: Vec<SymbolId> = turn.clone();
        ignored.extend(roll.iter().chain(&leaf));
        sys.context = ContextFilter::Ignore(ignored);
        Symbols {
            bit,
            turn,
            roll,
            leaf,
        }
    }

    /// The word of `chars` with the drawing symbols added (a leaf at the
    /// end when `axiom`), and a span per module.
    /// Branches are numbered from `first` (for the turn each gets).
    fn word(&self, chars: &Chars, axiom: bool, first: usize) -> (Word, Vec<Span>) {
        let mut ids = Vec::new();
        let mut spans = Vec::new();
        let mut branch = first;
        let mut push = |id: SymbolId, span: &Span| {
            ids.push(id);
            spans.push(span.clone());
        };
        for (c, span) in chars {
            match c {
                '0' | '1' => push(self.bit[(*c == '1') as usize], span),
                '[' => {
                    push(SymbolId::OPEN, span);
                    push(self.turn[branch % self.turn.len()], span);
                    if let Some(r) = self.roll {
                        push(r, span);
                    }
                    branch += 1;
                }
                _ => {
                    self.leaf_at(span, &mut push);
                    push(SymbolId::CLOSE, span);
                }
            }
        }
        if let (true, Some((_, last))) = (axiom, chars.last()) {
            self.leaf_at(last, &mut push);
        }
        (Word::from(ids), spans)
    }

    /// The leaf (or flower) at a branch end.
    fn leaf_at(&self, span: &Span, push: &mut impl FnMut(SymbolId, &Span)) {
        for &s in &self.leaf {
            push(s, span);
        }
    }
}
