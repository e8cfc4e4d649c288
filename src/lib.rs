//! graftal: L-system notations read into one IR, evaluated, drawn,
//! explained and translated.
//!
//! The pipeline: [`source`] text -> a front end ([`front`]: one folder per
//! notation, chosen by the registry) -> [`ir::System`] -> [`eval`]
//! (derivation) -> [`turtle`] (geometry) -> [`render`] (PNG, SVG), or ->
//! [`back`] (an emitter of another notation). Every stage reports
//! [`diagnostics`]. [`driver`] strings the stages together for the CLI and
//! for tests.

// Diagnostics are returned by value on cold error paths; boxing them buys nothing.
#![allow(clippy::result_large_err)]

pub mod back;
pub mod cli;
pub mod common;
pub mod decode;
pub mod diagnostics;
pub mod driver;
pub mod enviro;
pub mod eval;
pub mod format;
pub mod front;
pub mod gallery;
pub mod ir;
pub mod layout;
pub mod lsp;
pub mod mesh;
pub mod number;
pub mod parallel;
pub mod random;
pub mod raytrace;
pub mod render;
pub mod scene;
pub mod serve;
pub mod source;
pub mod stdlib;
pub mod turtle;
