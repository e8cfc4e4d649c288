//! Reads that cpfg's files make give nothing: `func(id, x)` with no
//! function `id` among the view file's function files, and an array
//! element whose constant subscript lies outside the array. Each evaluates
//! to 0, which draws a different plant without a word, so each place is
//! reported once, when the file is read.
//!
//! Only what is known when reading is reported: an id or a subscript
//! computed at run time cannot be checked here.

use super::ast::{self, ExprKind, Item, Module, Stmt};
use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use crate::ir::program::ArrayDecl;
use crate::ir::Span;

/// The most places reported per kind: a mistake copied through a file is
/// seen in its first few.
const MAX_REPORTED: usize = 20;

/// Reports, in the (preprocessed) `file`, the `func` calls that name no
/// function of the `functions` the view file gave, and the constant
/// subscripts outside the `arrays` they index.
pub fn check(file: &ast::File, arrays: &[ArrayDecl], functions: usize, diags: &mut Diagnostics) {
    let mut c = Checker {
        arrays,
        functions,
        found: Vec::new(),
    };
    for item in &file.items {
        c.item(item);
    }
    let mut funcs = 0;
    let mut subs = 0;
    for d in c.found {
        let n = if d.code == codes::CPFG_NO_USER_FUNCTION {
            &mut funcs
        } else {
            &mut subs
        };
        *n += 1;
        if *n <= MAX_REPORTED {
            diags.push(d);
        }
    }
}

struct Checker<'a> {
    arrays: &'a [ArrayDecl],
    functions: usize,
    found: Vec<Diagnostic>,
}

impl Checker<'_> {
    fn item(&mut self, item: &Item) {
        match item {
            Item::Seed(e, _) | Item::DerivationLength(e, _) | Item::MaximumDepth(e, _) => {
                self.expr(e)
            }
            Item::Axiom(modules, _) => self.modules(modules),
            Item::Block(_, stmts, _) => self.stmts(stmts),
            Item::Production(p) => {
                for m in [&p.left, &p.predecessor, &p.right, &p.successor] {
                    self.modules(m);
                }
                self.stmts(&p.before);
                self.stmts(&p.after);
                for e in p.condition.iter().chain(&p.probability) {
                    self.expr(e);
                }
            }
            _ => {}
        }
    }

    fn modules(&mut self, modules: &[Module]) {
        for m in modules {
            for a in &m.args {
                self.expr(a);
            }
        }
    }

    fn stmts(&mut self, stmts: &[Stmt]) {
        for s in stmts {
            match s {
                Stmt::Assign { target, value } => {
                    self.expr(target);
                    self.expr(value);
                }
                Stmt::Eval(e) => self.expr(e),
                Stmt::If(c, t, e) => {
                    self.expr(c);
                    self.stmts(t);
                    self.stmts(e);
                }
                Stmt::While(c, body) | Stmt::Do(body, c) => {
                    self.expr(c);
                    self.stmts(body);
                }
            }
        }
    }

    /// Walks `e` (as deep as the parser lets trees be).
    fn expr(&mut self, e: &ast::Expr) {
        match &e.kind {
            ExprKind::Call(name, _, args) => {
                if name == "func" {
                    self.func(args, &e.span);
                }
                args.iter().for_each(|a| self.expr(a));
            }
            ExprKind::Index(name, subs) => {
                self.element(name, subs, &e.span);
                subs.iter().for_each(|a| self.expr(a));
            }
            ExprKind::Unary(_, a) => self.expr(a),
            ExprKind::Binary(_, a, b) => {
                self.expr(a);
                self.expr(b);
            }
            ExprKind::Cond(c, a, b) => {
                self.expr(c);
                self.expr(a);
                self.expr(b);
            }
            _ => {}
        }
    }

    /// `func(id, x)` at `span`: reported when there are no functions at
    /// all, or when `id` is a constant naming none of them.
    fn func(&mut self, args: &[ast::Expr], span: &Span) {
        let id = args.first().and_then(constant);
        let given = self.functions;
        let (message, label) = match id {
            _ if given == 0 => (
                "`func` is called but the view file names no function file".to_string(),
                "evaluates to 0".to_string(),
            ),
            Some(id) if !(id >= 1.0 && id <= given as f64) => (
                format!("there is no user function {id}: the view file names {given}"),
                format!("function {id} evaluates to 0"),
            ),
            _ => return,
        };
        self.found.push(
            Diagnostic::at(codes::CPFG_NO_USER_FUNCTION, span.clone(), message)
                .with_label(label)
                .with_help("name the function's file in the view file: `function: name.func`"),
        );
    }

    /// `name[subs]` at `span`: reported when a constant subscript lies
    /// outside the array's size in its dimension.
    fn element(&mut self, name: &str, subs: &[ast::Expr], span: &Span) {
        let Some(a) = self.arrays.iter().find(|a| a.name == name) else {
            return;
        };
        for (k, s) in subs.iter().enumerate() {
            let (Some(v), Some(&size)) = (constant(s), a.dims.get(k)) else {
                continue;
            };
            if !(v >= 0.0 && v < size as f64) {
                self.found.push(
                    Diagnostic::at(
                        codes::CPFG_SUBSCRIPT_RANGE,
                        span.clone(),
                        format!("subscript {v} is outside array `{name}`, whose size is {size}"),
                    )
                    .with_label("reads 0 and writes nothing")
                    .with_help(format!(
                        "subscripts of `{name}` run from 0 to {}",
                        size.max(1) - 1
                    )),
                );
                return;
            }
        }
    }
}

/// The value of `e` when it is made of numbers alone (macros are already
/// expanded).
fn constant(e: &ast::Expr) -> Option<f64> {
    if e.is_cut() {
        return None;
    }
    match &e.kind {
        ExprKind::Num(v) => Some(*v),
        ExprKind::Unary(op, a) => Some(op.apply(constant(a)?)),
        ExprKind::Binary(op, a, b) => Some(op.apply(constant(a)?, constant(b)?)),
        _ => None,
    }
    .filter(|v| v.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn found(src: &str, functions: usize) -> Vec<(crate::diagnostics::Code, String)> {
        let mut d = Diagnostics::default();
        let ast = super::super::parser::parse(src, &mut d);
        let lowered = super::super::lower::lower(&ast, &mut d);
        let mut out = Diagnostics::default();
        check(&ast, &lowered.system.program.arrays, functions, &mut out);
        out.iter()
            .map(|d| (d.code, src[d.span.clone().unwrap()].to_string()))
            .collect()
    }

    #[test]
    fn a_func_call_without_its_function_is_reported_at_the_call() {
        let src =
            "lsystem: 1\naxiom: A(1)\nA(x) --> F(func(1,x))F(func(2,x))F(func(x,x))\nendlsystem\n";
        let none = found(src, 0);
        assert_eq!(none.len(), 3);
        assert!(none.iter().all(|(c, _)| *c == codes::CPFG_NO_USER_FUNCTION));
        assert_eq!(none[0].1, "func(1,x)");
        // With one function, only the constant id past it is known wrong.
        assert_eq!(
            found(src, 1),
            vec![(codes::CPFG_NO_USER_FUNCTION, "func(2,x)".to_string())]
        );
        assert!(found(src, 2).is_empty());
    }

    #[test]
    fn a_constant_subscript_outside_its_array_is_reported_at_the_element() {
        let src = "lsystem: 1\ndefine: { array a[3]; }\nStart: { a[2] = 1; a[3] = 1; }\naxiom: A(1)\nA(x) --> F(a[-1])F(a[x])\nendlsystem\n";
        let f = found(src, 0);
        let places: Vec<&str> = f.iter().map(|(_, s)| s.as_str()).collect();
        assert_eq!(places, ["a[3]", "a[-1]"]);
        assert!(f.iter().all(|(c, _)| *c == codes::CPFG_SUBSCRIPT_RANGE));
    }
}
