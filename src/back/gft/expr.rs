//! Expressions and statements as cpfg writes them, with the fewest
//! parentheses that keep the tree: the printed text, read by cpfg's rules
//! (unary operators binding tightest, every binary operator
//! left-associative, `c ? a : b` loosest, its condition without another
//! `?`), gives the same tree back.

use crate::ir::program::{BinOp, Builtin, Expr, Place, Stmt, UnOp, Var};
use crate::number;

/// How to write the names an expression refers to.
pub struct Names<'a> {
    /// Local slot k's name.
    pub locals: &'a [String],
    pub globals: &'a [String],
    pub arrays: &'a [String],
}

impl Names<'_> {
    fn var(&self, v: Var) -> String {
        match v {
            Var::Local(k) => {
                (self.locals.get(k as usize)).map_or(format!("local{k}"), String::clone)
            }
            Var::Global(k) => {
                (self.globals.get(k as usize)).map_or(format!("global{k}"), String::clone)
            }
        }
    }
    fn array(&self, a: u16) -> String {
        (self.arrays.get(a as usize)).map_or(format!("array{a}"), String::clone)
    }
}

/// A number as the notation reads it back: [`number::exact`], keeping the
/// sign of a negative zero.
pub fn num(x: f64) -> String {
    if x == 0.0 && x.is_sign_negative() {
        "-0".to_string()
    } else {
        number::exact(x)
    }
}

/// How tightly each form binds (the tightest highest); atoms are 9.
fn precedence(op: BinOp) -> u8 {
    match op {
        BinOp::Or => 1,
        BinOp::And => 2,
        BinOp::Eq | BinOp::Ne => 3,
        BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge => 4,
        BinOp::Add | BinOp::Sub => 5,
        BinOp::Mul | BinOp::Div | BinOp::Rem => 6,
        BinOp::Pow => 7,
    }
}

const UNARY: u8 = 8;

fn symbol(op: BinOp) -> &'static str {
    match op {
        BinOp::Or => "||",
        BinOp::And => "&&",
        BinOp::Eq => "==",
        BinOp::Ne => "!=",
        BinOp::Lt => "<",
        BinOp::Le => "<=",
        BinOp::Gt => ">",
        BinOp::Ge => ">=",
        BinOp::Add => "+",
        BinOp::Sub => "-",
        BinOp::Mul => "*",
        BinOp::Div => "/",
        BinOp::Rem => "%",
        BinOp::Pow => "^",
    }
}

/// The name a built-in is called by (the first of cpfg's names for the
/// functions that share one meaning: `printf` for the I/O functions,
/// `vvXmin` for the view-volume extents).
pub fn builtin(f: Builtin) -> &'static str {
    match f {
        Builtin::Sin => "sin",
        Builtin::Cos => "cos",
        Builtin::Tan => "tan",
        Builtin::Asin => "asin",
        Builtin::Acos => "acos",
        Builtin::Atan => "atan",
        Builtin::Atan2 => "atan2",
        Builtin::Exp => "exp",
        Builtin::Log => "log",
        Builtin::Sqrt => "sqrt",
        Builtin::Fabs => "fabs",
        Builtin::Floor => "floor",
        Builtin::Ceil => "ceil",
        Builtin::Trunc => "trunc",
        Builtin::Sign => "sign",
        Builtin::Srand => "srand",
        Builtin::Ran => "ran",
        Builtin::Nran => "nran",
        Builtin::Bran => "bran",
        Builtin::Biran => "biran",
        Builtin::Func => "func",
        Builtin::CurveX => "curveX",
        Builtin::CurveY => "curveY",
        Builtin::CurveZ => "curveZ",
        Builtin::CurveGal => "curveGAL",
        Builtin::Io => "printf",
        Builtin::Stop => "stop",
        Builtin::ViewVolume => "vvXmin",
        Builtin::SetDerivationLength => "SetDerivationLength",
        Builtin::GetDerivationLength => "GetDerivationLength",
    }
}

/// `e` as text.
pub fn expr(e: &Expr, names: &Names<'_>) -> String {
    let mut out = String::new();
    write(&mut out, e, 0, names);
    out
}

fn list(out: &mut String, es: &[Expr], names: &Names<'_>) {
    for (i, e) in es.iter().enumerate() {
        if i > 0 {
            out.push_str(", ");
        }
        write(out, e, 0, names);
    }
}

/// Writes `e` where a form binding at least `min` is needed, in
/// parentheses when it binds less. Recursion is as deep as the tree,
/// which [`crate::ir::MAX_NESTING`] bounds.
fn write(out: &mut String, e: &Expr, min: u8, names: &Names<'_>) {
    let (own, _) = binding(e);
    if own < min {
        out.push('(');
        write(out, e, 0, names);
        out.push(')');
        return;
    }
    match e {
        Expr::Num(x) => out.push_str(&num(*x)),
        Expr::Str(s) => {
            out.push('"');
            out.push_str(s);
            out.push('"');
        }
        Expr::Var(v) => out.push_str(&names.var(*v)),
        Expr::Element(a, subs) => {
            out.push_str(&names.array(*a));
            for s in subs {
                out.push('[');
                write(out, s, 0, names);
                out.push(']');
            }
        }
        Expr::Unary(op, x) => {
            out.push(if *op == UnOp::Neg { '-' } else { '!' });
            let start = out.len();
            write(out, x, UNARY, names);
            // `- -x`, not `--x`.
            if out[start..].starts_with('-') {
                out.insert(start, ' ');
            }
        }
        Expr::Binary(op, l, r) => {
            let p = precedence(*op);
            write(out, l, p, names);
            out.push(' ');
            out.push_str(symbol(*op));
            out.push(' ');
            write(out, r, p + 1, names);
        }
        Expr::Cond(c, a, b) => {
            write(out, c, 1, names);
            out.push_str(" ? ");
            write(out, a, 0, names);
            out.push_str(" : ");
            write(out, b, 0, names);
        }
        Expr::Call(f, args) => {
            out.push_str(builtin(*f));
            out.push('(');
            list(out, args, names);
            out.push(')');
        }
    }
}

/// How tightly `e` binds as written, and whether it is an atom.
fn binding(e: &Expr) -> (u8, bool) {
    match e {
        Expr::Cond(..) => (0, false),
        Expr::Binary(op, ..) => (precedence(*op), false),
        Expr::Unary(..) => (UNARY, false),
        // A negative number reads as a negation: it binds as one.
        Expr::Num(x) if x.is_sign_negative() => (UNARY, false),
        _ => (9, true),
    }
}

/// Statements, one per line at `indent` spaces; blocks in braces.
pub fn stmts(out: &mut String, ss: &[Stmt], indent: usize, names: &Names<'_>) {
    for s in ss {
        out.push_str(&" ".repeat(indent));
        stmt(out, s, indent, names);
        out.push('\n');
    }
}

fn block(out: &mut String, ss: &[Stmt], indent: usize, names: &Names<'_>) {
    out.push_str("{\n");
    stmts(out, ss, indent + 2, names);
    out.push_str(&" ".repeat(indent));
    out.push('}');
}

fn stmt(out: &mut String, s: &Stmt, indent: usize, names: &Names<'_>) {
    match s {
        Stmt::Assign(place, e) => {
            match place {
                Place::Var(v) => out.push_str(&names.var(*v)),
                Place::Element(a, subs) => {
                    write(out, &Expr::Element(*a, subs.clone()), 9, names);
                }
            }
            out.push_str(" = ");
            write(out, e, 0, names);
            out.push(';');
        }
        Stmt::Eval(e) => {
            write(out, e, 0, names);
            out.push(';');
        }
        Stmt::If(c, yes, no) => {
            out.push_str(&format!("if ({}) ", expr(c, names)));
            block(out, yes, indent, names);
            if !no.is_empty() {
                out.push_str(" else ");
                block(out, no, indent, names);
            }
        }
        Stmt::While(c, body) => {
            out.push_str(&format!("while ({}) ", expr(c, names)));
            block(out, body, indent, names);
        }
        Stmt::Do(body, c) => {
            out.push_str("do ");
            block(out, body, indent, names);
            out.push_str(&format!(" while ({});", expr(c, names)));
        }
    }
}

/// Statements on one line (`{ t = x + y; }`), for a production.
pub fn inline(ss: &[Stmt], names: &Names<'_>) -> String {
    let mut out = String::new();
    stmts(&mut out, ss, 0, names);
    let joined: Vec<&str> = out.lines().map(str::trim).collect();
    format!("{{ {} }}", joined.join(" "))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn n(x: f64) -> Box<Expr> {
        Box::new(Expr::Num(x))
    }
    fn x() -> Box<Expr> {
        Box::new(Expr::Var(Var::Local(0)))
    }
    fn bin(op: BinOp, l: Box<Expr>, r: Box<Expr>) -> Box<Expr> {
        Box::new(Expr::Binary(op, l, r))
    }

    #[test]
    fn parentheses_only_where_the_tree_needs_them() {
        let locals = ["x".to_string()];
        let names = Names {
            locals: &locals,
            globals: &[],
            arrays: &[],
        };
        let cases: Vec<(Box<Expr>, &str)> = vec![
            (
                bin(BinOp::Add, bin(BinOp::Add, x(), n(1.0)), n(2.0)),
                "x + 1 + 2",
            ),
            (
                bin(BinOp::Add, x(), bin(BinOp::Add, n(1.0), n(2.0))),
                "x + (1 + 2)",
            ),
            (
                bin(BinOp::Mul, bin(BinOp::Add, x(), n(1.0)), n(0.7)),
                "(x + 1) * 0.7",
            ),
            (
                bin(BinOp::Pow, Box::new(Expr::Unary(UnOp::Neg, x())), n(2.0)),
                "-x ^ 2",
            ),
            (
                Box::new(Expr::Unary(UnOp::Neg, bin(BinOp::Pow, x(), n(2.0)))),
                "-(x ^ 2)",
            ),
            (
                Box::new(Expr::Unary(
                    UnOp::Neg,
                    Box::new(Expr::Unary(UnOp::Neg, x())),
                )),
                "- -x",
            ),
        ];
        for (e, text) in cases {
            assert_eq!(expr(&e, &names), text);
        }
    }
}
