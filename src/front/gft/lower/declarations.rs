//! Declarations, read before anything else: the turtle set, `NAME =
//! OPERATION`, `symbol`, `silent` and rotations, so that words split by
//! the longest declared name.

use super::{err, groups, Cx};
use crate::common::vocabulary;
use crate::common::vocabulary::TurtleSet;
use crate::diagnostics::{codes, Diagnostic};
use crate::front::gft::ast::{Arg, Keyword};
use crate::ir::{Angle, Axis, Rotation, RotationId, Span, SymbolId, TurtleOp};

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
    ("set-texture", TurtleOp::SetTexture),
    ("forward-real", TurtleOp::ForwardReal { draw: true }),
    ("move-real", TurtleOp::ForwardReal { draw: false }),
    ("untwist", TurtleOp::Untwist),
    ("keep-twist", TurtleOp::KeepTwist),
    ("sub-lsystem-call", TurtleOp::SubLsystemCall),
    ("sub-lsystem-return", TurtleOp::SubLsystemReturn),
    ("write-label", TurtleOp::Label),
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
    pub(super) fn turtle(&mut self, k: &Keyword) {
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
    pub(super) fn give_set(&mut self) {
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

    pub(super) fn declare(&mut self, name: &str, span: &Span) -> SymbolId {
        if name.chars().count() > 1 {
            self.names.add(name);
        }
        let id = self.sys.intern(name);
        self.spans.symbols.entry(id).or_insert_with(|| span.clone());
        id
    }

    /// An angle: `delta`, `-delta`, `2.5*delta`, `30deg`, `0.5rad`.
    pub(super) fn angle(&mut self, text: &str, span: &Span) -> Option<Angle> {
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
    pub(super) fn silent(&mut self, k: &Keyword) {
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

    pub(super) fn define(&mut self, name: &str, span: &Span, op: &[Arg], op_span: &Span) {
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
    pub(super) fn rotation(&mut self, k: &Keyword) {
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
pub(super) fn constant(text: &str) -> Option<f64> {
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
