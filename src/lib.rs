//! graftal: L-system notations read into one IR, evaluated, drawn,
//! explained and translated.
//!
//! The pipeline: [`source`] text -> a front end ([`pfg`]) -> [`ir::System`]
//! -> [`eval`] (derivation) -> [`turtle`] (geometry) -> [`render`] (PNG,
//! SVG). Every stage reports [`diagnostics`]. [`driver`] strings the stages
//! together for the CLI and for tests.

// Diagnostics are returned by value on cold error paths; boxing them buys nothing.
#![allow(clippy::result_large_err)]

pub mod cli;
pub mod cpfg;
pub mod diagnostics;
pub mod driver;
pub mod emit;
pub mod eval;
pub mod ir;
pub mod linf;
pub mod pfg;
pub mod render;
pub mod source;
pub mod stdlib;
pub mod stl;
pub mod turtle;
