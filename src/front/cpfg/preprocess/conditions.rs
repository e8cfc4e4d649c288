//! Conditional groups: `#if`/`#ifdef`/`#ifndef`/`#elif`/`#else`/`#endif`,
//! and evaluating an `#if` expression as C does (integers, `defined`).

use super::tokens::{strip_ws, Kind, Tok};
use super::{Cond, Directive, Pp};
use crate::diagnostics::{codes, Diagnostic};
use crate::front::depth::too_deep;
use crate::ir::MAX_NESTING;
use std::ops::Range;
use std::rc::Rc;

impl Pp<'_> {
    /// The value of an `#if`, `#ifdef` or `#ifndef` in kept text.
    pub(super) fn condition(&mut self, dir: &Directive) -> bool {
        if dir.name == "if" {
            return self.eval_if(&dir.rest, dir.rest_span.clone(), dir.name_span.clone());
        }
        self.macro_operand(dir)
            .is_some_and(|m| self.macros.contains_key(&*m) == (dir.name == "ifdef"))
    }

    /// The macro name an `#ifdef`, `#ifndef` or `#undef` is about: text after
    /// it is reported as ignored, and a line without it as a bad directive.
    pub(super) fn macro_operand(&mut self, dir: &Directive) -> Option<Rc<str>> {
        let words = strip_ws(dir.rest.clone());
        match words.first() {
            Some(w) if w.kind == Kind::Ident => {
                self.extra_tokens(&words[1..], dir.name);
                Some(w.text.clone())
            }
            _ => {
                self.bad_directive(
                    dir.line_span.clone(),
                    format!("`#{}` needs a macro name", dir.name),
                );
                None
            }
        }
    }

    /// `#elif`, `#else` or `#endif`: ends the current group of the innermost
    /// `#if` and, but for `#endif`, starts the next one.
    pub(super) fn next_group(&mut self, dir: Directive, conds: &mut Vec<Cond>) {
        let name = dir.name;
        let Some(c) = conds.last_mut() else {
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_STRAY_CONDITIONAL,
                    dir.line_span,
                    format!("`#{name}` without `#if`"),
                )
                .with_label("no conditional block is open here")
                .with_help("remove it, or add the `#if` it belongs to"),
            );
            return;
        };
        if name == "endif" {
            self.extra_tokens(&strip_ws(dir.rest), name);
            conds.pop();
            return;
        }
        if c.seen_else {
            let first = c.span.clone();
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_STRAY_CONDITIONAL,
                    dir.line_span,
                    format!("`#{name}` after `#else`"),
                )
                .with_secondary(first, "in the block opened here")
                .with_label("the block already had its `#else`")
                .with_help("a block has at most one `#else`, after every `#elif`"),
            );
            return;
        }
        if name == "else" {
            self.extra_tokens(&strip_ws(dir.rest), name);
            c.seen_else = true;
            c.active = c.parent && !c.taken;
            c.taken = true;
        } else {
            let (parent, taken) = (c.parent, c.taken);
            let value = if parent && !taken {
                self.eval_if(&dir.rest, dir.rest_span, dir.name_span)
            } else {
                false
            };
            if let Some(c) = conds.last_mut() {
                c.active = parent && !taken && value;
                c.taken = taken || value;
            }
        }
    }

    /// Evaluates an `#if`/`#elif` condition.
    fn eval_if(&mut self, rest: &[Tok], span: Range<usize>, name_span: Range<usize>) -> bool {
        // `defined X` / `defined(X)` first, then macro expansion.
        let mut toks: Vec<Tok> = Vec::new();
        let mut i = 0;
        let sig = |k: &mut usize| {
            while *k < rest.len() && rest[*k].kind == Kind::Ws {
                *k += 1;
            }
        };
        while i < rest.len() {
            let t = &rest[i];
            if t.kind == Kind::Ident && &*t.text == "defined" {
                let mut k = i + 1;
                sig(&mut k);
                let paren = rest.get(k).is_some_and(|x| &*x.text == "(");
                if paren {
                    k += 1;
                    sig(&mut k);
                }
                let name = rest.get(k).filter(|x| x.kind == Kind::Ident);
                let Some(name) = name else {
                    self.bad_directive(span, "`defined` needs a macro name".to_string());
                    return false;
                };
                let v = self.macros.contains_key(&*name.text);
                k += 1;
                if paren {
                    sig(&mut k);
                    if rest.get(k).is_none_or(|x| &*x.text != ")") {
                        self.bad_directive(span, "`defined(` is not closed".to_string());
                        return false;
                    }
                    k += 1;
                }
                let mut t2 = t.clone();
                t2.kind = Kind::Other;
                t2.text = Rc::from(if v { "1" } else { "0" });
                toks.push(t2);
                i = k;
            } else {
                toks.push(t.clone());
                i += 1;
            }
        }
        let expanded = self.expand(toks.into(), 0);
        let words: Vec<&Tok> = expanded
            .iter()
            .filter(|t| !matches!(t.kind, Kind::Ws | Kind::Splice))
            .collect();
        if words.is_empty() {
            self.bad_directive(name_span, "`#if` needs a condition".to_string());
            return false;
        }
        let mut p = Expr {
            toks: &words,
            pos: 0,
            err: None,
            too_deep: None,
        };
        let v = p.ternary(0);
        if p.err.is_none() && p.pos < words.len() {
            p.err = Some(format!("unexpected `{}`", words[p.pos].text));
        }
        if let Some(at) = p.too_deep {
            self.diags.push(too_deep(
                at,
                "write the condition with fewer parentheses, signs and `?:`",
            ));
            return false;
        }
        match p.err {
            Some(e) => {
                self.diags.push(
                    Diagnostic::at(
                        codes::CPFG_BAD_DIRECTIVE,
                        span,
                        format!("cannot evaluate the condition: {e}"),
                    )
                    .with_label("this condition")
                    .with_help(
                        "`#if` takes an integer expression; names that are not macros count as 0",
                    ),
                );
                false
            }
            None => v != 0,
        }
    }
}

/// The integer expressions of `#if`.
struct Expr<'a> {
    pub(super) toks: &'a [&'a Tok],
    pub(super) pos: usize,
    err: Option<String>,
    /// The token that went past [`MAX_NESTING`], if one did.
    pub(super) too_deep: Option<Range<usize>>,
}

impl Expr<'_> {
    fn peek(&self) -> &str {
        self.toks.get(self.pos).map_or("", |t| &t.text)
    }
    fn peek2(&self) -> String {
        let a = self.peek();
        match self.toks.get(self.pos + 1) {
            Some(b) if b.origin.start == self.toks[self.pos].origin.end || !b.own => {
                format!("{a}{}", b.text)
            }
            _ => a.to_string(),
        }
    }
    fn fail(&mut self, msg: String) -> i64 {
        if self.err.is_none() {
            self.err = Some(msg);
        }
        self.pos = self.toks.len();
        0
    }

    /// Whether `depth` (the levels of parentheses, signs and `?:` around
    /// the token at `pos`) is past the limit; if so, evaluation stops there
    /// and the token that opened the level is kept to be reported.
    fn past_limit(&mut self, depth: usize) -> bool {
        if depth <= MAX_NESTING {
            return false;
        }
        let opener = self.toks.get(self.pos.saturating_sub(1));
        self.too_deep = opener.map(|t| t.origin.clone());
        self.fail("nested too deeply".to_string());
        true
    }

    fn ternary(&mut self, depth: usize) -> i64 {
        if self.past_limit(depth) {
            return 0;
        }
        let c = self.binary(0, depth);
        if self.peek() == "?" {
            self.pos += 1;
            let a = self.ternary(depth + 1);
            if self.peek() != ":" {
                return self.fail("`?` without `:`".to_string());
            }
            self.pos += 1;
            let b = self.ternary(depth + 1);
            return if c != 0 { a } else { b };
        }
        c
    }

    /// Binary operators by precedence level (0 = `||`).
    fn binary(&mut self, level: usize, depth: usize) -> i64 {
        const LEVELS: &[&[&str]] = &[
            &["||"],
            &["&&"],
            &["|"],
            &["^"],
            &["&"],
            &["==", "!="],
            &["<=", ">=", "<", ">"],
            &["<<", ">>"],
            &["+", "-"],
            &["*", "/", "%"],
        ];
        if level == LEVELS.len() {
            return self.unary(depth);
        }
        let mut l = self.binary(level + 1, depth);
        loop {
            if self.err.is_some() {
                return 0;
            }
            let two = self.peek2();
            let op = if LEVELS[level].contains(&two.as_str()) && two.len() == 2 {
                two
            } else if LEVELS[level].contains(&self.peek()) {
                // A one-character operator that is not the start of a longer one.
                let one = self.peek().to_string();
                if two.len() == 2
                    && ["||", "&&", "==", "!=", "<=", ">=", "<<", ">>"].contains(&two.as_str())
                {
                    return l;
                }
                one
            } else {
                return l;
            };
            self.pos += if op.len() == 2 && self.peek().len() == 1 {
                2
            } else {
                1
            };
            let r = self.binary(level + 1, depth);
            l = match op.as_str() {
                "||" => i64::from(l != 0 || r != 0),
                "&&" => i64::from(l != 0 && r != 0),
                "|" => l | r,
                "^" => l ^ r,
                "&" => l & r,
                "==" => i64::from(l == r),
                "!=" => i64::from(l != r),
                "<" => i64::from(l < r),
                ">" => i64::from(l > r),
                "<=" => i64::from(l <= r),
                ">=" => i64::from(l >= r),
                "<<" => l.wrapping_shl(r as u32),
                ">>" => l.wrapping_shr(r as u32),
                "+" => l.wrapping_add(r),
                "-" => l.wrapping_sub(r),
                "*" => l.wrapping_mul(r),
                "/" | "%" if r == 0 => return self.fail("division by zero".to_string()),
                "/" => l.wrapping_div(r),
                _ => l.wrapping_rem(r),
            };
        }
    }

    fn unary(&mut self, depth: usize) -> i64 {
        if self.past_limit(depth) {
            return 0;
        }
        let Some(t) = self.toks.get(self.pos) else {
            return self.fail("the condition ends too early".to_string());
        };
        let text = t.text.clone();
        self.pos += 1;
        match &*text {
            "-" => self.unary(depth + 1).wrapping_neg(),
            "+" => self.unary(depth + 1),
            "!" => i64::from(self.unary(depth + 1) == 0),
            "~" => !self.unary(depth + 1),
            "(" => {
                let v = self.ternary(depth + 1);
                if self.peek() != ")" {
                    return self.fail("`(` without `)`".to_string());
                }
                self.pos += 1;
                v
            }
            // Names left after expansion are 0, as in C.
            _ if t.kind == Kind::Ident => 0,
            s if s.as_bytes()[0].is_ascii_digit() => match parse_int(s) {
                Some(v) => v,
                None => self.fail(format!("`{s}` is not an integer")),
            },
            s => self.fail(format!("unexpected `{s}`")),
        }
    }
}

fn parse_int(s: &str) -> Option<i64> {
    let s = s.trim_end_matches(['u', 'U', 'l', 'L']);
    let (digits, radix) = if let Some(h) = s.strip_prefix("0x").or_else(|| s.strip_prefix("0X")) {
        (h, 16)
    } else if s.len() > 1 && s.starts_with('0') {
        (&s[1..], 8)
    } else {
        (s, 10)
    };
    u64::from_str_radix(digits, radix).ok().map(|v| v as i64)
}
