//! The syntax tree of a cpfg L-system file, as written (after the
//! preprocessor). Every node keeps its span in the preprocessed text.

use crate::front::depth::{bounded_operation, Bounded};
use crate::ir::program::{BinOp, UnOp};
use crate::ir::{Span, MAX_NESTING};

#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    Num(f64),
    Str(String),
    Name(String),
    /// `name[i][j]`.
    Index(String, Vec<Expr>),
    Unary(UnOp, Box<Expr>),
    Binary(BinOp, Box<Expr>, Box<Expr>),
    Cond(Box<Expr>, Box<Expr>, Box<Expr>),
    /// `name(args)`: a predefined function.
    Call(String, Span, Vec<Expr>),
    /// `&name` (an `fscanf` target).
    Address(String),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    pub kind: ExprKind,
    pub span: Span,
    /// How deep the tree is: 1 for a value or a name, one more than the
    /// deepest operand for an operation. Past [`MAX_NESTING`] the
    /// expression is *cut* (see [`Expr::operation`]).
    pub depth: usize,
}

impl Expr {
    /// A value, a name, or anything else without operands.
    pub fn leaf(kind: ExprKind, span: Span) -> Self {
        Expr {
            kind,
            span,
            depth: 1,
        }
    }

    /// An operation whose operands are in `kind`, written at `span`; `at`
    /// is the operator. The tree is kept within [`MAX_NESTING`] as it is
    /// built ([`bounded_operation`]): an operation that would go deeper
    /// becomes a *cut*, a leaf at `at`, and an operation on a cut is that
    /// cut.
    pub fn operation(kind: ExprKind, span: Span, at: Span) -> Self {
        bounded_operation(kind, ExprKind::operands, at, |kind, depth| Expr {
            kind,
            span,
            depth,
        })
    }

    /// A cut at `at`: where an expression went past [`MAX_NESTING`]. It
    /// stands for what was left out (as a value it is NaN; the parser
    /// reports it and replaces it before anything evaluates it).
    pub fn cut(at: Span) -> Self {
        Expr {
            kind: ExprKind::Num(f64::NAN),
            span: at,
            depth: MAX_NESTING + 1,
        }
    }

    /// Whether this is where an expression went past [`MAX_NESTING`] (its
    /// span is the operator there).
    pub fn is_cut(&self) -> bool {
        self.depth > MAX_NESTING
    }
}

impl Bounded for Expr {
    fn depth(&self) -> usize {
        self.depth
    }
    fn cut(at: Span) -> Self {
        Expr::cut(at)
    }
    fn written_at(self, span: Span) -> Self {
        Expr { span, ..self }
    }
}

impl ExprKind {
    /// The expressions this one is made of.
    fn operands(&self) -> Vec<&Expr> {
        match self {
            ExprKind::Num(_) | ExprKind::Str(_) | ExprKind::Name(_) | ExprKind::Address(_) => {
                Vec::new()
            }
            ExprKind::Index(_, v) | ExprKind::Call(_, _, v) => v.iter().collect(),
            ExprKind::Unary(_, a) => vec![a],
            ExprKind::Binary(_, a, b) => vec![a, b],
            ExprKind::Cond(c, a, b) => vec![c, a, b],
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum Stmt {
    /// `target = value;` where target is a name or an array element.
    Assign {
        target: Expr,
        value: Expr,
    },
    Eval(Expr),
    If(Expr, Vec<Stmt>, Vec<Stmt>),
    While(Expr, Vec<Stmt>),
    Do(Vec<Stmt>, Expr),
}

/// A module as written: `A`, `A(x, y)`, `@O(2)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Module {
    pub name: String,
    pub span: Span,
    pub args: Vec<Expr>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Production {
    pub left: Vec<Module>,
    pub predecessor: Vec<Module>,
    pub right: Vec<Module>,
    pub before: Vec<Stmt>,
    pub condition: Option<Expr>,
    pub after: Vec<Stmt>,
    /// Empty for `*`.
    pub successor: Vec<Module>,
    pub probability: Option<Expr>,
    /// The whole production.
    pub span: Span,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BlockKind {
    Start,
    StartEach,
    EndEach,
    End,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Section {
    Decomposition,
    Homomorphism,
}

/// `array name[d1, d2] = { values }`.
#[derive(Clone, Debug, PartialEq)]
pub struct ArrayDef {
    pub name: String,
    pub span: Span,
    pub dims: Vec<Expr>,
    pub init: Vec<Expr>,
}

/// One item of the file (a logical line).
#[derive(Clone, Debug, PartialEq)]
pub enum Item {
    Lsystem { label: String, span: Span },
    Seed(Expr, Span),
    DerivationLength(Expr, Span),
    MaximumDepth(Expr, Span),
    Ignore(Vec<(String, Span)>),
    Consider(Vec<(String, Span)>),
    Axiom(Vec<Module>, Span),
    Define(Vec<ArrayDef>),
    Ring(Span),
    Block(BlockKind, Vec<Stmt>, Span),
    Section(Section, Span),
    Production(Box<Production>),
    EndLsystem(Span),
}

#[derive(Clone, Debug, Default, PartialEq)]
pub struct File {
    pub items: Vec<Item>,
}
