//! Lowering a `.gft` syntax tree to the IR (docs/gft.md): declarations
//! first (the turtle set, `NAME = OPERATION`, `symbol`, `silent`,
//! rotations), so that words split by the longest declared name; then
//! settings, the program, the axiom and the productions.

use super::ast::{self, Arg, Block, Expr as AExpr, ExprKind, File, Item, Keyword, Piece};
use crate::common::vocabulary::{self, TurtleSet};
use crate::diagnostics::{codes, Code, Diagnostic, Diagnostics};
use crate::front::repeats::push_lazily;
use crate::front::suggest::Suggester;
use crate::ir::program::{ArrayDecl, BinOp, Expr, Place, Stmt, UnOp, Var, BUILTINS};
use crate::ir::{
    Alternative, Angle, Axis, ContextFilter, Formals, Lowered, Production, Rgb, Rotation,
    RotationId, RulePolicy, Span, SpanTable, SymbolId, System, TurtleOp, Word,
};
use std::collections::HashMap;

mod items;
mod structure;

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
    let mut cx = Cx {
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
    // A structure's seed gives the axiom.
    if keyword("axiom").next().is_none() && cx.sys.structure.is_none() {
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

/// The operations without arguments (docs/gft.md §3).
const SIMPLE_OPERATIONS: &[(&str, TurtleOp)] = &[
    ("forward", TurtleOp::Forward { draw: true }),
    ("move", TurtleOp::Forward { draw: false }),
    ("turn-around", TurtleOp::TurnAround),
    ("push", TurtleOp::Push),
    ("pop", TurtleOp::Pop),
    ("polygon-begin", TurtleOp::PolygonBegin),
    ("polygon-end", TurtleOp::PolygonEnd),
    ("vertex", TurtleOp::PolygonVertex),
    ("scale-width", TurtleOp::DecrementWidth),
    ("next-colour", TurtleOp::NextColour),
    ("previous-colour", TurtleOp::PreviousColour),
    ("swap-turns", TurtleOp::SwapTurns),
    ("colour-up", TurtleOp::ColourIndex { up: true }),
    ("colour-down", TurtleOp::ColourIndex { up: false }),
    ("width-up", TurtleOp::LineWidth { up: true }),
    ("width-down", TurtleOp::LineWidth { up: false }),
    ("sphere", TurtleOp::Sphere),
    ("disc", TurtleOp::ScreenDisc),
    ("circle", TurtleOp::Circle),
    ("move-to", TurtleOp::MoveTo),
    ("set-heading", TurtleOp::SetHeading),
    ("roll-to-vertical", TurtleOp::RollToVertical),
    ("cylinder-start", TurtleOp::CylinderStart),
    ("cylinder-point", TurtleOp::CylinderPoint { end: false }),
    ("cylinder-end", TurtleOp::CylinderPoint { end: true }),
    ("cylinder-tangents", TurtleOp::CylinderTangents),
    ("radius-tangents", TurtleOp::RadiusTangents),
    ("set-contour", TurtleOp::SetContour),
    ("forward-real", TurtleOp::ForwardReal { draw: true }),
    ("move-real", TurtleOp::ForwardReal { draw: false }),
    ("untwist", TurtleOp::Untwist),
    ("keep-twist", TurtleOp::KeepTwist),
];

/// The operations that take arguments.
const PARAMETRISED_OPERATIONS: &[&str] = &[
    "turn",
    "pitch",
    "roll",
    "turn-unswapped",
    "turn-real",
    "frenet",
    "scale-length",
    "stem",
    "set-colour",
    "nothing",
    "query",
    "colour-shift",
    "elasticity",
    "surface",
];

fn simple_op(name: &str) -> Option<TurtleOp> {
    SIMPLE_OPERATIONS.iter().find(|o| o.0 == name).map(|o| o.1)
}

impl Cx<'_> {
    fn turtle(&mut self, k: &Keyword) {
        let name = k
            .args
            .first()
            .map(|a| a.text().to_string())
            .unwrap_or_default();
        match TurtleSet::from_name(&name) {
            Some(set) => self.set = set,
            None => {
                let span = k.args.first().map_or(k.span.clone(), |a| a.span().clone());
                let sets: Vec<&str> = TurtleSet::ALL.iter().map(|s| s.name()).collect();
                let help = match self.suggester.nearest(&name, &sets).first() {
                    Some(n) => format!("did you mean `{n}`?"),
                    None => "the sets are `pfg`, `linf`, `stl`, `cpfg`, `fractint` and `none`"
                        .to_string(),
                };
                self.diags.push(err(
                    codes::GFT_UNKNOWN_OPERATION,
                    &span,
                    format!("unknown turtle set `{name}`"),
                    "not a turtle set",
                    &help,
                ));
            }
        }
    }

    /// Gives the set's symbols their meaning and their names to words.
    fn give_set(&mut self) {
        // Fractint's commands get their meaning where they are used, with
        // the file's angle (`|` turns by half a turn's increments), as the
        // Fractint front end gives them: see `declare_use`.
        if self.set == TurtleSet::Fractint {
            return;
        }
        for name in self.set.names() {
            if let Some(op) = vocabulary::op(self.set, name) {
                let id = self.sys.intern(name);
                self.sys.set_interpretation(id, op);
            }
            self.names.add(name);
        }
    }

    fn declare(&mut self, name: &str, span: &Span) -> SymbolId {
        if name.chars().count() > 1 {
            self.names.add(name);
        }
        let id = self.sys.intern(name);
        self.spans.symbols.entry(id).or_insert_with(|| span.clone());
        id
    }

    /// An angle: `delta`, `-delta`, `2.5*delta`, `30deg`, `0.5rad`.
    fn angle(&mut self, text: &str, span: &Span) -> Option<Angle> {
        let bad = |cx: &mut Self| {
            cx.diags.push(err(
                codes::GFT_BAD_VALUE,
                span,
                format!("`{text}` is not an angle"),
                "not an angle",
                "write `delta`, `-delta`, `2*delta`, `30deg` or `0.5rad`",
            ));
            None
        };
        if let Some(f) = text.strip_suffix("delta") {
            let f = f.strip_suffix('*').unwrap_or(f);
            return match f {
                "" => Some(Angle::Delta(1.0)),
                "-" => Some(Angle::Delta(-1.0)),
                f => f.parse().ok().map(Angle::Delta).or_else(|| bad(self)),
            };
        }
        let (num, deg) = match (text.strip_suffix("deg"), text.strip_suffix("rad")) {
            (Some(n), _) => (n, true),
            (_, Some(n)) => (n, false),
            _ => (text, false),
        };
        match num.parse::<f64>() {
            Ok(v) if v.is_finite() => Some(Angle::Radians(if deg { v.to_radians() } else { v })),
            _ => bad(self),
        }
    }

    /// `silent KEY = OPERATION`: a symbol with an empty name under `KEY`.
    fn silent(&mut self, k: &Keyword) {
        let eq = k.args.iter().position(|a| a.text() == "=");
        let key = groups(&k.args[..eq.unwrap_or(0)]);
        match (eq, key.as_slice()) {
            (Some(eq), [(key, span)]) if eq + 1 < k.args.len() => {
                let key = key.trim_matches('`');
                let id = self.sys.intern_silent(key);
                self.spans.symbols.entry(id).or_insert_with(|| span.clone());
                let rest = &k.args[eq + 1..];
                let op_span = rest[0].span().start..rest[rest.len() - 1].span().end;
                self.define_op(id, rest, &op_span);
            }
            _ => self.diags.push(err(
                codes::GFT_BAD_VALUE,
                &k.line,
                "malformed `silent`",
                "not `silent KEY = OPERATION`",
                "write e.g. `silent s1 = stem 8 40`",
            )),
        }
    }

    fn define(&mut self, name: &str, span: &Span, op: &[Arg], op_span: &Span) {
        let id = self.declare(name, span);
        self.define_op(id, op, op_span);
    }

    fn define_op(&mut self, id: SymbolId, op: &[Arg], op_span: &Span) {
        let g = groups(op);
        let Some((head, _)) = g.first() else { return };
        let arg = |k: usize| g.get(k).cloned();
        let number = |cx: &mut Self, k: usize| -> Option<f64> {
            let (t, s) = arg(k).unwrap_or_default();
            match t.parse::<f64>() {
                Ok(v) => Some(v),
                Err(_) => {
                    let s = if t.is_empty() { op_span.clone() } else { s };
                    cx.diags.push(err(
                        codes::GFT_BAD_VALUE,
                        &s,
                        format!("`{head}` takes a number"),
                        "not a number",
                        "write a number, e.g. `0.5`",
                    ));
                    None
                }
            }
        };
        let angle = |cx: &mut Self, k: usize| -> Option<Angle> {
            let (t, s) = arg(k).unwrap_or_else(|| (String::new(), op_span.clone()));
            cx.angle(&t, &s)
        };
        let op = match head.as_str() {
            "turn" => angle(self, 1).map(|angle| TurtleOp::Rotate {
                axis: Axis::Up,
                angle,
            }),
            "pitch" => angle(self, 1).map(|angle| TurtleOp::Rotate {
                axis: Axis::Left,
                angle,
            }),
            "roll" => angle(self, 1).map(|angle| TurtleOp::Rotate {
                axis: Axis::Heading,
                angle,
            }),
            "turn-unswapped" => angle(self, 1).map(TurtleOp::TurnUnswapped),
            "turn-real" => angle(self, 1).map(TurtleOp::RotateReal),
            "frenet" => self.frenet(arg(1), op_span),
            "scale-length" => number(self, 1).map(TurtleOp::ScaleLength),
            "stem" => number(self, 1)
                .zip(number(self, 2))
                .map(|(width, length)| TurtleOp::Stem { width, length }),
            "set-colour" => {
                number(self, 1).map(|v| TurtleOp::SetColour(v.clamp(0.0, u32::MAX as f64) as u32))
            }
            "nothing" => {
                if let Some(slot) = self.sys.interpretation.get_mut(id.index()) {
                    *slot = None;
                }
                None
            }
            "query" | "colour-shift" | "elasticity" | "surface" => self.named_op(&g, op_span),
            other if simple_op(other).is_some() => simple_op(other),
            other => {
                let names: Vec<&str> = SIMPLE_OPERATIONS
                    .iter()
                    .map(|o| o.0)
                    .chain(PARAMETRISED_OPERATIONS.iter().copied())
                    .collect();
                let near = self.suggester.nearest(other, &names);
                let d = Diagnostic::at(
                    codes::GFT_UNKNOWN_OPERATION,
                    g[0].1.clone(),
                    format!("unknown operation `{other}`"),
                )
                .with_label("not a turtle operation");
                self.diags.push(match near.first() {
                    Some(n) => d.suggesting(n),
                    None => d.with_help("docs/gft.md §3 lists the operations"),
                });
                None
            }
        };
        if let Some(op) = op {
            self.sys.set_interpretation(id, op);
        }
    }

    fn frenet(&mut self, arg: Option<(String, Span)>, span: &Span) -> Option<TurtleOp> {
        let (text, s) = arg.unwrap_or_else(|| (String::new(), span.clone()));
        let (negate, name) = match text.strip_prefix('-') {
            Some(n) => (true, n),
            None => (false, text.as_str()),
        };
        let name = if name == "default" { "" } else { name };
        match self.sys.rotations.iter().position(|r| r.name == name) {
            Some(i) => Some(TurtleOp::Frenet {
                rotation: RotationId(i as u32),
                negate,
            }),
            None => {
                let declared: Vec<&str> = (self.sys.rotations.iter())
                    .map(|r| r.name.as_str())
                    .filter(|n| !n.is_empty())
                    .collect();
                let help = match self.suggester.nearest(name, &declared).first() {
                    Some(n) => format!("did you mean `{n}`?"),
                    None => "declare it: `rotation t = (0, pi/3)`".to_string(),
                };
                self.diags.push(err(
                    codes::GFT_UNKNOWN_NAME,
                    &s,
                    format!("no rotation `{name}`"),
                    "not declared with `rotation`",
                    &help,
                ));
                None
            }
        }
    }

    /// `rotation [NAME] = (TORSION, CURVATURE)`.
    fn rotation(&mut self, k: &Keyword) {
        let name = match k.args.first() {
            Some(Arg::Word(n, _)) => n.clone(),
            _ => String::new(),
        };
        let inner: Vec<&Arg> = k
            .args
            .iter()
            .skip_while(|a| a.text() != "(")
            .skip(1)
            .collect();
        let parts: Vec<Vec<&Arg>> = inner
            .split(|a| a.text() == ",")
            .map(|p| p.iter().copied().filter(|a| a.text() != ")").collect())
            .collect();
        let angles: Vec<Option<Angle>> = parts.iter().map(|p| self.radians(p)).collect();
        match angles.as_slice() {
            [Some(torsion), Some(curvature)] => self.sys.rotations.push(Rotation {
                name,
                torsion: *torsion,
                curvature: *curvature,
            }),
            _ => self.diags.push(err(
                codes::GFT_BAD_VALUE,
                &k.line,
                "malformed rotation",
                "not `rotation NAME = (TORSION, CURVATURE)`",
                "write e.g. `rotation t = (0, pi/3)` or `rotation w = (0, [0 2*pi])`",
            )),
        }
    }

    /// A LinF angle in radians: a constant with `pi`, or `[lo hi]`.
    fn radians(&self, args: &[&Arg]) -> Option<Angle> {
        if args.first().is_some_and(|a| a.text() == "[") {
            let inner: Vec<&Arg> = args[1..]
                .iter()
                .copied()
                .filter(|a| a.text() != "]")
                .collect();
            let g = groups(&inner.iter().map(|a| (*a).clone()).collect::<Vec<_>>());
            let [lo, hi] = g.as_slice() else { return None };
            return Some(Angle::Uniform {
                lo: constant(&lo.0)?,
                hi: constant(&hi.0)?,
            });
        }
        let text: String = args.iter().map(|a| a.text()).collect();
        constant(&text).map(Angle::Radians)
    }
}

/// A constant of numbers, `pi`, `* / + -` (LinF's angles).
fn constant(text: &str) -> Option<f64> {
    if let Some(k) = text.rfind(['+', '-']).filter(|&k| k > 0) {
        let (a, b) = (constant(&text[..k])?, constant(&text[k + 1..])?);
        return Some(if &text[k..=k] == "+" { a + b } else { a - b });
    }
    if let Some(k) = text.rfind(['*', '/']) {
        let (a, b) = (constant(&text[..k])?, constant(&text[k + 1..])?);
        return Some(if &text[k..=k] == "*" { a * b } else { a / b });
    }
    match text {
        "pi" => Some(std::f64::consts::PI),
        "-pi" => Some(-std::f64::consts::PI),
        t => t.parse().ok().filter(|v: &f64| v.is_finite()),
    }
}

/// The names a production binds: its formals, then the names its
/// statements assign.
struct Locals(Vec<String>);

impl Cx<'_> {
    fn once(&mut self, k: &Keyword) -> bool {
        self.once_as(k, &k.name)
    }

    /// Whether `k` is the first item under `key` (else reported, E0905).
    fn once_as(&mut self, k: &Keyword, key: &str) -> bool {
        if let Some(first) = self.settings.get(key) {
            let d = err(
                codes::GFT_DUPLICATE,
                &k.span,
                format!("`{}` given twice", k.name),
                "given again here",
                "remove one of them",
            )
            .with_secondary(first.clone(), "first given here");
            self.diags.push(d);
            return false;
        }
        self.settings.insert(key.to_string(), k.span.clone());
        true
    }

    /// The constant value of a keyword (`angle 360/7`).
    fn value(&mut self, k: &Keyword) -> Option<f64> {
        // A name is not a value here: it gives E0903, not E0906.
        let v = k.value.as_ref().and_then(|e| {
            let saved = std::mem::take(self.diags);
            let v = self.expr(e, &mut Locals(Vec::new())).constant();
            let named = !std::mem::replace(self.diags, saved).is_empty();
            v.filter(|_| !named)
        });
        if v.is_none() {
            self.diags.push(err(
                codes::GFT_BAD_VALUE,
                &k.line,
                format!("`{}` takes a number", k.name),
                "no number here",
                &format!("write e.g. `{} 2`", k.name),
            ));
        }
        v
    }

    fn whole(&mut self, k: &Keyword) -> Option<u64> {
        let v = self.value(k)?;
        if v >= 0.0 && v.fract() == 0.0 && v < u64::MAX as f64 {
            return Some(v as u64);
        }
        self.diags.push(err(
            codes::GFT_BAD_VALUE,
            &k.line,
            format!("`{}` takes a whole number", k.name),
            "not a whole number",
            "write e.g. `4`",
        ));
        None
    }

    fn keyword(&mut self, k: &Keyword) {
        let settings = &mut self.sys.settings;
        let _ = settings;
        let repeated = [
            "symbol", "silent", "rotation", "array", "globals", "rule", "light", "material",
            "surface", "contour", "function", "tropism",
        ];
        if structure::is_structure_seed(k) {
            // Read with the structure; given once like the settings.
            self.once_as(k, "structure seed");
            return;
        }
        if !repeated.contains(&k.name.as_str()) && !self.once(k) || self.look_item(k) {
            return;
        }
        match k.name.as_str() {
            "steps" => self.sys.settings.steps = self.whole(k),
            "seed" => self.sys.settings.seed = self.whole(k),
            "colour" => {
                if let Some(v) = self.whole(k) {
                    self.sys.settings.colour = v as usize;
                }
            }
            "angle" => {
                let rad = k.args.last().is_some_and(|a| a.text() == "rad");
                if let Some(v) = self.value(k) {
                    self.sys.settings.delta = if rad { v } else { v.to_radians() };
                }
            }
            "length" | "scale" | "width" | "width-factor" | "width-step" | "colour-step" => {
                if let Some(v) = self.value(k) {
                    let s = &mut self.sys.settings;
                    *match k.name.as_str() {
                        "length" => &mut s.step,
                        "scale" => &mut s.scale,
                        "width" => &mut s.width,
                        "width-factor" => &mut s.width_factor,
                        "width-step" => &mut s.width_step,
                        _ => &mut s.colour_step,
                    } = v;
                }
            }
            "widths" => {
                self.sys.settings.world_widths = k.args.first().is_some_and(|a| a.text() == "world")
            }
            "view" => self.view(k),
            "choose" => {
                self.sys.policy = match k.args.first().map(Arg::text) {
                    Some("weighted") => RulePolicy::Weighted,
                    _ => RulePolicy::FirstMatch,
                }
            }
            "ring" => self.sys.ring = true,
            "axiom" => self.axiom(k),
            "ignore" | "consider" => {
                let w = k
                    .word
                    .as_ref()
                    .map(|w| self.word(w, &mut Locals(Vec::new())).0);
                let ids = w.map(|w| w.symbols().to_vec()).unwrap_or_default();
                self.sys.context = if k.name == "ignore" {
                    ContextFilter::Ignore(ids)
                } else {
                    ContextFilter::Consider(ids)
                };
            }
            "cut" => {
                let w = k
                    .word
                    .as_ref()
                    .map(|w| self.word(w, &mut Locals(Vec::new())).0);
                self.sys.cut = w.and_then(|w| w.symbols().first().copied());
            }
            "colours" => self.colours(k),
            "decomposition" | "homomorphism" => self.phase(k),
            "start" | "start-each" | "end-each" | "end" => {
                let Some(Block::Statements(s)) = &k.block else {
                    return;
                };
                let s = self.stmts(s, &mut Locals(Vec::new()));
                let p = &mut self.sys.program;
                *match k.name.as_str() {
                    "start" => &mut p.start,
                    "start-each" => &mut p.start_each,
                    "end-each" => &mut p.end_each,
                    _ => &mut p.end,
                } = s;
            }
            _ => {}
        }
    }

    /// `array NAME[D1][D2]… [= V, V, …]` (cpfg's arrays; values row-major).
    fn array(&mut self, k: &Keyword) {
        let g = groups(&k.args);
        let name = k
            .args
            .first()
            .map(|a| a.text().to_string())
            .unwrap_or_default();
        let eq = g.iter().position(|a| a.0 == "=").unwrap_or(g.len());
        let head: String = g[..eq].iter().map(|a| a.0.as_str()).collect();
        let dims: Option<Vec<usize>> = head
            .strip_prefix(name.as_str())
            .map(|d| d.trim_start_matches('[').trim_end_matches(']'))
            .map(|d| d.split("][").map(|n| n.parse().ok()).collect())
            .unwrap_or_default();
        let init: Option<Vec<f64>> = g[(eq + 1).min(g.len())..]
            .iter()
            .map(|a| a.0.trim_end_matches(','))
            .filter(|a| !a.is_empty())
            .map(|a| a.parse().ok())
            .collect();
        let size = dims
            .as_ref()
            .map(|d| d.iter().try_fold(1usize, |n, &x| n.checked_mul(x)));
        match (dims, init, size) {
            (Some(dims), Some(init), Some(Some(n)))
                if !dims.is_empty() && n <= 1 << 20 && init.len() <= n && !name.is_empty() =>
            {
                let id = self.sys.program.arrays.len() as u16;
                self.arrays.insert(name.clone(), (id, dims.len()));
                self.sys.program.arrays.push(ArrayDecl { name, dims, init });
            }
            _ => self.diags.push(err(
                codes::GFT_BAD_VALUE,
                &k.line,
                "malformed array",
                "not `array NAME[N]… = VALUES`",
                "write e.g. `array lengths[3] = 1, 2, 3` (at most 1048576 elements)",
            )),
        }
    }

    fn global(&mut self, name: &str) -> u16 {
        if let Some(&g) = self.globals.get(name) {
            return g;
        }
        let g = self.sys.program.globals.len() as u16;
        self.sys.program.globals.push(name.to_string());
        self.globals.insert(name.to_string(), g);
        g
    }

    fn view(&mut self, k: &Keyword) {
        // A sign is its own token: read the groups (`-0.1`) as numbers.
        let nums: Vec<f64> = groups(&k.args)
            .iter()
            .filter_map(|g| g.0.parse().ok())
            .collect();
        let rad = k.args.last().is_some_and(|a| a.text() == "rad");
        match nums.as_slice() {
            [az, el] if rad => self.sys.settings.view = Some((*az, *el)),
            [az, el] => self.sys.settings.view = Some((az.to_radians(), el.to_radians())),
            _ => self.diags.push(err(
                codes::GFT_BAD_VALUE,
                &k.line,
                "`view` takes two angles",
                "not `view AZIMUTH ELEVATION`",
                "write e.g. `view 30 20`",
            )),
        }
    }

    fn colours(&mut self, k: &Keyword) {
        if let [Arg::Word(w, _)] = k.args.as_slice() {
            if w == "fractint" {
                self.sys.colours = crate::common::palettes::fractint_palette();
                return;
            }
        }
        for a in &k.args {
            let rgb = match a {
                Arg::Colour(c, _) => {
                    let h = |i: usize| u8::from_str_radix(&c[i..i + 2], 16).unwrap_or(0);
                    Some(Rgb(h(1), h(3), h(5)))
                }
                _ => None,
            };
            match rgb {
                Some(c) => self.sys.colours.push(c),
                None => self.diags.push(err(
                    codes::GFT_BAD_VALUE,
                    a.span(),
                    format!("`{}` is not a colour", a.text()),
                    "not `#rrggbb`",
                    "write colours as `#rrggbb`, e.g. `#00a000`",
                )),
            }
        }
    }

    fn phase(&mut self, k: &Keyword) {
        let g = groups(&k.args);
        let mut depth = 0;
        let mut seed = None;
        for pair in g.windows(2) {
            match (pair[0].0.as_str(), pair[1].0.parse::<u64>()) {
                ("depth", Ok(v)) => depth = v.min(u32::MAX as u64) as u32,
                ("seed", Ok(v)) => seed = Some(v),
                _ => {}
            }
        }
        let mut ps = Vec::new();
        if let Some(Block::Productions(list)) = &k.block {
            for p in list {
                ps.extend(self.production(p));
            }
        }
        let phase = if k.name == "decomposition" {
            &mut self.sys.decomposition
        } else {
            &mut self.sys.homomorphism
        };
        phase.productions = ps;
        phase.depth = depth;
        phase.seed = seed;
    }

    fn axiom(&mut self, k: &Keyword) {
        let Some(w) = &k.word else { return };
        let (word, args, spans) = self.word(w, &mut Locals(Vec::new()));
        self.sys.axiom = word;
        self.sys.axiom_args = args;
        self.spans.axiom = spans;
    }

    /// A word's modules, their parameter expressions (empty when none has
    /// any) and spans. Unbalanced brackets are read as written (W0901).
    fn word(&mut self, w: &ast::Word, locals: &mut Locals) -> (Word, Vec<Vec<Expr>>, Vec<Span>) {
        let (word, args, spans) = self.word_unbalanced(w, locals);
        self.balance(w, word.symbols(), &spans);
        (word, args, spans)
    }

    /// A word's modules, parameter expressions and spans, its brackets
    /// unchecked (an STL seed's words open branches that its terms fill).
    fn word_unbalanced(
        &mut self,
        w: &ast::Word,
        locals: &mut Locals,
    ) -> (Word, Vec<Vec<Expr>>, Vec<Span>) {
        let mut ids: Vec<SymbolId> = Vec::new();
        let mut spans: Vec<Span> = Vec::new();
        let mut args: Vec<Vec<Expr>> = Vec::new();
        let mut guard: Option<f64> = None;
        for piece in &w.pieces {
            match piece {
                Piece::Guard(p, _) => guard = Some(*p),
                Piece::Args(list, span) => {
                    if ids.is_empty() {
                        self.diags.push(err(
                            codes::SYNTAX,
                            span,
                            "parameters without a module",
                            "no symbol before `(`",
                            "write the symbol first: `F(1)`",
                        ));
                        continue;
                    }
                    args.resize(ids.len(), Vec::new());
                    let e: Vec<Expr> = list.iter().map(|e| self.expr(e, locals)).collect();
                    *args.last_mut().expect("one per module") = e;
                }
                Piece::Quoted(name, span) => {
                    let id = self.symbol(name, span, guard.take());
                    ids.push(id);
                    spans.push(span.clone());
                }
                Piece::Text(text, span) => {
                    self.misspelt_name(text, span);
                    for (name, s) in self.split(text, span.start) {
                        let id = self.symbol(&name, &s, guard.take());
                        ids.push(id);
                        spans.push(s);
                    }
                }
            }
        }
        // The parameters are expressions beside the word, as cpfg's reader
        // keeps them: the word itself holds symbols only.
        let word = Word::from(ids.clone());
        let has_args = args.iter().any(|a| !a.is_empty());
        if has_args {
            args.resize(ids.len(), Vec::new());
        } else {
            args.clear();
        }
        (word, args, spans)
    }

    /// Warns of a `]` without `[` and an unclosed `[` (W0901): cpfg and
    /// Fractint words may be so, and the IR holds them as written.
    fn balance(&mut self, w: &ast::Word, ids: &[SymbolId], spans: &[Span]) {
        let mut depth = 0i64;
        for (id, s) in ids.iter().zip(spans) {
            depth += i64::from(*id == SymbolId::OPEN) - i64::from(*id == SymbolId::CLOSE);
            if depth < 0 {
                self.diags.push(err(
                    codes::GFT_UNBALANCED_BRACKETS,
                    s,
                    "`]` without `[`",
                    "closes no branch",
                    "remove it unless another word opens its branch",
                ));
                depth = 0;
            }
        }
        if depth > 0 {
            self.diags.push(err(
                codes::GFT_UNBALANCED_BRACKETS,
                &w.span,
                "unclosed `[`",
                "a branch is not closed",
                "close it with `]` unless another word closes it",
            ));
        }
    }

    fn symbol(&mut self, name: &str, span: &Span, guard: Option<f64>) -> SymbolId {
        let id = self.declare_use(name, span);
        match guard {
            Some(p) => {
                let g = self.sys.symbols.intern_guarded(p, id);
                let n = self.sys.symbols.len();
                if self.sys.interpretation.len() < n {
                    self.sys.interpretation.resize(n, None);
                }
                g
            }
            None => id,
        }
    }

    fn declare_use(&mut self, name: &str, span: &Span) -> SymbolId {
        let id = self.sys.intern(name);
        self.spans.symbols.entry(id).or_insert_with(|| span.clone());
        if self.set == TurtleSet::Fractint && self.sys.op(id).is_none() {
            let n = (std::f64::consts::TAU / self.sys.settings.delta).round();
            if let Some(op) = vocabulary::fractint_op(name, n.clamp(0.0, u32::MAX as f64) as u32) {
                self.sys.set_interpretation(id, op);
            }
        }
        id
    }

    /// Warns (W0903) of a run of three or more letters that no declared
    /// name matches, so that it is read one letter a module, when it is
    /// near a name the file declares (`symbol apex`, then `apx`).
    fn misspelt_name(&mut self, text: &str, span: &Span) {
        if text.len() < 3 || !text.chars().all(|c| c.is_ascii_alphabetic()) {
            return;
        }
        if self.names.longest_prefix(text) > 0 {
            return;
        }
        let own: Vec<&str> = (self.names.names.iter())
            .map(String::as_str)
            .filter(|n| !self.set.names().contains(n))
            .collect();
        if own.is_empty() {
            return;
        }
        if let Some(near) = self.suggester.nearest(text, &own).first() {
            let near = near.to_string();
            push_lazily(self.diags, codes::GFT_UNDECLARED_NAME, || {
                err(
                    codes::GFT_UNDECLARED_NAME,
                    span,
                    format!(
                        "`{text}` is no declared name: it is read as {} modules",
                        text.len()
                    ),
                    "one module per letter",
                    &format!("did you mean `{near}`?"),
                )
            });
        }
    }

    /// Splits symbol text by the longest declared name (one character
    /// otherwise; a Fractint command with its number).
    fn split(&self, text: &str, at: usize) -> Vec<(String, Span)> {
        let mut out = Vec::new();
        let mut i = 0;
        while i < text.len() {
            let rest = &text[i..];
            let mut len = self.names.longest_prefix(rest);
            let c = rest.chars().next().expect("not empty");
            if len == 0 && self.set == TurtleSet::Fractint && vocabulary::fractint_takes_number(c) {
                len = c.len_utf8()
                    + rest[c.len_utf8()..]
                        .find(|d: char| !(d.is_ascii_digit() || matches!(d, '.' | 'q' | 'i')))
                        .unwrap_or(rest.len() - c.len_utf8());
            }
            let len = len.max(c.len_utf8());
            out.push((rest[..len].to_string(), at + i..at + i + len));
            i += len;
        }
        out
    }
}

impl Cx<'_> {
    /// A pattern (predecessor or context): symbols, and the slots each
    /// module's parameter names bind.
    fn pattern(&mut self, w: &ast::Word, locals: &mut Locals) -> (Vec<SymbolId>, Vec<Vec<u16>>) {
        let mut ids = Vec::new();
        let mut slots: Vec<Vec<u16>> = Vec::new();
        let plain = ast::Word {
            pieces: w
                .pieces
                .iter()
                .filter(|p| !matches!(p, Piece::Args(..)))
                .cloned()
                .collect(),
            span: w.span.clone(),
        };
        let mut k = 0;
        for piece in &w.pieces {
            match piece {
                Piece::Args(list, _) => {
                    slots.resize(k, Vec::new());
                    if let Some(last) = slots.last_mut() {
                        for e in list {
                            match &e.kind {
                                ExprKind::Name(n) => {
                                    locals.0.push(n.clone());
                                    last.push((locals.0.len() - 1) as u16);
                                }
                                _ => self.diags.push(err(
                                    codes::GFT_PARAMETER_COUNT,
                                    &e.span,
                                    "a value where a parameter name belongs",
                                    "not a name",
                                    "bind a name and test it: `A(x) : x == 1 -> …`",
                                )),
                            }
                        }
                    }
                }
                Piece::Text(..) | Piece::Quoted(..) => {
                    let one = ast::Word {
                        pieces: vec![piece.clone()],
                        span: w.span.clone(),
                    };
                    let n = self.word(&one, &mut Locals(Vec::new())).0.len();
                    k += n;
                }
                Piece::Guard(..) => {}
            }
        }
        let (word, _, _) = self.word(&plain, &mut Locals(Vec::new()));
        ids.extend_from_slice(word.symbols());
        if slots.iter().any(|s| !s.is_empty()) {
            slots.resize(ids.len(), Vec::new());
        } else {
            slots.clear();
        }
        (ids, slots)
    }

    fn production(&mut self, p: &ast::Production) -> Option<Production> {
        let mut locals = Locals(Vec::new());
        let (left, fl) = p
            .left
            .as_ref()
            .map(|w| self.pattern(w, &mut locals))
            .unwrap_or_default();
        let (pred, fp) = self.pattern(&p.predecessor, &mut locals);
        let (right, fr) = p
            .right
            .as_ref()
            .map(|w| self.pattern(w, &mut locals))
            .unwrap_or_default();
        let before = self.stmts(&p.before, &mut locals);
        let condition = p.condition.as_ref().map(|c| self.expr(c, &mut locals));
        let after = self.stmts(&p.after, &mut locals);
        let mut alternatives = Vec::new();
        let mut succ_spans = Vec::new();
        for a in &p.alternatives {
            let (successor, args, spans) = self.word(&a.successor, &mut locals);
            let weight = a.weight.as_ref().map(|w| self.expr(w, &mut locals));
            let (weight, computed) = match weight {
                None => (1.0, None),
                Some(w) => match w.constant() {
                    Some(v) => (v, None),
                    None => (1.0, Some(w)),
                },
            };
            alternatives.push(Alternative {
                weight,
                computed_weight: computed,
                successor,
                args,
            });
            succ_spans.push(spans);
        }
        self.spans.productions.push(p.span.clone());
        self.spans.successors.push(succ_spans);
        let mut prod = Production::new(left, pred, right, alternatives);
        prod.formals = Formals {
            left: fl,
            predecessor: fp,
            right: fr,
            locals: locals.0.len() as u16,
            names: locals.0.clone(),
        };
        if prod.formals.left.is_empty()
            && prod.formals.predecessor.is_empty()
            && prod.formals.right.is_empty()
            && locals.0.is_empty()
        {
            prod.formals = Formals::default();
        }
        prod.before = before;
        prod.condition = condition;
        prod.after = after;
        Some(prod)
    }

    fn stmts(&mut self, list: &[ast::Stmt], locals: &mut Locals) -> Vec<Stmt> {
        list.iter().map(|s| self.stmt(s, locals)).collect()
    }

    fn stmt(&mut self, s: &ast::Stmt, locals: &mut Locals) -> Stmt {
        match s {
            ast::Stmt::Assign {
                name,
                index,
                value,
                span,
            } => {
                let value = self.expr(value, locals);
                let place = if !index.is_empty() {
                    let idx: Vec<Expr> = index.iter().map(|e| self.expr(e, locals)).collect();
                    match self.arrays.get(name) {
                        Some(&(a, _)) => Place::Element(a, idx),
                        None => {
                            self.unknown(name, span);
                            Place::Var(Var::Global(0))
                        }
                    }
                } else if let Some(k) = locals.0.iter().rposition(|l| l == name) {
                    Place::Var(Var::Local(k as u16))
                } else if let Some(&g) = self.globals.get(name) {
                    Place::Var(Var::Global(g))
                } else {
                    locals.0.push(name.clone());
                    Place::Var(Var::Local((locals.0.len() - 1) as u16))
                };
                Stmt::Assign(place, value)
            }
            ast::Stmt::Expr(e) => Stmt::Eval(self.expr(e, locals)),
            ast::Stmt::If(c, a, b) => Stmt::If(
                self.expr(c, locals),
                self.stmts(a, locals),
                self.stmts(b, locals),
            ),
            ast::Stmt::While(c, b) => Stmt::While(self.expr(c, locals), self.stmts(b, locals)),
            ast::Stmt::Do(b, c) => Stmt::Do(self.stmts(b, locals), self.expr(c, locals)),
        }
    }

    fn unknown(&mut self, name: &str, span: &Span) {
        self.diags.push(err(
            codes::GFT_UNKNOWN_NAME,
            span,
            format!("unknown name `{name}`"),
            "not a parameter, local or global",
            "declare a global with `globals NAME` or bind it in the predecessor",
        ));
    }

    fn expr(&mut self, e: &AExpr, locals: &mut Locals) -> Expr {
        match &e.kind {
            ExprKind::Num(v) => Expr::Num(*v),
            ExprKind::Str(s) => Expr::Str(s.clone()),
            ExprKind::Name(n) => {
                if let Some(k) = locals.0.iter().rposition(|l| l == n) {
                    Expr::Var(Var::Local(k as u16))
                } else if let Some(&g) = self.globals.get(n) {
                    Expr::Var(Var::Global(g))
                } else {
                    // As in cpfg: a name never assigned is a local worth 0
                    // (the IR of a cpfg file holds such locals).
                    self.diags.push(
                        Diagnostic::at(
                            codes::GFT_UNASSIGNED,
                            e.span.clone(),
                            format!("`{n}` is never assigned; its value is 0"),
                        )
                        .with_label("not a parameter, local or global")
                        .with_help(
                            "declare a global with `globals NAME` or bind it in the predecessor",
                        ),
                    );
                    locals.0.push(n.clone());
                    Expr::Var(Var::Local((locals.0.len() - 1) as u16))
                }
            }
            ExprKind::Element(n, idx) => {
                let idx: Vec<Expr> = idx.iter().map(|i| self.expr(i, locals)).collect();
                match self.arrays.get(n) {
                    Some(&(a, _)) => Expr::Element(a, idx),
                    None => {
                        self.unknown(n, &e.span);
                        Expr::Num(0.0)
                    }
                }
            }
            ExprKind::Call(n, args) => {
                let args: Vec<Expr> = args.iter().map(|a| self.expr(a, locals)).collect();
                match BUILTINS.iter().find(|b| b.0 == n) {
                    // An empty list of counts means any number (`printf`, `fprintf`, `fscanf`).
                    Some((_, b, counts)) if counts.is_empty() || counts.contains(&args.len()) => {
                        Expr::Call(*b, args)
                    }
                    Some((_, _, counts)) => {
                        self.diags.push(err(
                            codes::GFT_PARAMETER_COUNT,
                            &e.span,
                            format!("`{n}` takes {counts:?} arguments, not {}", args.len()),
                            "wrong number of arguments",
                            "see cpfg's manual §5 for the built-in functions",
                        ));
                        Expr::Num(0.0)
                    }
                    None => {
                        self.unknown(n, &e.span);
                        Expr::Num(0.0)
                    }
                }
            }
            ExprKind::Unary(op, x) => {
                let x = self.expr(x, locals);
                Expr::Unary(if *op == "-" { UnOp::Neg } else { UnOp::Not }, Box::new(x))
            }
            ExprKind::Binary(op, a, b) => {
                let (a, b) = (self.expr(a, locals), self.expr(b, locals));
                let op = match op.as_str() {
                    "||" => BinOp::Or,
                    "&&" => BinOp::And,
                    "==" => BinOp::Eq,
                    "!=" => BinOp::Ne,
                    "<" => BinOp::Lt,
                    "<=" => BinOp::Le,
                    ">" => BinOp::Gt,
                    ">=" => BinOp::Ge,
                    "+" => BinOp::Add,
                    "-" => BinOp::Sub,
                    "*" => BinOp::Mul,
                    "/" => BinOp::Div,
                    "%" => BinOp::Rem,
                    _ => BinOp::Pow,
                };
                Expr::Binary(op, Box::new(a), Box::new(b))
            }
            ExprKind::Cond(c, a, b) => Expr::Cond(
                Box::new(self.expr(c, locals)),
                Box::new(self.expr(a, locals)),
                Box::new(self.expr(b, locals)),
            ),
        }
    }
}
