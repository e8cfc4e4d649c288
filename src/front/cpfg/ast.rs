//! The syntax tree of a cpfg L-system file, as written (after the
//! preprocessor). Every node keeps its span in the preprocessed text.

use crate::ir::program::{BinOp, UnOp};
use crate::ir::Span;

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
