//! Lowering a cpfg AST to the IR: symbols and their turtle meaning (the
//! manual's §6 table), variables resolved to local slots, globals and
//! arrays, functions to [`Builtin`]s, and the file's sections in cpfg's
//! order. Settings that live in the view file are applied by the caller
//! ([`super::read`]).

use super::ast::{self, BlockKind, ExprKind, Item, Section};
use crate::common::vocabulary::{self, TurtleSet};
use crate::diagnostics::{codes, nearest, Code, Diagnostic, Diagnostics};
use crate::front::repeats::Repeats;
use crate::front::suggest::Suggester;
use crate::ir::program::{ArrayDecl, Builtin, Expr, Place, Program, Stmt, Var};
use crate::ir::{
    Alternative, ContextFilter, Formals, Phase, Production, RulePolicy, Span, SpanTable,
    SubLsystem, SymbolId, System, TurtleOp, Word,
};
use std::collections::HashMap;

/// The largest derivation length or recursion depth graftal accepts.
pub const MAX_DEPTH: f64 = 1_000_000.0;
/// The most elements an array may have.
pub const MAX_ARRAY: f64 = 1_000_000.0;

pub use crate::ir::Lowered;

/// What a cpfg symbol does ([`crate::common::vocabulary`]'s cpfg set).
pub fn turtle_op(name: &str) -> Option<TurtleOp> {
    vocabulary::op(TurtleSet::Cpfg, name)
}

/// Turtle commands graftal reads but does not draw (W0823).
const NOT_DRAWN: &[&str] = &["@PS", "@PC", "@PD", "@bo", "@bc"];

/// Names bound in a production or block, resolved as they are met.
/// A pattern's symbols and, for each module, the local slots it binds.
type Patterns = (Vec<SymbolId>, Vec<Vec<u16>>);

struct Scope {
    locals: Vec<String>,
    /// Whether names not yet known become locals (in productions) or
    /// globals (in Start/End blocks: every assigned name is global there).
    global_block: bool,
}

struct Lowerer<'d> {
    sys: System,
    spans: SpanTable,
    diags: &'d mut Diagnostics,
    globals: HashMap<String, u16>,
    arrays: HashMap<String, (u16, usize)>,
    /// Names warned about as undefined (once each).
    undefined: std::collections::HashSet<String>,
    warned_not_drawn: std::collections::HashSet<String>,
    /// The input and output functions warned about (W0822), each once.
    warned_io: std::collections::HashSet<String>,
    warned_env: bool,
    /// The sub-L-system calls whose label is a number, with their spans:
    /// each must name an L-system of the file.
    calls: Vec<(f64, Span)>,
    /// The first `$`: without sub-L-systems and calls it returns from
    /// nothing.
    first_return: Option<Span>,
    /// Whether any module is a call `?(…)`.
    called: bool,
    /// The first `@#` and whether any `@Gs` starts a generalized
    /// cylinder: contours are drawn only on those.
    first_contour: Option<Span>,
    cylinder_started: bool,
    /// What the item being lowered reported: a mistake repeated through a
    /// line (`F(foo(1))` a million times) is reported a few times, then
    /// counted.
    repeats: Repeats,
    /// What suggestions for undefined names may still cost.
    suggester: Suggester,
    /// The length of the longest global variable's name.
    longest_global: usize,
    /// The ids of the curves the view file loads (`curveX` reads them).
    curves: Vec<u32>,
}

impl Lowerer<'_> {
    /// Reports what `build` makes, a diagnostic of `code` found in the item
    /// being lowered, unless the item has reported enough of that code
    /// already ([`Repeats`]).
    fn report(&mut self, code: Code, build: impl FnOnce() -> Diagnostic) {
        self.repeats.report(self.diags, code, build);
    }

    fn symbol(&mut self, name: &str, span: &Span) -> crate::ir::SymbolId {
        let id = self.sys.intern(name);
        self.spans.symbols.entry(id).or_insert_with(|| span.clone());
        if self.sys.op(id).is_none() {
            if let Some(op) = turtle_op(name) {
                self.sys.set_interpretation(id, op);
            }
        }
        id
    }

    fn check_module(&mut self, m: &ast::Module) {
        match m.name.as_str() {
            "@#" if self.first_contour.is_none() => self.first_contour = Some(m.span.clone()),
            "@Gs" => self.cylinder_started = true,
            _ => {}
        }
        if m.name == "$" {
            self.first_return.get_or_insert(m.span.clone());
        } else if m.name == "?" {
            self.called |= !m.args.is_empty();
            if let Some(ExprKind::Num(label)) = m.args.first().map(|a| &a.kind) {
                self.calls.push((*label, m.span.clone()));
            }
        } else if m.name == "?E" && !self.warned_env {
            self.warned_env = true;
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_NO_ENVIRONMENT,
                    m.span.clone(),
                    "`?E` modules get no answer: no environment program graftal runs is named",
                )
                .with_label("keeps the parameters the L-system gives it"),
            );
        } else if m.name == "@G" && self.warned_not_drawn.insert(m.name.clone()) {
            // cpfg: "Unknown subfunction following @G", then it reads on.
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_NOT_DRAWN,
                    m.span.clone(),
                    "`@G` is not followed by a generalized-cylinder command",
                )
                .with_label("no effect on the picture")
                .with_help("cpfg knows `@Gs`, `@Gc`, `@Ge`, `@Gt` and `@Gr`"),
            );
        } else if m.name.len() > 1
            && m.name.starts_with('@')
            && turtle_op(&m.name).is_none()
            && !NOT_DRAWN.contains(&m.name.as_str())
            && self.warned_not_drawn.insert(m.name.clone())
        {
            // cpfg's `@` commands graftal does not carry out (the scale
            // `@D`, `@Di`, `@Dd`) or that cpfg does not know at all.
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_NOT_DRAWN,
                    m.span.clone(),
                    format!("`{}` is not a turtle command graftal carries out", m.name),
                )
                .with_label("no effect on the picture"),
            );
        } else if NOT_DRAWN.contains(&m.name.as_str())
            && self.warned_not_drawn.insert(m.name.clone())
        {
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_NOT_DRAWN,
                    m.span.clone(),
                    format!("`{}` is read but not drawn", m.name),
                )
                .with_label("no effect on the picture"),
            );
        }
    }

    /// `e` in the IR, node for node. The recursion is as deep as `e`, which
    /// the parser keeps within [`crate::ir::MAX_NESTING`].
    fn expr(&mut self, scope: &mut Scope, e: &ast::Expr) -> Expr {
        match &e.kind {
            ExprKind::Num(v) => Expr::Num(*v),
            ExprKind::Str(s) => Expr::Str(s.clone()),
            ExprKind::Name(n) | ExprKind::Address(n) => self.name(scope, n, &e.span),
            ExprKind::Index(n, subs) => {
                let subs: Vec<Expr> = subs.iter().map(|s| self.expr(scope, s)).collect();
                self.element(n, subs, &e.span)
            }
            ExprKind::Unary(op, a) => Expr::Unary(*op, Box::new(self.expr(scope, a))),
            ExprKind::Binary(op, a, b) => Expr::Binary(
                *op,
                Box::new(self.expr(scope, a)),
                Box::new(self.expr(scope, b)),
            ),
            ExprKind::Cond(c, a, b) => Expr::Cond(
                Box::new(self.expr(scope, c)),
                Box::new(self.expr(scope, a)),
                Box::new(self.expr(scope, b)),
            ),
            ExprKind::Call(name, name_span, args) => {
                self.call(scope, name, name_span, args, &e.span)
            }
        }
    }

    /// A name read at `span`: a local, a global, or else (warned once as
    /// undefined) a new local, which is 0.
    fn name(&mut self, scope: &mut Scope, n: &str, span: &Span) -> Expr {
        if let Some(i) = scope.locals.iter().position(|l| l == n) {
            return Expr::Var(Var::Local(i as u16));
        }
        if let Some(&g) = self.globals.get(n) {
            return Expr::Var(Var::Global(g));
        }
        if self.arrays.contains_key(n) {
            self.report(codes::CPFG_NOT_ARRAY, || {
                Diagnostic::at(
                    codes::CPFG_NOT_ARRAY,
                    span.clone(),
                    format!("array `{n}` used without subscripts"),
                )
                .with_label("needs `[i]`")
            });
            return Expr::Num(0.0);
        }
        if self.undefined.insert(n.to_string()) {
            self.warn_undefined(scope, n, span);
        }
        scope.locals.push(n.to_string());
        Expr::Var(Var::Local((scope.locals.len() - 1) as u16))
    }

    fn warn_undefined(&mut self, scope: &Scope, n: &str, span: &Span) {
        let d = Diagnostic::at(
            codes::CPFG_UNDEFINED_NAME,
            span.clone(),
            format!("`{n}` is not defined; its value is 0"),
        )
        .with_label("not a parameter, local or global variable");
        let count = scope.locals.len() + self.globals.len();
        let longest = scope.locals.iter().map(String::len).max().unwrap_or(0);
        let longest = longest.max(self.longest_global);
        if !self.suggester.afford(n.len(), count, longest) {
            return self.diags.push(d);
        }
        let mut known: Vec<&str> = scope
            .locals
            .iter()
            .map(String::as_str)
            // A name already found undefined is a local only so that it is
            // reported once: never the name to suggest.
            .filter(|l| !l.is_empty() && !self.undefined.contains(*l))
            .collect();
        known.extend(self.globals.keys().map(String::as_str));
        self.diags.push(with_nearest(d, n, &known));
    }

    /// The element `n[subs]` of an array; 0 if `n` is no array of as many
    /// dimensions.
    fn element(&mut self, n: &str, subs: Vec<Expr>, span: &Span) -> Expr {
        match self.arrays.get(n).copied() {
            Some((id, dims)) if dims == subs.len() => Expr::Element(id, subs),
            Some((_, dims)) => {
                self.report(codes::CPFG_NOT_ARRAY, || {
                    Diagnostic::at(
                        codes::CPFG_NOT_ARRAY,
                        span.clone(),
                        format!("`{n}` has {dims} dimension(s), not {}", subs.len()),
                    )
                    .with_label("subscripts do not match the declaration")
                });
                Expr::Num(0.0)
            }
            None => {
                self.report(codes::CPFG_NOT_ARRAY, || {
                    Diagnostic::at(
                        codes::CPFG_NOT_ARRAY,
                        span.clone(),
                        format!("`{n}` is not an array"),
                    )
                    .with_label("subscripted here")
                    .with_help(format!("declare it: `define: {{ array {n}[size]; }}`"))
                });
                Expr::Num(0.0)
            }
        }
    }

    /// A call of a predefined function ([`crate::ir::program::BUILTINS`]) at `span`; 0 if
    /// there is no such function.
    fn call(
        &mut self,
        scope: &mut Scope,
        name: &str,
        name_span: &Span,
        args: &[ast::Expr],
        span: &Span,
    ) -> Expr {
        let Some(&(_, builtin, arities)) =
            crate::ir::program::BUILTINS.iter().find(|f| f.0 == name)
        else {
            self.report(codes::CPFG_UNKNOWN_FUNCTION, || {
                let names: Vec<&str> = crate::ir::program::BUILTINS.iter().map(|f| f.0).collect();
                let d = Diagnostic::at(
                    codes::CPFG_UNKNOWN_FUNCTION,
                    name_span.clone(),
                    format!("unknown function `{name}`"),
                )
                .with_label("not a cpfg function");
                with_nearest(d, name, &names)
            });
            return Expr::Num(0.0);
        };
        if !arities.is_empty() && !arities.contains(&args.len()) {
            self.report(codes::CPFG_ARITY, || {
                let want: Vec<String> = arities.iter().map(|a| a.to_string()).collect();
                Diagnostic::at(
                    codes::CPFG_ARITY,
                    span.clone(),
                    format!(
                        "`{name}` takes {} argument(s), not {}",
                        want.join(" or "),
                        args.len()
                    ),
                )
                .with_label("called here")
            });
        }
        self.warn_not_run(name, name_span, builtin);
        let args: Vec<Expr> = args.iter().map(|a| self.expr(scope, a)).collect();
        if matches!(
            builtin,
            Builtin::CurveX | Builtin::CurveY | Builtin::CurveZ | Builtin::CurveGal
        ) {
            self.check_curve(name, name_span, args.first());
        }
        // `atan(y, x)` with two arguments is atan2.
        let builtin = if builtin == Builtin::Atan && arities.len() > 1 && args.len() == 2 {
            Builtin::Atan2
        } else {
            builtin
        };
        Expr::Call(builtin, args)
    }

    /// A curve function whose curve the view file does not load: an
    /// error at its name (the id is checked when it is a constant).
    fn check_curve(&mut self, name: &str, name_span: &Span, id: Option<&Expr>) {
        let id = id.and_then(Expr::constant);
        let problem = match id {
            _ if self.curves.is_empty() => "the view file loads no curve".to_string(),
            Some(id) if !self.curves.iter().any(|&c| f64::from(c) == id) => {
                format!("the view file loads no curve {id}")
            }
            _ => return,
        };
        let count = self.curves.len();
        self.report(codes::CPFG_NO_CURVE, || {
            Diagnostic::at(
                codes::CPFG_NO_CURVE,
                name_span.clone(),
                format!("`{name}` reads a curve, and {problem}"),
            )
            .with_label("a curve function")
            .with_help(if count == 0 {
                "name the curve's file on a `curve:` line of the view file (`curve: profile.con`)"
                    .to_string()
            } else {
                format!("the view file's `curve:` lines load curves 1 to {count}")
            })
        });
    }

    /// Warns, once for each of them, about the input and output functions,
    /// which graftal reads but does not run.
    fn warn_not_run(&mut self, name: &str, name_span: &Span, builtin: Builtin) {
        if builtin == Builtin::Io && self.warned_io.insert(name.to_string()) {
            let (message, label) = match name {
                "fscanf" => (
                    "`fscanf` reads nothing in graftal".to_string(),
                    "the variables it is given keep their values; it returns 0",
                ),
                "fopen" => (
                    "`fopen` opens no file in graftal".to_string(),
                    "returns 0; reads and writes through it do nothing",
                ),
                _ => (
                    format!("`{name}` does nothing in graftal"),
                    "no file or console output",
                ),
            };
            self.diags.push(
                Diagnostic::at(codes::CPFG_IO_IGNORED, name_span.clone(), message)
                    .with_label(label),
            );
        }
    }

    fn place(&mut self, scope: &mut Scope, target: &ast::Expr) -> Option<Place> {
        match &target.kind {
            ExprKind::Name(n) => {
                if let Some(i) = scope.locals.iter().position(|l| l == n) {
                    return Some(Place::Var(Var::Local(i as u16)));
                }
                if let Some(&g) = self.globals.get(n) {
                    return Some(Place::Var(Var::Global(g)));
                }
                if scope.global_block {
                    // Not reached: globals are collected before lowering.
                    return None;
                }
                scope.locals.push(n.clone());
                Some(Place::Var(Var::Local((scope.locals.len() - 1) as u16)))
            }
            ExprKind::Index(..) => match self.expr(scope, target) {
                Expr::Element(a, subs) => Some(Place::Element(a, subs)),
                _ => None,
            },
            _ => {
                self.report(codes::SYNTAX, || {
                    Diagnostic::at(
                        codes::SYNTAX,
                        target.span.clone(),
                        "only a variable or an array element can be assigned",
                    )
                    .with_label("not assignable")
                });
                None
            }
        }
    }

    /// The statements in the IR (blocks nest as deep as their braces, which
    /// the parser keeps within [`crate::ir::MAX_NESTING`]).
    fn stmts(&mut self, scope: &mut Scope, stmts: &[ast::Stmt]) -> Vec<Stmt> {
        let mut out = Vec::new();
        for s in stmts {
            match s {
                ast::Stmt::Assign { target, value } => {
                    let v = self.expr(scope, value);
                    if let Some(p) = self.place(scope, target) {
                        out.push(Stmt::Assign(p, v));
                    }
                }
                ast::Stmt::Eval(e) => {
                    let e = self.expr(scope, e);
                    out.push(Stmt::Eval(e));
                }
                ast::Stmt::If(c, t, e) => {
                    let c = self.expr(scope, c);
                    let t = self.stmts(scope, t);
                    let e = self.stmts(scope, e);
                    out.push(Stmt::If(c, t, e));
                }
                ast::Stmt::While(c, b) => {
                    let c = self.expr(scope, c);
                    let b = self.stmts(scope, b);
                    out.push(Stmt::While(c, b));
                }
                ast::Stmt::Do(b, c) => {
                    let b = self.stmts(scope, b);
                    let c = self.expr(scope, c);
                    out.push(Stmt::Do(b, c));
                }
            }
        }
        out
    }

    /// The symbols of a pattern and the local slots each module binds.
    fn patterns(&mut self, scope: &mut Scope, mods: &[ast::Module]) -> Patterns {
        let mut out = (Vec::new(), Vec::new());
        for m in mods {
            self.check_module(m);
            let symbol = self.symbol(&m.name, &m.span);
            let mut params = Vec::new();
            for a in &m.args {
                match &a.kind {
                    ExprKind::Name(n) => {
                        scope.locals.push(n.clone());
                        params.push((scope.locals.len() - 1) as u16);
                    }
                    _ => {
                        self.report(codes::CPFG_NOT_FORMAL, || {
                            Diagnostic::at(
                                codes::CPFG_NOT_FORMAL,
                                a.span.clone(),
                                "a predecessor parameter must be a name",
                            )
                            .with_label("an expression cannot be matched")
                            .with_help("name the parameter and test it in the condition")
                        });
                        scope.locals.push(String::new());
                        params.push((scope.locals.len() - 1) as u16);
                    }
                }
            }
            out.0.push(symbol);
            out.1.push(params);
        }
        out
    }

    /// A right context. cpfg's `=` skips the rest of the current branch up
    /// to its closing `]` (cpfg's `RconDiff`); the IR's `]` in a right
    /// context already means "the rest of the branch, then its end", so
    /// `=]` lowers to `]`. An `=` before anything else can never match
    /// in cpfg (W0826); it stays a module `=`, which no word holds.
    fn right_context(&mut self, scope: &mut Scope, mods: &[ast::Module]) -> Patterns {
        let is_rest = |m: &ast::Module| m.name == "=" && m.args.is_empty();
        let mut kept: Vec<ast::Module> = Vec::with_capacity(mods.len());
        for (k, m) in mods.iter().enumerate() {
            if is_rest(m) && mods.get(k + 1).is_some_and(|n| n.name == "]") {
                continue;
            }
            if is_rest(m) {
                self.report(codes::CPFG_REST_OF_BRANCH, || {
                    Diagnostic::at(
                        codes::CPFG_REST_OF_BRANCH,
                        m.span.clone(),
                        "`=` skips the rest of the branch, but no `]` follows it",
                    )
                    .with_label("this context never matches")
                    .with_help("write `=]` to match the rest of a branch")
                });
            }
            kept.push(m.clone());
        }
        self.patterns(scope, &kept)
    }

    /// A successor (or the axiom): its symbols and each module's
    /// parameter expressions.
    fn calls(&mut self, scope: &mut Scope, mods: &[ast::Module]) -> (Word, Vec<Vec<Expr>>) {
        let mut symbols = Vec::with_capacity(mods.len());
        let mut args = Vec::with_capacity(mods.len());
        for m in mods {
            self.check_module(m);
            symbols.push(self.symbol(&m.name, &m.span));
            args.push(m.args.iter().map(|a| self.expr(scope, a)).collect());
        }
        (Word::from(symbols), args)
    }

    /// A production. Its patterns always carry their parameter lists (a
    /// cpfg module matches only a module with as many parameters), so even
    /// a production without parameters is one of modules.
    fn production(&mut self, p: &ast::Production) -> Production {
        let mut scope = Scope {
            locals: Vec::new(),
            global_block: false,
        };
        let left = self.patterns(&mut scope, &p.left);
        let predecessor = self.patterns(&mut scope, &p.predecessor);
        let right = self.right_context(&mut scope, &p.right);
        let before = self.stmts(&mut scope, &p.before);
        let condition = p.condition.as_ref().map(|c| self.expr(&mut scope, c));
        let after = self.stmts(&mut scope, &p.after);
        let (successor, args) = self.calls(&mut scope, &p.successor);
        let computed_weight = p.probability.as_ref().map(|e| self.expr(&mut scope, e));
        // A constant probability is the weight (one form in the IR, as the
        // gft reader keeps it).
        let (weight, computed_weight) = match computed_weight {
            Some(Expr::Num(v)) => (v, None),
            c => (1.0, c),
        };
        Production {
            left: left.0,
            predecessor: predecessor.0,
            right: right.0,
            formals: Formals {
                left: left.1,
                predecessor: predecessor.1,
                right: right.1,
                locals: scope.locals.len().min(u16::MAX as usize) as u16,
                names: scope.locals.clone(),
            },
            before,
            condition,
            after,
            alternatives: vec![Alternative {
                weight,
                computed_weight,
                successor,
                args,
            }],
        }
    }

    /// A constant expression (macros expanded): derivation length, depth,
    /// array sizes, seeds.
    fn constant(&mut self, e: &ast::Expr, what: &str, max: f64) -> Option<f64> {
        self.constant_in(e, what, 0.0, max)
    }

    /// A constant in `min..=max`.
    fn constant_in(&mut self, e: &ast::Expr, what: &str, min: f64, max: f64) -> Option<f64> {
        let mut scope = Scope {
            locals: Vec::new(),
            global_block: false,
        };
        let saved = std::mem::take(&mut self.globals);
        let x = self.expr(&mut scope, e);
        self.globals = saved;
        let v = x.constant();
        match v {
            Some(v) if (min..=max).contains(&v) => Some(v),
            _ => {
                let range = if min == 0.0 {
                    format!("from 0 to {max}")
                } else {
                    "that is finite".to_string()
                };
                self.diags.push(
                    Diagnostic::at(
                        codes::CPFG_BAD_VALUE,
                        e.span.clone(),
                        format!("{what} must be a number {range}"),
                    )
                    .with_label(match v {
                        Some(v) => format!("this is {v}"),
                        None => "not a constant".to_string(),
                    }),
                );
                None
            }
        }
    }
}

/// The warning for the first `$` of a file that has no sub-L-system: it
/// returns from nothing (cpfg ignores it). Such a `$` is more often pfg's
/// and LinF's roll to horizontal, which cpfg writes `@v`: the fix writes it.
fn stray_return(span: Span) -> Diagnostic {
    Diagnostic::at(
        codes::CPFG_STRAY_RETURN,
        span.clone(),
        "`$` returns from no sub-L-system",
    )
    .with_label("`$` ends a sub-L-system call `?(n, s)` in cpfg")
    .with_note("the file has one L-system: cpfg ignores this `$`")
    .with_fix(
        span,
        "@v".into(),
        "for the roll to horizontal (`$` in pfg and LinF), cpfg writes `@v`".into(),
    )
}

/// `d` with a help naming the nearest of `candidates` to `name`, when one
/// is near.
fn with_nearest(d: Diagnostic, name: &str, candidates: &[&str]) -> Diagnostic {
    match nearest(name, candidates).first() {
        Some(near) => d.suggesting(near),
        None => d,
    }
}

/// Names assigned in `stmts` (recursively).
fn assigned(stmts: &[ast::Stmt], out: &mut Vec<String>) {
    for s in stmts {
        match s {
            ast::Stmt::Assign { target, .. } => {
                if let ExprKind::Name(n) = &target.kind {
                    if !out.contains(n) {
                        out.push(n.clone());
                    }
                }
            }
            ast::Stmt::If(_, t, e) => {
                assigned(t, out);
                assigned(e, out);
            }
            ast::Stmt::While(_, b) | ast::Stmt::Do(b, _) => assigned(b, out),
            ast::Stmt::Eval(_) => {}
        }
    }
}

/// What the items of an L-system say, gathered in file order before it
/// goes into the system.
#[derive(Default)]
struct Gathered {
    program: Program,
    axiom: (Word, Vec<Vec<Expr>>),
    productions: Vec<Production>,
    decomposition: Phase,
    homomorphism: Phase,
    ring: bool,
    /// `seed:`: the system chooses among productions by weight, with this
    /// added to the run's seed.
    seed: Option<u64>,
    /// `ignore:` or `consider:`, for a sub-L-system (the main one's goes
    /// straight into the system).
    context: Option<ContextFilter>,
}

impl Gathered {
    fn into_system(self, sys: &mut System) {
        // The axiom's expressions, none when no module has any (as the IR
        // says: one system, one form).
        let (axiom, args) = self.axiom;
        sys.axiom = axiom;
        sys.axiom_args = if args.iter().all(Vec::is_empty) {
            Vec::new()
        } else {
            args
        };
        sys.productions = self.productions;
        sys.decomposition = self.decomposition;
        sys.homomorphism = self.homomorphism;
        tidy(
            &mut sys.productions,
            [&mut sys.decomposition, &mut sys.homomorphism],
        );
        sys.program = self.program;
        sys.ring = self.ring;
        sys.settings.seed = self.seed;
        if self.seed.is_some() {
            sys.policy = RulePolicy::Weighted;
        }
        sys.cut = sys.symbols.get("%");
    }
}

/// Tidies every production of an L-system and of its phases.
fn tidy(productions: &mut [Production], phases: [&mut Phase; 2]) {
    let all = (productions.iter_mut()).chain(phases.into_iter().flat_map(|p| &mut p.productions));
    for p in all {
        p.tidy();
    }
}

#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Stage {
    Before,
    Header,
    Productions,
    Decomposition,
    Homomorphism,
    Done,
}

/// Where the items are read: the stage reached, what the header gave, and
/// what is gathered so far.
struct Reading {
    stage: Stage,
    lsystem_span: Option<Span>,
    axiom_seen: bool,
    par: Gathered,
    /// Whether this is a sub-L-system (not the file's first).
    sub: bool,
    /// The number `lsystem:` gives it (1 when it gives none).
    label: u32,
}

/// The stages an item may stand in, and where it stands.
fn placement(item: &Item) -> (&'static [Stage], Span) {
    const BODY: &[Stage] = &[
        Stage::Productions,
        Stage::Decomposition,
        Stage::Homomorphism,
    ];
    match item {
        Item::Lsystem { span, .. } => (&[Stage::Before], span.clone()),
        Item::Seed(_, s) => (&[Stage::Header, Stage::Homomorphism], s.clone()),
        Item::DerivationLength(_, s) | Item::Ring(s) | Item::Axiom(_, s) | Item::Block(_, _, s) => {
            (&[Stage::Header], s.clone())
        }
        Item::Ignore(v) | Item::Consider(v) => {
            (&[Stage::Header], v.first().map_or(0..0, |(_, s)| s.clone()))
        }
        Item::Define(d) => (&[Stage::Header], d.first().map_or(0..0, |d| d.span.clone())),
        Item::MaximumDepth(_, s) => (&[Stage::Decomposition, Stage::Homomorphism], s.clone()),
        Item::Section(Section::Decomposition, s) => (&[Stage::Productions], s.clone()),
        Item::Section(Section::Homomorphism, s) => {
            (&[Stage::Productions, Stage::Decomposition], s.clone())
        }
        Item::Production(p) => (BODY, p.span.clone()),
        Item::EndLsystem(s) => (BODY, s.clone()),
    }
}

impl<'d> Lowerer<'d> {
    fn new(diags: &'d mut Diagnostics) -> Self {
        let mut sys = System::new();
        sys.settings.delta = 45f64.to_radians();
        Lowerer {
            sys,
            spans: SpanTable::default(),
            diags,
            globals: HashMap::new(),
            arrays: HashMap::new(),
            undefined: Default::default(),
            warned_not_drawn: Default::default(),
            warned_io: Default::default(),
            warned_env: false,
            calls: Vec::new(),
            first_return: None,
            called: false,
            first_contour: None,
            cylinder_started: false,
            repeats: Repeats::default(),
            suggester: Suggester::default(),
            longest_global: 0,
            curves: Vec::new(),
        }
    }
}

impl Lowerer<'_> {
    /// The items of each L-system of the file, the first (the main one)
    /// from the file's start: what stands before its `lsystem:` is
    /// reported there.
    fn lsystems(file: &ast::File) -> Vec<&[Item]> {
        let mut out = Vec::new();
        let mut start = 0;
        while start < file.items.len() {
            let end = file.items[start..]
                .iter()
                .position(|i| matches!(i, Item::EndLsystem(_)))
                .map_or(file.items.len(), |p| start + p + 1);
            out.push(&file.items[start..end]);
            start = match file.items[end..]
                .iter()
                .position(|i| matches!(i, Item::Lsystem { .. }))
            {
                Some(p) => end + p,
                None => break,
            };
        }
        if out.is_empty() {
            out.push(&file.items[..]);
        }
        out
    }

    /// cpfg also sweeps a contour along plain `F` cylinders; graftal only
    /// along generalized cylinders (`@Gs` … `@Ge`), so a file that sets
    /// contours and starts none draws round lines where cpfg does not.
    fn report_contours_without_cylinders(&mut self) {
        if let (Some(span), false) = (self.first_contour.take(), self.cylinder_started) {
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_NOT_DRAWN,
                    span,
                    "contours are drawn only along generalized cylinders (`@Gs` … `@Ge`)",
                )
                .with_label("`F` keeps a round section here")
                .with_help("start the cylinder with `@Gs` and end it with `@Ge`"),
            );
        }
    }

    /// Reports each call naming no L-system of the file, and a `$` in a
    /// file without sub-L-systems or calls (it returns from nothing).
    fn report_calls(&mut self) {
        let labels: Vec<u32> = std::iter::once(self.sys.label)
            .chain(self.sys.sub_lsystems.iter().map(|s| s.label))
            .collect();
        let named = |v: f64| labels.iter().any(|&l| f64::from(l) == v.trunc());
        for (label, span) in std::mem::take(&mut self.calls) {
            if !named(label) {
                let list: Vec<String> = labels.iter().map(u32::to_string).collect();
                self.report(codes::CPFG_SUB_LSYSTEM, || {
                    Diagnostic::at(
                        codes::CPFG_SUB_LSYSTEM,
                        span,
                        format!("no L-system of this file is labelled {label}"),
                    )
                    .with_label("calls a sub-L-system")
                    .with_help(format!("the file's L-systems: {}", list.join(", ")))
                });
            }
        }
        match self.first_return.take() {
            Some(span) if self.sys.sub_lsystems.is_empty() && !self.called => {
                self.diags.push(stray_return(span))
            }
            _ => {}
        }
    }

    /// Declares the arrays and the globals (every name assigned in a
    /// Start/End block that is not an array) before anything is lowered,
    /// so that every use resolves to them.
    fn declare_globals(&mut self, items: &[Item], program: &mut Program) {
        let mut global_names = Vec::new();
        for item in items {
            match item {
                Item::Block(_, stmts, _) => assigned(stmts, &mut global_names),
                Item::Define(defs) => {
                    for d in defs {
                        self.declare_array(d, program);
                    }
                }
                _ => {}
            }
        }
        for n in global_names {
            if !self.arrays.contains_key(&n) {
                self.longest_global = self.longest_global.max(n.len());
                self.globals.insert(n.clone(), program.globals.len() as u16);
                program.globals.push(n);
            }
        }
    }

    /// An array of `define:`, with constant sizes and initial values.
    fn declare_array(&mut self, d: &ast::ArrayDef, program: &mut Program) {
        let dims: Vec<usize> = d
            .dims
            .iter()
            .map(|e| self.constant(e, "an array size", MAX_ARRAY).unwrap_or(0.0) as usize)
            .collect();
        let total: f64 = dims.iter().map(|&d| d as f64).product();
        if total > MAX_ARRAY {
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_BAD_VALUE,
                    d.span.clone(),
                    format!(
                        "array `{}` has {total} elements, more than {MAX_ARRAY}",
                        d.name
                    ),
                )
                .with_label("too large"),
            );
            return;
        }
        let init: Vec<f64> = d
            .init
            .iter()
            .map(|e| {
                self.constant_in(e, "an array value", f64::MIN, f64::MAX)
                    .unwrap_or(0.0)
            })
            .collect();
        self.arrays
            .insert(d.name.clone(), (program.arrays.len() as u16, dims.len()));
        program.arrays.push(ArrayDecl {
            name: d.name.clone(),
            dims,
            init,
        });
    }

    /// Whether `item` is read: an item out of cpfg's order is reported
    /// where it stands and read all the same, except before `lsystem:`,
    /// where it is skipped (the missing `lsystem:` is reported once, at
    /// the end).
    fn in_order(&mut self, item: &Item, stage: Stage) -> bool {
        let (need, span) = placement(item);
        if need.contains(&stage) {
            return true;
        }
        if stage == Stage::Before {
            return false;
        }
        self.diags.push(
            Diagnostic::at(
                codes::CPFG_MISPLACED,
                span,
                "this item is out of place",
            )
            .with_label(match stage {
                Stage::Header => "expected after `axiom:` only productions",
                Stage::Productions => "the header ended at `axiom:`",
                Stage::Decomposition | Stage::Homomorphism => {
                    "inside the decomposition or homomorphism"
                }
                _ => "after `endlsystem`",
            })
            .with_help("cpfg order: lsystem:, declarations, axiom:, productions, decomposition, homomorphism, endlsystem"),
        );
        true
    }

    /// Reads one item in its stage.
    fn item(&mut self, item: &Item, rd: &mut Reading) {
        match item {
            Item::Lsystem { span, label } => {
                rd.lsystem_span = Some(span.clone());
                rd.label = label.trim().parse().unwrap_or(1);
                rd.stage = Stage::Header;
            }
            Item::Seed(e, _) => {
                let v = self
                    .constant(e, "a seed", u32::MAX as f64)
                    .map(|v| v as u64);
                if rd.stage == Stage::Homomorphism {
                    rd.par.homomorphism.seed = v;
                } else {
                    rd.par.seed = v.or(Some(0));
                }
            }
            Item::DerivationLength(e, _) => {
                let steps = self
                    .constant(e, "the derivation length", MAX_DEPTH)
                    .map(|v| v as u64);
                if !rd.sub {
                    self.sys.settings.steps = steps;
                }
            }
            Item::MaximumDepth(e, _) => {
                let d = self
                    .constant(e, "the maximum depth", MAX_DEPTH)
                    .map_or(1, |v| v as u32);
                if rd.stage == Stage::Decomposition {
                    rd.par.decomposition.depth = d;
                } else {
                    rd.par.homomorphism.depth = d;
                }
            }
            Item::Ignore(v) | Item::Consider(v) => {
                let symbols = self.context_symbols(v);
                let filter = if matches!(item, Item::Ignore(_)) {
                    ContextFilter::Ignore(symbols)
                } else {
                    ContextFilter::Consider(symbols)
                };
                if rd.sub {
                    rd.par.context = Some(filter);
                } else {
                    self.sys.context = filter;
                }
            }
            Item::Axiom(mods, _) => {
                let mut scope = Scope {
                    locals: Vec::new(),
                    global_block: false,
                };
                let axiom = self.calls(&mut scope, mods);
                if !rd.sub {
                    rd.par.axiom = axiom;
                    self.spans.axiom = mods.iter().map(|m| m.span.clone()).collect();
                }
                rd.axiom_seen = true;
                rd.stage = Stage::Productions;
            }
            Item::Define(_) => {}
            Item::Ring(_) => rd.par.ring = true,
            Item::Block(kind, stmts, _) => self.block(*kind, stmts, &mut rd.par.program),
            Item::Section(Section::Decomposition, _) => {
                rd.stage = Stage::Decomposition;
                rd.par.decomposition.depth = 1;
            }
            Item::Section(Section::Homomorphism, _) => {
                rd.stage = Stage::Homomorphism;
                rd.par.homomorphism.depth = 1;
            }
            Item::Production(p) => self.production_item(p, rd),
            Item::EndLsystem(_) => rd.stage = Stage::Done,
        }
    }

    /// The symbols of `ignore:` or `consider:`.
    fn context_symbols(&mut self, names: &[(String, Span)]) -> Vec<SymbolId> {
        names.iter().map(|(n, s)| self.symbol(n, s)).collect()
    }

    /// A Start, StartEach, EndEach or End block: every name it assigns is
    /// global.
    fn block(&mut self, kind: BlockKind, stmts: &[ast::Stmt], program: &mut Program) {
        let mut scope = Scope {
            locals: Vec::new(),
            global_block: true,
        };
        let s = self.stmts(&mut scope, stmts);
        match kind {
            BlockKind::Start => program.start = s,
            BlockKind::StartEach => program.start_each = s,
            BlockKind::EndEach => program.end_each = s,
            BlockKind::End => program.end = s,
        }
    }

    /// A production, into the productions, decomposition or homomorphism
    /// it stands in.
    fn production_item(&mut self, p: &ast::Production, rd: &mut Reading) {
        let prod = self.production(p);
        if p.probability.is_some() && rd.par.seed.is_none() && rd.stage == Stage::Productions {
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_PROBABILITY_IGNORED,
                    p.probability
                        .as_ref()
                        .map_or(p.span.clone(), |e| e.span.clone()),
                    "a probability in a deterministic L-system",
                )
                .with_label("ignored: there is no `seed:`")
                .with_help("add `seed: 1` after `lsystem:` to make the L-system stochastic"),
            );
        }
        self.spans.productions.push(p.span.clone());
        match rd.stage {
            Stage::Decomposition => rd.par.decomposition.productions.push(prod),
            Stage::Homomorphism => rd.par.homomorphism.productions.push(prod),
            _ => rd.par.productions.push(prod),
        }
    }

    /// Reports a file without `lsystem:`, or an L-system without an axiom.
    fn check_complete(&mut self, rd: &Reading) {
        if rd.lsystem_span.is_none() {
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_NO_LSYSTEM,
                    0..0,
                    "the file has no `lsystem:` line",
                )
                .with_label("expected `lsystem: 1` before the axiom")
                .with_help("a cpfg L-system starts with `lsystem: 1` and ends with `endlsystem`"),
            );
        } else if !rd.axiom_seen {
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_NO_AXIOM,
                    rd.lsystem_span.clone().unwrap_or(0..0),
                    "this L-system has no axiom",
                )
                .with_label("no `axiom:` follows")
                .with_help("add `axiom: A` before the productions"),
            );
        }
    }
}

impl Lowerer<'_> {
    /// Reads the items of one L-system into `par`; a sub-L-system's
    /// (`sub`) axiom and derivation length are checked and not used, as
    /// cpfg uses them only when the L-system runs alone.
    fn read_lsystem(&mut self, items: &[Item], par: Gathered, sub: bool) -> Reading {
        let mut rd = Reading {
            stage: Stage::Before,
            lsystem_span: None,
            axiom_seen: false,
            par,
            sub,
            label: 1,
        };
        for item in items {
            if self.in_order(item, rd.stage) {
                self.item(item, &mut rd);
                self.repeats.end_item(self.diags, "on this line");
            }
        }
        self.check_complete(&rd);
        rd
    }

    /// A sub-L-system read into `rd`: its productions and phases as a
    /// [`SubLsystem`], its blocks run after the main L-system's (cpfg runs
    /// every L-system's).
    fn add_sub_lsystem(&mut self, rd: Reading) {
        let par = rd.par;
        let program = &mut self.sys.program;
        program.start.extend(par.program.start);
        program.start_each.extend(par.program.start_each);
        program.end_each.extend(par.program.end_each);
        program.end.extend(par.program.end);
        let mut sub = SubLsystem {
            label: rd.label,
            productions: par.productions,
            decomposition: par.decomposition,
            homomorphism: par.homomorphism,
            context: par.context.unwrap_or_default(),
        };
        tidy(
            &mut sub.productions,
            [&mut sub.decomposition, &mut sub.homomorphism],
        );
        self.sys.sub_lsystems.push(sub);
    }
}

/// Lowers `file` to a parametric [`System`].
pub fn lower(file: &ast::File, diags: &mut Diagnostics) -> Lowered {
    lower_with_curves(file, &[], diags)
}

/// [`lower`], with the ids of the curves the view file loads (what
/// `curveX(id, t)` may read).
pub fn lower_with_curves(file: &ast::File, curves: &[u32], diags: &mut Diagnostics) -> Lowered {
    let mut l = Lowerer::new(diags);
    l.curves = curves.to_vec();
    let lsystems = Lowerer::lsystems(file);
    let mut main = Gathered::default();
    // Every L-system's arrays and globals are the file's.
    l.declare_globals(&file.items, &mut main.program);
    let rd = l.read_lsystem(lsystems[0], main, false);
    rd.par.into_system(&mut l.sys);
    l.sys.label = rd.label;
    for items in &lsystems[1..] {
        let rd = l.read_lsystem(items, Gathered::default(), true);
        l.add_sub_lsystem(rd);
    }
    l.report_calls();
    l.report_contours_without_cylinders();
    Lowered {
        system: l.sys,
        spans: l.spans,
    }
}
