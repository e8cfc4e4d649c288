//! The lines of a `graph { … }` block (docs/gft.md §13): Bekaert &
//! Willems' object-instancing graphs. Each line is read by hand from its
//! tokens into [`GraphLine`]; a transform's steps become matrices here
//! (they hold only numbers), and names are left for the lowering to
//! resolve. A malformed line gives one diagnostic (the first problem) and
//! is left out.

use super::ast::{Couple, GraphLine, Name, Placement, Step};
use super::lexer::Token;
use crate::common::gft_words::{AXES, FINISHES, GRAPH_LINES, SHAPES, TRANSFORMS};
use crate::diagnostics::{codes, nearest, Code, Diagnostic, Diagnostics};
use crate::ir::graph::{Affine, Finish, Point, Primitive, Shape, DEFAULT_SHAPE_COLOUR};
use crate::ir::{Rgb, Span};

type Tok<'s> = (Token<'s>, Span);
type R<T> = Result<T, Diagnostic>;

/// Reads the lines of a `graph` block (the tokens between its braces).
pub fn block(toks: &[Tok<'_>], diags: &mut Diagnostics) -> Vec<GraphLine> {
    let mut out = Vec::new();
    for line in lines(toks) {
        let span = line[0].1.start..line[line.len() - 1].1.end;
        let mut c = Cursor {
            toks: &line,
            at: 0,
            line: span,
        };
        match c.line() {
            Ok(l) => out.push(l),
            Err(d) => {
                diags.push(d);
                out.push(unread(&line, c.line));
            }
        }
    }
    out
}

/// What a line that did not read would have introduced.
fn unread(line: &[Tok<'_>], span: Span) -> GraphLine {
    let name = |t: &Tok<'_>| match t.0 {
        Token::Ident(w) => Some(Name {
            text: w.to_string(),
            span: t.1.clone(),
        }),
        Token::Quoted(q) => Some(Name {
            text: q.trim_matches('`').to_string(),
            span: t.1.clone(),
        }),
        _ => None,
    };
    let mut symbols = Vec::new();
    let mut transform = None;
    let mut geometry = false;
    let arrow = line.iter().position(|t| t.0 == Token::Arrow);
    match (arrow, line.first().map(|t| t.0)) {
        // A rule's head that is not one symbol: each name in it.
        (Some(arrow), _) => symbols.extend(line[..arrow].iter().filter_map(name)),
        (None, Some(Token::Ident("transform"))) => {
            transform = line.get(1).and_then(name);
        }
        (None, Some(Token::Ident("geometry" | "alternative"))) => {
            geometry = true;
            symbols.extend(line.get(1).and_then(name));
        }
        (None, Some(Token::Ident("symbol"))) => {
            symbols.extend(line[1..].iter().filter_map(name));
        }
        _ => {}
    }
    GraphLine::Unread {
        symbols,
        transform,
        geometry,
        span,
    }
}

/// The block's lines: a line break ends one outside `( )` and `[ ]`,
/// unless the next line starts with `[` (more couples of a long rule).
/// Line breaks inside are dropped.
fn lines<'s>(toks: &[Tok<'s>]) -> Vec<Vec<Tok<'s>>> {
    let mut out = Vec::new();
    let mut line: Vec<Tok<'s>> = Vec::new();
    let mut depth = 0usize;
    for (i, t) in toks.iter().enumerate() {
        let continued = toks.get(i + 1).is_some_and(|n| n.0.is("["));
        match t.0 {
            Token::Char("(" | "[") => depth += 1,
            Token::Char(")" | "]") => depth = depth.saturating_sub(1),
            Token::Newline if depth == 0 && !continued => {
                if !line.is_empty() {
                    out.push(std::mem::take(&mut line));
                }
                continue;
            }
            Token::Newline => continue,
            _ => {}
        }
        line.push(t.clone());
    }
    if !line.is_empty() {
        out.push(line);
    }
    out
}

fn error(code: Code, span: Span, message: impl Into<String>, label: &str) -> Diagnostic {
    Diagnostic::at(code, span, message).with_label(label.to_string())
}

/// "did you mean …?" among `words`, else `otherwise`.
fn suggest(d: Diagnostic, word: &str, words: &[&str], otherwise: &str) -> Diagnostic {
    match nearest(word, words).first() {
        Some(w) => d.suggesting(w),
        None => d.with_help(otherwise.to_string()),
    }
}

/// The forms of the shapes, for messages.
fn shape_form(kind: &str) -> &'static str {
    match kind {
        "sphere" => "sphere CENTRE RADIUS",
        "box" => "box MIN MAX",
        "cylinder" => "cylinder BASE TOP RADIUS",
        "cone" => "cone BASE TOP RADIUS [TOP-RADIUS]",
        "disc" => "disc CENTRE NORMAL RADIUS",
        "triangle" => "triangle P Q R",
        _ => "polygon P Q R …",
    }
}

struct Cursor<'a, 's> {
    toks: &'a [Tok<'s>],
    at: usize,
    line: Span,
}

impl<'s> Cursor<'_, 's> {
    fn peek(&self) -> Option<Token<'s>> {
        self.toks.get(self.at).map(|t| t.0)
    }

    /// The next token's span, or the end of the line.
    fn here(&self) -> Span {
        self.toks
            .get(self.at)
            .map_or(self.line.end..self.line.end, |t| t.1.clone())
    }

    /// Where the last token taken ends.
    fn end(&self) -> usize {
        self.at
            .checked_sub(1)
            .map_or(self.line.start, |k| self.toks[k].1.end)
    }

    fn peek_is(&self, c: &str) -> bool {
        self.peek().is_some_and(|t| t.is(c))
    }

    fn at_end(&self) -> bool {
        self.at >= self.toks.len()
    }

    /// What the next token is, for messages.
    fn found(&self) -> String {
        self.peek()
            .map_or("the end of the line".to_string(), |t| t.to_string())
    }

    fn expect(&mut self, c: &str, code: Code, what: &str, help: &str) -> R<Span> {
        if self.peek_is(c) {
            self.at += 1;
            return Ok(self.toks[self.at - 1].1.clone());
        }
        Err(error(
            code,
            self.here(),
            format!("expected `{c}`, found {}", self.found()),
            what,
        )
        .with_help(help.to_string()))
    }

    fn line(&mut self) -> R<GraphLine> {
        if let Some(arrow) = self.toks.iter().position(|t| t.0 == Token::Arrow) {
            return self.rule(arrow);
        }
        let word = match self.peek() {
            Some(Token::Ident(w)) if GRAPH_LINES.contains(&w) => w,
            Some(Token::Ident(w)) => {
                let d = error(
                    codes::GRAPH_BAD_LINE,
                    self.here(),
                    format!("`{w}` does not start a graph line"),
                    "not a graph line",
                );
                return Err(suggest(
                    d,
                    w,
                    GRAPH_LINES,
                    "a graph line is `transform`, `axiom`, `symbol`, `geometry`, `alternative` or a rule `A -> …`",
                ));
            }
            _ => {
                return Err(error(
                    codes::GRAPH_BAD_LINE,
                    self.line.clone(),
                    "not a graph line",
                    "neither a keyword of the block nor a rule",
                )
                .with_help("a rule is written `A -> h(A) [scale 0.5](B) C`"))
            }
        };
        self.at += 1;
        let line = match word {
            "transform" => self.transform()?,
            "axiom" => {
                let couples = self.couples()?;
                if couples.is_empty() {
                    return Err(error(
                        codes::GRAPH_BAD_LINE,
                        self.line.clone(),
                        "an axiom that places nothing",
                        "no symbol after `axiom`",
                    )
                    .with_help("write `axiom A`, or `axiom w(A) v(B)`"));
                }
                GraphLine::Axiom {
                    couples,
                    span: self.line.clone(),
                }
            }
            "symbol" => {
                let mut names = Vec::new();
                while !self.at_end() {
                    names.push(self.name("a symbol's name")?);
                }
                if names.is_empty() {
                    return Err(error(
                        codes::GRAPH_BAD_LINE,
                        self.line.clone(),
                        "`symbol` names no symbol",
                        "no name after `symbol`",
                    )
                    .with_help("write `symbol A B`"));
                }
                GraphLine::Symbol {
                    names,
                    span: self.line.clone(),
                }
            }
            "geometry" => {
                let symbol = self.name("the symbol the geometry is of")?;
                self.equals("geometry B = sphere (0, 0, 0) 1")?;
                let shape = self.shape()?;
                GraphLine::Geometry {
                    symbol,
                    shape,
                    span: self.line.clone(),
                }
            }
            _ => self.alternative()?,
        };
        Ok(line)
    }

    fn equals(&mut self, form: &str) -> R<Span> {
        self.expect(
            "=",
            codes::GRAPH_BAD_LINE,
            "`=` goes here",
            &format!("write `{form}`"),
        )
    }

    /// A symbol's name: an identifier or a backquoted name.
    fn name(&mut self, what: &str) -> R<Name> {
        let span = self.here();
        let text = match self.peek() {
            Some(Token::Ident(w)) => w.to_string(),
            Some(Token::Quoted(q)) => q.trim_matches('`').to_string(),
            _ => {
                return Err(error(
                    codes::GRAPH_BAD_LINE,
                    span,
                    format!("expected {what}, found {}", self.found()),
                    "not a name",
                )
                .with_help(
                    "a symbol is a name such as `A` or `Branch`, or any text in backquotes",
                ))
            }
        };
        self.at += 1;
        Ok(Name { text, span })
    }

    fn rule(&mut self, arrow: usize) -> R<GraphLine> {
        let head = &self.toks[..arrow];
        let symbol = match head {
            [(Token::Ident(_) | Token::Quoted(_), _)] => self.name("a symbol")?,
            [] => {
                return Err(error(
                    codes::GRAPH_BAD_LINE,
                    self.toks[arrow].1.clone(),
                    "a rule without its symbol",
                    "nothing before `->`",
                )
                .with_help("write the symbol the rule rewrites: `A -> h(A)`"))
            }
            _ => {
                let span = head[0].1.start..head[head.len() - 1].1.end;
                return Err(error(
                    codes::GRAPH_BAD_LINE,
                    span,
                    "a rule rewrites one symbol",
                    "not one symbol",
                )
                .with_help("write one rule for each symbol: `A -> …`"));
            }
        };
        self.at = arrow + 1;
        let couples = self.couples()?;
        Ok(GraphLine::Rule {
            symbol,
            couples,
            span: self.line.clone(),
        })
    }

    /// Couples up to the end of the line.
    fn couples(&mut self) -> R<Vec<Couple>> {
        let mut out = Vec::new();
        while !self.at_end() {
            out.push(self.couple()?);
        }
        Ok(out)
    }

    /// `B`, `NAME(B)` or `[STEPS](B)`.
    fn couple(&mut self) -> R<Couple> {
        let start = self.here().start;
        let placement = match self.peek() {
            Some(Token::Char("[")) => {
                self.at += 1;
                let steps = self.steps(true)?;
                self.expect(
                    "]",
                    codes::GRAPH_BAD_LINE,
                    "the transform is not closed",
                    "close the transform with `]`: `[scale 0.5](A)`",
                )?;
                Placement::Steps(steps, start..self.end())
            }
            Some(Token::Ident(w))
                if self.toks.get(self.at + 1).is_some_and(|t| t.0.is("(")) =>
            {
                let name = Name {
                    text: w.to_string(),
                    span: self.here(),
                };
                self.at += 1;
                Placement::Named(name)
            }
            Some(Token::Ident(_) | Token::Quoted(_)) => {
                let symbol = self.name("a symbol")?;
                return Ok(Couple {
                    placement: Placement::Identity,
                    span: symbol.span.clone(),
                    symbol,
                });
            }
            _ => {
                return Err(error(
                    codes::GRAPH_BAD_LINE,
                    self.here(),
                    format!("expected a couple, found {}", self.found()),
                    "not `w(B)`, `[…](B)` or a symbol",
                )
                .with_help("a couple is a symbol placed by a transform: `h(A)`, `[scale 0.5](A)`, or `A` alone"))
            }
        };
        let help = "the symbol placed is written in parentheses: `h(A)`";
        self.expect("(", codes::GRAPH_BAD_LINE, "`(` goes here", help)?;
        let symbol = self.name("the symbol placed")?;
        self.expect(")", codes::GRAPH_BAD_LINE, "`)` goes here", help)?;
        Ok(Couple {
            placement,
            symbol,
            span: start..self.end(),
        })
    }

    /// `transform NAME = STEPS`.
    fn transform(&mut self) -> R<GraphLine> {
        let name = match self.peek() {
            Some(Token::Ident(w)) => Name {
                text: w.to_string(),
                span: self.here(),
            },
            _ => {
                return Err(error(
                    codes::GRAPH_BAD_LINE,
                    self.here(),
                    format!("expected the transform's name, found {}", self.found()),
                    "not a name",
                )
                .with_help("write `transform h = scale 0.5`"))
            }
        };
        if TRANSFORMS.contains(&name.text.as_str()) {
            return Err(error(
                codes::GRAPH_BAD_LINE,
                name.span,
                format!("`{}` is a transform word, not a name", name.text),
                "a word of the notation",
            )
            .with_help("choose another name: `transform s = scale 0.5`"));
        }
        self.at += 1;
        self.equals("transform h = scale 0.5")?;
        let steps = self.steps(false)?;
        Ok(GraphLine::Transform {
            name,
            steps,
            span: self.line.clone(),
        })
    }

    /// Steps up to `]` (`bracketed`) or the end of the line; at least one.
    fn steps(&mut self, bracketed: bool) -> R<Vec<Step>> {
        let mut out = Vec::new();
        while !(self.at_end() || bracketed && self.peek_is("]")) {
            out.push(self.step()?);
        }
        if out.is_empty() {
            return Err(error(
                codes::GRAPH_UNKNOWN_TRANSFORM,
                self.here(),
                "no transform",
                "a transform goes here",
            )
            .with_help("write e.g. `scale 0.5`, `translate (1, 0, 0)` or a declared name"));
        }
        Ok(out)
    }

    fn step(&mut self) -> R<Step> {
        let span = self.here();
        let word = match self.peek() {
            Some(Token::Ident(w)) => w,
            _ => {
                return Err(error(
                    codes::GRAPH_UNKNOWN_TRANSFORM,
                    span,
                    format!("expected a transform, found {}", self.found()),
                    "not a transform",
                )
                .with_help(
                    "a transform is `translate`, `scale`, `rotate`, `shear`, `matrix` or a declared name",
                ))
            }
        };
        self.at += 1;
        let affine = match word {
            "translate" => Affine::translate(self.point()?.0),
            "scale" if self.peek_is("(") => {
                let (p, at, count) = self.coordinates()?;
                if count != 3 {
                    return Err(error(
                        codes::GRAPH_BAD_VALUE,
                        at,
                        "`scale` takes one number or three",
                        "two numbers",
                    )
                    .with_help("write `scale 0.5` or `scale (0.5, 0.5, 1)`"));
                }
                Affine::scale(p)
            }
            "scale" => {
                let s = self.number()?.0;
                Affine::scale([s; 3])
            }
            "rotate" => self.rotation()?,
            "shear" => {
                let (i, at) = self.axis()?;
                let (j, _) = self.axis()?;
                if i == j {
                    return Err(error(
                        codes::GRAPH_BAD_VALUE,
                        at.start..self.end(),
                        "a shear moves one axis along another",
                        "the same axis twice",
                    )
                    .with_help("write e.g. `shear x y 0.5`: x' = x + 0.5 y"));
                }
                Affine::shear(i, j, self.number()?.0)
            }
            "matrix" => self.matrix()?,
            _ if self.at_number() || self.peek_is("(") => {
                // A name takes no value: a misspelt transform word.
                let d = error(
                    codes::GRAPH_UNKNOWN_TRANSFORM,
                    span,
                    format!("unknown transform `{word}`"),
                    "not a transform word",
                );
                return Err(suggest(
                    d,
                    word,
                    TRANSFORMS,
                    "a transform is `translate`, `scale`, `rotate`, `shear` or `matrix`",
                ));
            }
            _ => {
                return Ok(Step::Name(Name {
                    text: word.to_string(),
                    span,
                }))
            }
        };
        Ok(Step::Affine(affine, span.start..self.end()))
    }

    /// `rotate x|y|z ANGLE` or `rotate (ax, ay, az) ANGLE`, after `rotate`.
    fn rotation(&mut self) -> R<Affine> {
        let at = self.here();
        let axis = if self.peek_is("(") {
            self.point()?.0
        } else {
            let (k, _) = self.axis()?;
            let mut v = [0.0; 3];
            v[k] = 1.0;
            v
        };
        let axis_span = at.start..self.end();
        let angle = self.angle()?;
        Affine::rotate(axis, angle).ok_or_else(|| {
            error(
                codes::GRAPH_BAD_VALUE,
                axis_span,
                "a rotation about no axis",
                "this axis has no direction",
            )
            .with_help("give the axis a length: `rotate (0, 1, 0) 30`, or `rotate y 30`")
        })
    }

    /// `x`, `y` or `z`: 0, 1 or 2.
    fn axis(&mut self) -> R<(usize, Span)> {
        let span = self.here();
        if let Some(Token::Ident(w)) = self.peek() {
            if let Some(k) = AXES.iter().position(|a| *a == w) {
                self.at += 1;
                return Ok((k, span));
            }
        }
        Err(error(
            codes::GRAPH_BAD_VALUE,
            span,
            format!("expected an axis, found {}", self.found()),
            "not `x`, `y` or `z`",
        )
        .with_help("write `rotate y 30`, `rotate (1, 1, 0) 45` or `shear x y 0.5`"))
    }

    /// A number in degrees (`30`, `30deg`) or radians (`0.52rad`), in radians.
    fn angle(&mut self) -> R<f64> {
        let (v, _) = self.number()?;
        match self.peek() {
            Some(Token::Ident("rad")) => {
                self.at += 1;
                Ok(v)
            }
            Some(Token::Ident("deg")) => {
                self.at += 1;
                Ok(v.to_radians())
            }
            _ => Ok(v.to_radians()),
        }
    }

    /// Whether the next token can start a number.
    fn at_number(&self) -> bool {
        matches!(self.peek(), Some(Token::Number(_) | Token::Char("-" | "+")))
    }

    /// `[-]N[/D]`, finite.
    fn number(&mut self) -> R<(f64, Span)> {
        let start = self.here();
        let negative = match self.peek() {
            Some(Token::Char("-")) => {
                self.at += 1;
                true
            }
            Some(Token::Char("+")) => {
                self.at += 1;
                false
            }
            _ => false,
        };
        let mut v = self.unsigned(&start)?;
        if self.peek_is("/") {
            self.at += 1;
            v /= self.unsigned(&start)?;
        }
        let span = start.start..self.end();
        if negative {
            v = -v;
        }
        if !v.is_finite() {
            return Err(error(
                codes::GRAPH_BAD_VALUE,
                span,
                "not a finite number",
                "too large, or a division by zero",
            )
            .with_help("write a number such as `0.5` or `1/3`"));
        }
        Ok((v, span))
    }

    fn unsigned(&mut self, start: &Span) -> R<f64> {
        if let Some(Token::Number(n)) = self.peek() {
            if let Ok(v) = n.parse::<f64>() {
                self.at += 1;
                return Ok(v);
            }
        }
        let span = if self.at_end() {
            self.here()
        } else {
            start.start..self.here().end
        };
        Err(error(
            codes::GRAPH_BAD_VALUE,
            span,
            format!("expected a number, found {}", self.found()),
            "not a number",
        )
        .with_help("write a number such as `0.5`, `-2` or `1/3`"))
    }

    /// `(x, y, z)` or `(x, y)` (z = 0), with its span.
    fn point(&mut self) -> R<(Point, Span)> {
        let (p, span, _) = self.coordinates()?;
        Ok((p, span))
    }

    /// A point with its span and how many coordinates it was written with.
    fn coordinates(&mut self) -> R<(Point, Span, usize)> {
        let start = self.here();
        let form = "write a point as `(x, y, z)`, or `(x, y)` for z = 0";
        let malformed = |c: &Self, what: &str| {
            error(
                codes::GRAPH_BAD_VALUE,
                c.here(),
                format!("malformed point: expected {what}, found {}", c.found()),
                "not `(x, y, z)`",
            )
            .with_help(form)
        };
        if !self.peek_is("(") {
            return Err(malformed(self, "`(`"));
        }
        self.at += 1;
        let mut p = [0.0; 3];
        let mut count = 0;
        for (k, c) in p.iter_mut().enumerate() {
            if k == 2 && self.peek_is(")") {
                break;
            }
            if k > 0 {
                if !self.peek_is(",") {
                    return Err(malformed(self, "`,`"));
                }
                self.at += 1;
            }
            if !self.at_number() {
                return Err(malformed(self, "a number"));
            }
            *c = self.number()?.0;
            count += 1;
        }
        if !self.peek_is(")") {
            return Err(malformed(self, "`)`"));
        }
        self.at += 1;
        Ok((p, start.start..self.end(), count))
    }

    /// `matrix (a b c d, e f g h, i j k l)`, after `matrix`.
    fn matrix(&mut self) -> R<Affine> {
        let malformed = |c: &Self| {
            error(
                codes::GRAPH_BAD_VALUE,
                c.here(),
                format!("malformed matrix at {}", c.found()),
                "not three rows of four numbers",
            )
            .with_help("write `matrix (a b c d, e f g h, i j k l)`: x' = a x + b y + c z + d, …")
        };
        if !self.peek_is("(") {
            return Err(malformed(self));
        }
        self.at += 1;
        let mut m = [[0.0; 4]; 3];
        for (i, row) in m.iter_mut().enumerate() {
            if i > 0 {
                if !self.peek_is(",") {
                    return Err(malformed(self));
                }
                self.at += 1;
            }
            for v in row.iter_mut() {
                if !self.at_number() {
                    return Err(malformed(self));
                }
                *v = self.number()?.0;
            }
        }
        if !self.peek_is(")") {
            return Err(malformed(self));
        }
        self.at += 1;
        Ok(Affine(m))
    }

    /// `alternative NAME [below N] = SHAPE`, after `alternative`.
    fn alternative(&mut self) -> R<GraphLine> {
        let symbol = self.name("the symbol the alternative is of")?;
        let below = if self.peek() == Some(Token::Ident("below")) {
            self.at += 1;
            let (v, span) = self.number()?;
            if v <= 0.0 {
                return Err(error(
                    codes::GRAPH_BAD_VALUE,
                    span,
                    "`below` takes a size above zero",
                    "not above zero",
                )
                .with_help("write a number of pixels, e.g. `below 2`"));
            }
            Some((v, span))
        } else {
            None
        };
        self.equals("alternative B below 2 = sphere (0, 0, 0) 1")?;
        let shape = self.shape()?;
        Ok(GraphLine::Alternative {
            symbol,
            below,
            shape,
            span: self.line.clone(),
        })
    }

    fn bad_shape(&self, kind: &str, expected: &str) -> Diagnostic {
        error(
            codes::GRAPH_BAD_SHAPE,
            self.here(),
            format!(
                "malformed `{kind}`: expected {expected}, found {}",
                self.found()
            ),
            &format!("not {expected}"),
        )
        .with_help(format!("write `{}`", shape_form(kind)))
    }

    fn shape_point(&mut self, kind: &str) -> R<Point> {
        if !self.peek_is("(") {
            return Err(self.bad_shape(kind, "a point `(x, y, z)`"));
        }
        Ok(self.point()?.0)
    }

    fn shape_number(&mut self, kind: &str) -> R<f64> {
        if !self.at_number() {
            return Err(self.bad_shape(kind, "a number"));
        }
        Ok(self.number()?.0)
    }

    /// `KIND ARGS [#rrggbb] [FINISH X]…` up to the end of the line.
    fn shape(&mut self) -> R<Shape> {
        let kind = match self.peek() {
            Some(Token::Ident(w)) if SHAPES.contains(&w) => w,
            _ => {
                let d = error(
                    codes::GRAPH_BAD_SHAPE,
                    self.here(),
                    format!("expected a shape, found {}", self.found()),
                    "not a shape",
                );
                let help = "a shape is `sphere`, `box`, `cylinder`, `cone`, `disc`, `triangle` or `polygon`";
                return Err(match self.peek() {
                    Some(Token::Ident(w)) => suggest(d, w, SHAPES, help),
                    _ => d.with_help(help),
                });
            }
        };
        self.at += 1;
        let primitive = match kind {
            "sphere" => Primitive::Sphere {
                centre: self.shape_point(kind)?,
                radius: self.shape_number(kind)?,
            },
            "box" => Primitive::Box {
                min: self.shape_point(kind)?,
                max: self.shape_point(kind)?,
            },
            "cylinder" => Primitive::Cylinder {
                base: self.shape_point(kind)?,
                top: self.shape_point(kind)?,
                radius: self.shape_number(kind)?,
            },
            "cone" => Primitive::Cone {
                base: self.shape_point(kind)?,
                top: self.shape_point(kind)?,
                base_radius: self.shape_number(kind)?,
                top_radius: if self.at_number() {
                    self.number()?.0
                } else {
                    0.0
                },
            },
            "disc" => Primitive::Disc {
                centre: self.shape_point(kind)?,
                normal: self.shape_point(kind)?,
                radius: self.shape_number(kind)?,
            },
            "triangle" => Primitive::Triangle([
                self.shape_point(kind)?,
                self.shape_point(kind)?,
                self.shape_point(kind)?,
            ]),
            _ => {
                let mut ps = Vec::new();
                while ps.len() < 3 || self.peek_is("(") {
                    ps.push(self.shape_point(kind)?);
                }
                Primitive::Polygon(ps)
            }
        };
        let colour = match self.peek() {
            Some(Token::Colour(c)) => {
                self.at += 1;
                rgb(c)
            }
            _ => DEFAULT_SHAPE_COLOUR,
        };
        let mut finish = Finish::default();
        let mut given: Vec<&str> = Vec::new();
        while !self.at_end() {
            let word = match self.peek() {
                Some(Token::Ident(w)) if FINISHES.contains(&w) && !given.contains(&w) => w,
                Some(Token::Ident(w)) if FINISHES.contains(&w) => {
                    return Err(error(
                        codes::GRAPH_BAD_SHAPE,
                        self.here(),
                        format!("`{w}` given twice"),
                        "given again here",
                    )
                    .with_help("give each finish word once"))
                }
                _ => {
                    let d = error(
                        codes::GRAPH_BAD_SHAPE,
                        self.here(),
                        format!("unexpected {} after the shape", self.found()),
                        "not a colour or a finish word",
                    );
                    let help = "after a shape come a colour `#rrggbb` and `ambient X`, `diffuse X`, `specular X`, `shininess X`";
                    return Err(match self.peek() {
                        Some(Token::Ident(w)) => suggest(d, w, FINISHES, help),
                        _ => d.with_help(help),
                    });
                }
            };
            self.at += 1;
            given.push(word);
            if !self.at_number() {
                return Err(error(
                    codes::GRAPH_BAD_SHAPE,
                    self.here(),
                    format!("`{word}` takes a number, found {}", self.found()),
                    "not a number",
                )
                .with_help(format!("write e.g. `{word} 0.5`")));
            }
            let v = self.number()?.0;
            *match word {
                "ambient" => &mut finish.ambient,
                "diffuse" => &mut finish.diffuse,
                "specular" => &mut finish.specular,
                _ => &mut finish.shininess,
            } = v;
        }
        Ok(Shape {
            primitive,
            colour,
            finish,
        })
    }
}

/// `#rrggbb` (six hex digits, as the lexer reads a colour).
fn rgb(text: &str) -> Rgb {
    let h = |i: usize| u8::from_str_radix(&text[i..i + 2], 16).unwrap_or(0);
    Rgb(h(1), h(3), h(5))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::gft::lexer::lex;

    /// The lines of a block's inner text, and the codes of its problems.
    fn read(inner: &str) -> (Vec<GraphLine>, Vec<&'static str>) {
        let mut d = Diagnostics::default();
        let toks = lex(inner, &mut d);
        let lines = block(&toks, &mut d);
        (lines, d.iter().map(|d| d.code.0).collect())
    }

    fn steps_of(line: &GraphLine) -> Vec<Affine> {
        let GraphLine::Transform { steps, .. } = line else {
            panic!("not a transform: {line:?}")
        };
        steps
            .iter()
            .map(|s| match s {
                Step::Affine(a, _) => *a,
                Step::Name(n) => panic!("a name: {n:?}"),
            })
            .collect()
    }

    #[test]
    fn numbers_are_signed_fractions_and_angles_degrees_unless_radians() {
        let (lines, codes) = read(
            "transform a = translate (-1/4, +2, 1e1) rotate z 30deg rotate z 0.5rad rotate z -90 scale 1/3",
        );
        assert!(codes.is_empty(), "{codes:?}");
        let s = steps_of(&lines[0]);
        assert_eq!(s[0], Affine::translate([-0.25, 2.0, 10.0]));
        let z = [0.0, 0.0, 1.0];
        assert_eq!(s[1], Affine::rotate(z, 30f64.to_radians()).unwrap());
        assert_eq!(s[2], Affine::rotate(z, 0.5).unwrap());
        assert_eq!(s[3], Affine::rotate(z, (-90f64).to_radians()).unwrap());
        assert_eq!(s[4], Affine::scale([1.0 / 3.0; 3]));
        // `-0` is negative zero, kept to the bit.
        let (lines, _) = read("transform z = translate (-0, 0)");
        let t = steps_of(&lines[0])[0];
        assert!(t.0[0][3].is_sign_negative() && !t.0[1][3].is_sign_negative());
    }

    #[test]
    fn lines_end_outside_brackets_and_go_on_before_a_bracket() {
        let (lines, codes) = read(
            "axiom A\nA -> [translate (1,\n 0, 0) scale 0.5](A)\n   [scale 0.5](A)\ngeometry A = sphere (0, 0, 0) 1\n",
        );
        assert!(codes.is_empty(), "{codes:?}");
        assert_eq!(lines.len(), 3);
        let GraphLine::Rule { couples, .. } = &lines[1] else {
            panic!("{:?}", lines[1])
        };
        assert_eq!(couples.len(), 2);
    }

    #[test]
    fn couples_are_a_symbol_a_name_or_steps_in_brackets() {
        let (lines, codes) = read("axiom A h(B) [scale 0.5 h](`c d`)");
        assert!(codes.is_empty(), "{codes:?}");
        let GraphLine::Axiom { couples, .. } = &lines[0] else {
            panic!()
        };
        assert!(matches!(couples[0].placement, Placement::Identity));
        assert!(matches!(&couples[1].placement, Placement::Named(n) if n.text == "h"));
        let Placement::Steps(steps, span) = &couples[2].placement else {
            panic!()
        };
        assert_eq!(steps.len(), 2);
        assert!(matches!(&steps[1], Step::Name(n) if n.text == "h"));
        assert_eq!(span.clone(), 13..26);
        assert_eq!(couples[2].symbol.text, "c d");
    }

    #[test]
    fn a_line_that_does_not_read_still_says_what_it_introduces() {
        let (lines, codes) =
            read("transform t = scale (1, 2)\ngeometry B = cube\nA B -> x\nsymbol C 3\n");
        assert_eq!(codes, ["E0922", "E0923", "E0920", "E0920"]);
        let unread: Vec<(Vec<&str>, Option<&str>, bool)> = lines
            .iter()
            .map(|l| match l {
                GraphLine::Unread {
                    symbols,
                    transform,
                    geometry,
                    ..
                } => (
                    symbols.iter().map(|n| n.text.as_str()).collect(),
                    transform.as_ref().map(|n| n.text.as_str()),
                    *geometry,
                ),
                l => panic!("read: {l:?}"),
            })
            .collect();
        assert_eq!(
            unread,
            [
                (vec![], Some("t"), false),
                (vec!["B"], None, true),
                (vec!["A", "B"], None, false),
                (vec!["C"], None, false),
            ]
        );
    }

    #[test]
    fn shapes_take_their_points_numbers_colour_and_finish() {
        let (lines, codes) =
            read("geometry A = cone (0, 0) (0, 1, 0) 0.5 0.25 #ff8000 shininess 5");
        assert!(codes.is_empty(), "{codes:?}");
        let GraphLine::Geometry { shape, .. } = &lines[0] else {
            panic!()
        };
        assert_eq!(
            shape.primitive,
            Primitive::Cone {
                base: [0.0; 3],
                top: [0.0, 1.0, 0.0],
                base_radius: 0.5,
                top_radius: 0.25
            }
        );
        assert_eq!(shape.colour, Rgb(255, 128, 0));
        assert_eq!(shape.finish.shininess, 5.0);
        assert_eq!(shape.finish.diffuse, Finish::default().diffuse);
        let (_, codes) = read("geometry A = polygon (0, 0) (1, 0)");
        assert_eq!(codes, ["E0923"]);
    }
}
