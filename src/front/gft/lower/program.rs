//! Productions and their program: patterns with their formals, statements
//! and expressions.

use super::{err, Cx, Locals};
use crate::diagnostics::{codes, Diagnostic};
use crate::front::gft::ast;
use crate::front::gft::ast::{Expr as AExpr, ExprKind, Piece};
use crate::ir::program::{BinOp, Expr, Place, Stmt, UnOp, Var, BUILTINS};
use crate::ir::{Alternative, Formals, Production, Span, SymbolId};

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

    pub(super) fn production(&mut self, p: &ast::Production) -> Option<Production> {
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

    pub(super) fn stmts(&mut self, list: &[ast::Stmt], locals: &mut Locals) -> Vec<Stmt> {
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

    pub(super) fn unknown(&mut self, name: &str, span: &Span) {
        self.diags.push(err(
            codes::GFT_UNKNOWN_NAME,
            span,
            format!("unknown name `{name}`"),
            "not a parameter, local or global",
            "declare a global with `globals NAME` or bind it in the predecessor",
        ));
    }

    pub(super) fn expr(&mut self, e: &AExpr, locals: &mut Locals) -> Expr {
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
